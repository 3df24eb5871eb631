// End-to-end scenario tests: programs compile, sample, and every relation they state holds on
// the sampled values, checked here with plain arithmetic independent of the sampler's regions.
#include <gtest/gtest.h>

#include <set>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

TEST(ScenarioTest, RotatedTrayCompletelyOnTableNeverOverhangs) {
  auto program = CompileOrDie(R"(from model import *
table = Table on floor
tray = Tray completely on table, facing V3D(1, 1, 0)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 1000; ++i) {
    const Scene scene = SampleScene(*program, 7, i).scene;
    const SceneObject& tray = Find(scene, "tray");
    const SceneObject& table = Find(scene, "table");
    EXPECT_TRUE((tray.R_WO * Vector3d::UnitY()).isApprox(Vector3d(1, 1, 0).normalized(), 1e-9));
    ExpectCompletelyOn(tray, table);
  }
}

TEST(ScenarioTest, SameSeedAndIndexGiveTheSameScene) {
  auto program = CompileOrDie("from model import *\n"
                              "t = Table on floor\nc = Cube completely on t\n"
                              "x = Normal(0, 1)\nparam p = x\n");
  ASSERT_NE(program, nullptr);
  const Scene a = SampleScene(*program, 5, 17).scene;
  const Scene b = SampleScene(*program, 5, 17).scene;
  const Scene c = SampleScene(*program, 5, 18).scene;
  EXPECT_EQ(Find(a, "c").p_WO, Find(b, "c").p_WO);
  EXPECT_NE(Find(a, "c").p_WO, Find(c, "c").p_WO);
  EXPECT_EQ(a.params[0].second.As<double>(), b.params[0].second.As<double>());
}

TEST(ScenarioTest, ParamOverrideForAnUndeclaredNameIsAnError) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.param_overrides = {{"clutter", "3"}, {"lable", "x"}};
  lang::CompileText(RepoPath("examples/test.prs"), "param clutter = 2, label = \"a\"\n", options,
                    diagnostics);
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].id, "unknown-param");
  EXPECT_EQ(diagnostics.diagnostics()[0].message,
            "-p lable=x: the program declares no param 'lable'; did you mean 'label'?");
}


// Imported modules that draw nothing are run once per sampler and their globals shared
// (RunCache::module_globals); what a scene can change or draw must still differ per scene.
TEST(ScenarioTest, SharedModuleGlobalsStillVaryPerScene) {
  auto program = CompileOrDie("from shared_values import *\n"
                              "from random_module import *\n"
                              "from reexport import *\n"
                              "param drawn = size + 0\n"
                              "param moved = offset\n"
                              "b = Box at Vector3D(offset, 0, 0.5)\n",
                              "tests/lang/modules/main.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  std::set<double> sizes, offsets;
  for (uint64_t i = 0; i < 20; ++i) {
    const SampledScene s = sampler.Sample(4, i);
    ASSERT_EQ(s.scene.params.size(), 2u);
    sizes.insert(s.scene.params[0].second.As<double>());    // a tuple from the module
    offsets.insert(s.scene.params[1].second.As<double>());  // a draw in the module
    EXPECT_EQ(Find(s.scene, "b").dimensions.x(), 0.1);
    // Cached or not, the scene is the same as a fresh sampler's.
    EXPECT_EQ(Find(s.scene, "b").p_WO, Find(SampleScene(*program, 4, i).scene, "b").p_WO);
  }
  EXPECT_EQ(sizes.size(), 20u);
  EXPECT_EQ(offsets.size(), 20u);
}


// Fixed objects are built once per sampler and copied (RunCache::fixed_objects): the scenes
// and their rejections must be those of fresh samplers, also when a random object placed
// before a fixed one collides with it, and when a fixed object's specifier creates another.
TEST(ScenarioTest, CachedFixedObjectsGiveTheScenesOfAFreshSampler) {
  auto program = CompileOrDie("from model import *\n"
                              "c = Cube at Vector3D(Range(-1.4, 1.4), 0, 0.5)\n"
                              "t = Table on Vector3D(0, 0, 0)\n"
                              "g = Gear on (Plate on Vector3D(1, 1, 0))\n");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int64_t rejections = 0;
  for (uint64_t i = 0; i < 30; ++i) {
    const SampledScene cached = sampler.Sample(6, i);
    const SampledScene fresh = SampleScene(*program, 6, i);
    ASSERT_EQ(cached.scene.objects.size(), 4u);
    EXPECT_EQ(cached.attempts, fresh.attempts);
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(cached.scene.objects[k].p_WO, fresh.scene.objects[k].p_WO);
    }
    EXPECT_FALSE(BoxesOverlapByPoints(Find(cached.scene, "c"), Find(cached.scene, "t")));
    rejections += cached.rejections.total;
  }
  EXPECT_GT(rejections, 0);  // the cube does land in the table, and is rejected
}

}  // namespace
}  // namespace prs::sampling
