// The work a sampler keeps between scenes (lang::RunCache): templates of objects fixed but for
// their position, shared module globals, regions `on` an object made at the origin and moved.
// None of it may change a scene: compared here with samplers that keep nothing, with samplers
// that met the scenes in another order, and with the law the relations state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lang/run_cache.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

// Every field a scene file shows, compared exactly.
void ExpectSameScene(const SampledScene& a, const SampledScene& b) {
  EXPECT_EQ(a.attempts, b.attempts);
  ASSERT_EQ(a.scene.objects.size(), b.scene.objects.size());
  for (size_t k = 0; k < a.scene.objects.size(); ++k) {
    const SceneObject& x = a.scene.objects[k];
    const SceneObject& y = b.scene.objects[k];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.cls, y.cls);
    EXPECT_EQ(x.p_WO, y.p_WO) << "object " << k << " of scene " << a.index;
    EXPECT_EQ(x.R_WO.coeffs(), y.R_WO.coeffs());
    EXPECT_EQ(x.dimensions, y.dimensions);
    ASSERT_EQ(x.properties.size(), y.properties.size());
    for (size_t p = 0; p < x.properties.size(); ++p) {
      EXPECT_EQ(x.properties[p].first, y.properties[p].first);
      EXPECT_EQ(lang::Repr(x.properties[p].second), lang::Repr(y.properties[p].second));
    }
  }
  ASSERT_EQ(a.scene.params.size(), b.scene.params.size());
  for (size_t p = 0; p < a.scene.params.size(); ++p) {
    EXPECT_EQ(lang::Repr(a.scene.params[p].second), lang::Repr(b.scene.params[p].second));
  }
}

// The first accepted attempt of scene `index` (seed 5), run with `cache`.
Scene RunUntilAccepted(const lang::CompiledProgram& program, uint64_t index,
                       lang::RunCache* cache) {
  geometry::Rng rng(5, index);
  lang::RunOptions options;
  options.cache = cache;
  for (;;) {
    lang::AttemptResult result = lang::RunAttempt(program, rng, options);
    if (auto* scene = std::get_if<Scene>(&result)) return std::move(*scene);
  }
}

// On a 1 m square workspace: a cube `on` a tray (it may overhang, so near the workspace's
// edge the region moved to the tray leaves the eroded workspace and the general path places
// the cube), a cube completely on a tray of random size (no template), and a gear completely
// on a plate (templates on templates: the region is kept).
constexpr char kOnPrograms[] = R"(from model import *
workspace = Cuboid(Vector3D(0, 0, 1), Vector3D(0, 0, 0), 1, 1, 2)
a = Tray on floor
c = Cube on a
b = Tray on floor, with width Range(0.1, 0.3)
d = Cube completely on b
p = Plate on floor
g = Gear completely on p
)";

TEST(KeptWorkTest, ScenesAreThoseOfASamplerThatKeepsNothing) {
  SampleOptions plain;
  plain.use_run_cache = false;
  for (const char* example : {"table_cube.prs", "constructs.prs", "pantry_shapes.prs"}) {
    SCOPED_TRACE(example);
    auto program = CompileExample(example);
    ASSERT_NE(program, nullptr);
    SceneSampler kept(*program), fresh(*program, plain);
    for (uint64_t i = 0; i < 60; ++i) ExpectSameScene(kept.Sample(3, i), fresh.Sample(3, i));
  }
  auto program = CompileOrDie(kOnPrograms);
  ASSERT_NE(program, nullptr);
  SceneSampler kept(*program), fresh(*program, plain);
  for (uint64_t i = 0; i < 300; ++i) ExpectSameScene(kept.Sample(9, i), fresh.Sample(9, i));
}

// Regions moved to their target are the regions made at the target: the same attempts, the
// same scenes but for positions' rounding (the two regions' vertices are worked out apart,
// within the geometry's 1e-9 m tolerance). Near the workspace's edge the general path runs.
TEST(KeptWorkTest, MovedRegionsGiveTheScenesOfRegionsMadeInPlace) {
  auto program = CompileOrDie(kOnPrograms);
  ASSERT_NE(program, nullptr);
  SampleOptions in_place;
  in_place.run.move_on_regions = false;
  SceneSampler moved(*program), made(*program, in_place);
  int differ = 0;
  for (uint64_t i = 0; i < 1000; ++i) {
    const SampledScene a = moved.Sample(6, i), b = made.Sample(6, i);
    ASSERT_EQ(a.attempts, b.attempts);
    ASSERT_EQ(a.scene.objects.size(), b.scene.objects.size());
    for (size_t k = 0; k < a.scene.objects.size(); ++k) {
      EXPECT_LT((a.scene.objects[k].p_WO - b.scene.objects[k].p_WO).norm(), 1e-9);
      differ += a.scene.objects[k].p_WO != b.scene.objects[k].p_WO;
    }
  }
  EXPECT_GT(differ, 0);  // the moved path did run
}

