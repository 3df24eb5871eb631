// The work a sampler keeps between scenes (lang::RunCache): templates of objects fixed but for
// their position, shared module globals, regions `on` an object made at the origin and moved.
// None of it may change a scene: compared here with samplers that keep nothing, with samplers
// that met the scenes in another order, and with the law the relations state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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
