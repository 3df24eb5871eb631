// Built-in shapes (spec §10: `Cylinder()`, `Sphere()`, `Capsule()`) in sampled scenes, checked
// against the true shapes, not the polytopes the sampler uses: every shape `completely on` the
// table lies within the tabletop and stands on it; two balls never overlap (centre distance)
// while their boxes do, so placement accepts what boxes would reject; a cube `on` a can
// stands on the can's top ellipse; sizes drawn anew in every scene (past the per-thread cache
// of polytopes) give the same scene as a fresh sampler.
#include <gtest/gtest.h>

#include "geometry/box.h"
#include "sampling/test/scene_checks.h"
#include "shapes/primitive.h"

namespace prs::sampling {
namespace {

using namespace testing_checks;

constexpr const char* kProgram = R"(
from model import *
class Can:
    shape: Cylinder()
    width: Range(0.05, 0.12)
    length: Range(0.05, 0.12)
    height: Range(0.08, 0.16)
class Ball:
    shape: Sphere()
    width: 0.1
    length: 0.1
    height: 0.1
class Pill:
    shape: Capsule()
    width: 0.05
    length: 0.08
    height: 0.2
t = Table on V3D(0, 0, 0)
c = Can completely on t
b1 = Ball completely on t
b2 = Ball at b1.position + V3D(Range(0.06, 0.1), Range(0.06, 0.1), 0)
p = Pill completely on t, with yaw 0.7
x = Cube on c, with width 0.02, with length 0.02, with height 0.02
)";

// The true shape's extent from its centre along the world direction n_W.
double CalcReach(const SceneObject& o, const Vector3d& n_W) {
  const shapes::PrimitiveAxes axes = shapes::CalcPrimitiveAxes(*o.primitive, o.dimensions);
  return shapes::CalcPrimitiveSupport(axes, o.R_WO.toRotationMatrix().transpose() * n_W);
}

TEST(PrimitiveSceneTest, ShapesLieOnTheTableBallsNeverOverlapCubeStandsOnTheCan) {
  auto program = CompileOrDie(kProgram);
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int ball_boxes_overlap = 0;
  for (int i = 0; i < 1000; ++i) {
    const SampledScene s = sampler.Sample(7, i);
    const SceneObject& table = Find(s.scene, "t");
    const double top = table.p_WO.z() + table.dimensions.z() / 2;
    for (const char* name : {"c", "b1", "p"}) {
      const SceneObject& o = Find(s.scene, name);
      ASSERT_TRUE(o.primitive && o.mesh) << name;
      for (const Vector3d& n : {Vector3d(1, 0, 0), Vector3d(-1, 0, 0)}) {
        ASSERT_LE(n.dot(o.p_WO) + CalcReach(o, n), 0.9 + kTol) << "scene " << i << " " << name;
      }
      for (const Vector3d& n : {Vector3d(0, 1, 0), Vector3d(0, -1, 0)}) {
        ASSERT_LE(n.dot(o.p_WO) + CalcReach(o, n), 0.4 + kTol) << "scene " << i << " " << name;
      }
      EXPECT_NEAR(o.p_WO.z() - CalcReach(o, -Vector3d::UnitZ()), top, 1e-9) << "scene " << i << " " << name;
    }
    const SceneObject& b1 = Find(s.scene, "b1");
    const SceneObject& b2 = Find(s.scene, "b2");
    ASSERT_GE((b1.p_WO - b2.p_WO).norm(), 0.1 - kTol) << "scene " << i;
    ball_boxes_overlap += geometry::DoBoxesOverlap(
        {b1.p_WO, b1.R_WO.toRotationMatrix(), b1.dimensions / 2},
        {b2.p_WO, b2.R_WO.toRotationMatrix(), b2.dimensions / 2});
    // The cube's centre over the can's top ellipse, its bottom on the can's top.
    const SceneObject& can = Find(s.scene, "c");
    const SceneObject& cube = Find(s.scene, "x");
    const Vector3d p_C = can.R_WO.toRotationMatrix().transpose() * (cube.p_WO - can.p_WO);
    ASSERT_LE(std::hypot(p_C.x() / (can.dimensions.x() / 2), p_C.y() / (can.dimensions.y() / 2)),
              1 + 1e-9) << "scene " << i;
    EXPECT_NEAR(p_C.z(), can.dimensions.z() / 2 + 0.01, 1e-9) << "scene " << i;
  }
  // b2 is diagonally beside b1, 6 to 10 cm along x and y: their boxes overlap in every scene
  // (a third of the attempts, where the balls themselves would overlap, are rejected).
  EXPECT_GT(ball_boxes_overlap, 990);
}

TEST(PrimitiveSceneTest, ScenesAreTheSameWhicheverPolytopesTheCacheHolds) {
  auto program = CompileOrDie(kProgram);
  ASSERT_NE(program, nullptr);
  SceneSampler warm(*program);
  for (int i = 0; i < 300; ++i) warm.Sample(11, i);  // past RunCache::kMaxPrimitives sizes
  SceneSampler cold(*program);
  for (int i : {0, 150, 299, 300}) {
    const SampledScene a = warm.Sample(11, i), b = cold.Sample(11, i);
    ASSERT_EQ(a.scene.objects.size(), b.scene.objects.size());
    for (size_t k = 0; k < a.scene.objects.size(); ++k) {
      EXPECT_EQ(a.scene.objects[k].p_WO, b.scene.objects[k].p_WO) << i << " " << k;
      EXPECT_EQ(a.scene.objects[k].dimensions, b.scene.objects[k].dimensions) << i << " " << k;
    }
  }
}

// Absurd sizes (1e300 m) collide as their boxes, without FCL's overflowing covariance fits
// printing to stderr; tiny ones (1e-300 m) are quiet too, and do not collide: smaller than the
// touching allowance, as boxes that small do not (geometry::DoBoxesOverlap).
TEST(PrimitiveSceneTest, AbsurdSizesCollideAsTheirBoxesQuietly) {
  for (const char* size : {"1e300", "1e-300"}) {
    auto program = CompileOrDie(std::string("class Ball:\n    shape: Sphere()\n    width: ") + size +
                                "\n    length: " + size + "\n    height: " + size +
                                "\na = Ball at V3D(0, 0, 1)\nb = Ball at V3D(0, 0, 1)\n");
    ASSERT_NE(program, nullptr);
    ::testing::internal::CaptureStderr();
    geometry::Rng rng(1, 0);
    const lang::AttemptResult result = lang::RunAttempt(*program, rng, lang::RunOptions{});
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << size;
    const auto* rejection = std::get_if<lang::Rejection>(&result);
    if (std::string(size) == "1e-300") {
      EXPECT_EQ(rejection, nullptr);
      continue;
    }
    ASSERT_NE(rejection, nullptr) << size;
    EXPECT_EQ(rejection->kind, lang::RejectionKind::kCollision) << size;
  }
}

TEST(PrimitiveSceneTest, AShapeWithAZeroSizeStaysItsFlatBox) {
  auto program = CompileOrDie(R"(
from model import *
class Disk:
    shape: Cylinder()
    width: 0.1
    length: 0.1
    height: 0
t = Table on V3D(0, 0, 0)
d = Disk completely on t
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  const SampledScene s = sampler.Sample(1, 0);
  const SceneObject& d = Find(s.scene, "d");
  EXPECT_TRUE(d.primitive);
  EXPECT_EQ(d.mesh, nullptr);
}

}  // namespace
}  // namespace prs::sampling