TEST(KeptWorkTest, ScenesDoNotDependOnTheScenesSampledBefore) {
  auto program = CompileOrDie(kOnPrograms);
  ASSERT_NE(program, nullptr);
  SceneSampler forward(*program), backward(*program);
  std::vector<SampledScene> first;
  for (uint64_t i = 0; i < 80; ++i) first.push_back(forward.Sample(4, i));
  for (uint64_t i = 80; i-- > 0;) ExpectSameScene(backward.Sample(4, i), first[i]);
}

// Every object on its support and inside the workspace, near its edge (general path) and
// away from it (region moved) alike; the gear's offset on the plate uniform over the centres
// that keep it on (the plate's top less the gear's half footprint).
TEST(KeptWorkTest, OnAMovedRegionIsUniformAndExact) {
  auto program = CompileOrDie(kOnPrograms);
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  constexpr int kScenes = 4000;
  std::vector<double> u_x, u_y, uniform;
  int near_edge = 0;
  for (uint64_t i = 0; i < kScenes; ++i) {
    const Scene scene = sampler.Sample(11, i).scene;
    const SceneObject& a = Find(scene, "a");
    const SceneObject& c = Find(scene, "c");
    EXPECT_NEAR(c.p_WO.z(), 0.03 + 0.025, kTol);
    EXPECT_LE(std::abs(c.p_WO.x() - a.p_WO.x()), a.dimensions.x() / 2 + kTol);
    EXPECT_LE(std::abs(c.p_WO.y() - a.p_WO.y()), a.dimensions.y() / 2 + kTol);
    for (const SceneObject& o : scene.objects) {
      for (const Vector3d& corner : Corners(o)) EXPECT_LE(corner.head<2>().cwiseAbs().maxCoeff(), 0.5 + kTol);
    }
    ExpectCompletelyOn(Find(scene, "d"), Find(scene, "b"));
    const SceneObject& p = Find(scene, "p");
    const SceneObject& g = Find(scene, "g");
    ExpectCompletelyOn(g, p);
    const Vector3d half_room = (p.dimensions - g.dimensions) / 2;
    u_x.push_back((g.p_WO.x() - p.p_WO.x() + half_room.x()) / (2 * half_room.x()));
    u_y.push_back((g.p_WO.y() - p.p_WO.y() + half_room.y()) / (2 * half_room.y()));
    uniform.push_back((i + 0.5) / kScenes);
    const Vector3d reach = a.p_WO.cwiseAbs() + a.dimensions / 2;
    near_edge += std::max(reach.x(), reach.y()) > 0.5 - 0.025;
  }
  EXPECT_GT(near_edge, 100);  // the cube's region crosses the workspace's edge in these
  // Two-sample KS against an exact uniform grid; 1.63 / sqrt(n/2) is the 1 % critical value.
  const double critical = 1.63 * std::sqrt(2.0 / kScenes);
  EXPECT_LT(KolmogorovSmirnov(u_x, uniform), critical);
  EXPECT_LT(KolmogorovSmirnov(u_y, uniform), critical);
}

// A region call with the same arguments in every run (kOnPrograms' main-module workspace) gives
// one region that lives in the thread's cache, so the workspace is kept (its erosions reused);
// a call whose arguments change within a run makes each region anew. Scenes are those of a
// sampler that keeps nothing.
TEST(KeptWorkTest, RegionCallsWithTheSameArgumentsGiveOneKeptRegion) {
  auto constant = CompileOrDie(kOnPrograms);
  auto looped = CompileOrDie(
      "from model import *\n"
      "for i in range(3):\n"
      "    Cube in Cuboid(Vector3D(i - 1, 0, 0.5), Vector3D(0, 0, 0), "
      "0.3, 0.3, 0.3)\n");
  ASSERT_TRUE(constant && looped);
  lang::RunCache cache;
  const Scene first = RunUntilAccepted(*constant, 0, &cache);
  const Scene second = RunUntilAccepted(*constant, 1, &cache);
  ASSERT_TRUE(first.workspace && second.workspace);
  EXPECT_EQ(first.workspace.get(), second.workspace.get()) << "one region for both scenes";
  EXPECT_EQ(cache.kept_regions.count(first.workspace.get()), 1u);
  for (const auto& [call, kept] : cache.region_calls) EXPECT_FALSE(kept.varying);
  EXPECT_FALSE(cache.eroded_workspaces.empty()) << "the kept workspace's erosions are kept";

  lang::RunCache looped_cache;
  for (uint64_t i = 0; i < 20; ++i) {
    const Scene scene = RunUntilAccepted(*looped, i, &looped_cache);
    ASSERT_EQ(scene.objects.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(scene.objects[k].p_WO.x() - (k - 1)), 0.15 + 1e-9) << "cube " << k;
    }
  }
  SampleOptions plain;
  plain.use_run_cache = false;
  for (const auto* program : {constant.get(), looped.get()}) {
    SceneSampler kept(*program), fresh(*program, plain);
    for (uint64_t i = 0; i < 100; ++i) ExpectSameScene(kept.Sample(7, i), fresh.Sample(7, i));
  }
}

// A workspace of drawn size: each scene folds its own into the cube's region. The position
// sampler of a region fixed in every scene (ObjectPlan::region_fixed) was kept with the first
// scene's workspace, so with seed 7 no cube lay more than 0.58 m from the centre in 2,000
// scenes. The law is rejection's: P(|x| > 0.5) = 0.2025 / 0.7 = 0.289 (x uniform on the 3 m
// floor, kept when the cube fits the workspace of width w ~ U(1, 2)).
TEST(KeptWorkTest, AWorkspaceOfDrawnSizeIsFoldedAnewInEveryScene) {
  auto drawn = CompileOrDie(
      "from model import *\n"
      "workspace = Cuboid(Vector3D(0, 0, 1), Vector3D(0, 0, 0), "
      "Range(1, 2), 1, 2)\n"
      "Cube on floor\n");
  ASSERT_NE(drawn, nullptr);
  lang::RunCache cache;
  const Scene a = RunUntilAccepted(*drawn, 0, &cache), b = RunUntilAccepted(*drawn, 1, &cache);
  EXPECT_NE(a.workspace->CalcVertices(), b.workspace->CalcVertices()) << "widths drawn apart";
  EXPECT_EQ(cache.kept_regions.count(b.workspace.get()), 0u);
  for (const auto& [key, eroded] : cache.eroded_workspaces) {
    EXPECT_NE(key.first, b.workspace.get()) << "a workspace made anew is not kept";
  }
  SampleOptions plain;
  plain.use_run_cache = false;
  SceneSampler kept(*drawn), fresh(*drawn, plain);
  constexpr int kScenes = 4000;
  int far = 0;
  for (uint64_t i = 0; i < kScenes; ++i) {
    const SampledScene scene = kept.Sample(7, i);
    if (i < 100) ExpectSameScene(scene, fresh.Sample(7, i));
    far += std::abs(scene.scene.objects[0].p_WO.x()) > 0.5;
  }
  const double p = 0.2025 / 0.7, se = std::sqrt(p * (1 - p) / kScenes);
  EXPECT_NEAR(static_cast<double>(far) / kScenes, p, 4 * se);
}

// `from M import *` binds M's globals over what the module bound before, and later bindings
// win, whether M's globals are shared (model.prs draws nothing) or not.
TEST(KeptWorkTest, ImportsBindInStatementOrder) {
  auto program = CompileOrDie("width = 7\n"
                              "from model import *\n"
                              "param imported = width\n"
                              "length = 5\n"
                              "param rebound = length\n"
                              "from model import *\n"
                              "param again = length\n"
                              "height = Range(1, 2)\n"
                              "param drawn = height\n");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  for (uint64_t i = 0; i < 3; ++i) {
    const Scene scene = sampler.Sample(2, i).scene;
    ASSERT_EQ(scene.params.size(), 4u);
    EXPECT_EQ(scene.params[0].second.As<double>(), 3);  // model.prs: width = 3
    EXPECT_EQ(scene.params[1].second.As<double>(), 5);
    EXPECT_EQ(scene.params[2].second.As<double>(), 3);
    EXPECT_GT(scene.params[3].second.As<double>(), 1);
  }
}

}  // namespace
}  // namespace prs::sampling
