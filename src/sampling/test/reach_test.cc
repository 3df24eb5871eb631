// `reachable by ARM` (spec §10): every sampled position is reachable by the arm standing where
// the scene's robot stands (an independent IK check with joint 1 free and restarts, not the
// reachable set's own cells), with no rejection; the approach and margin options hold; and the
// positions are uniform over the union of cells (against a brute-force sampler on the same
// surface).
#include <gtest/gtest.h>

#include <numbers>

#include "geometry/union.h"
#include "kinematics/mount.h"
#include "kinematics/panda.h"
#include "kinematics/reach.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using namespace testing_checks;

const char* kPrologue = R"(
class Table:
    width: 1.8
    length: 0.8
    height: 0.8
class Robot:
    width: 0.2
    length: 0.2
    height: 0.1
    arm: "panda"
class Cube:
    width: 0.05
    length: 0.05
    height: 0.05
t = Table at V3D(0, 0, 0.4)
)";

// The robot's arm base pose, as the simulator mounts it (kinematics/mount.h).
Eigen::Isometry3d BaseOf(const SceneObject& robot) {
  return kinematics::CalcArmMount(robot.p_WO, robot.R_WO.toRotationMatrix(), robot.dimensions);
}

// Whether the Panda at X_WBase reaches p_W pointing down: the independent check.
bool IsReachableFrom(const Eigen::Isometry3d& X_WBase, const Vector3d& p_W) {
  static const kinematics::Chain panda = kinematics::MakePandaChain();
  return kinematics::IsReachable(panda, X_WBase.inverse() * p_W, kinematics::Grasp::kDown,
                                 /*restarts=*/20);
}

TEST(ReachTest, EveryPositionIsReachableAndNoneIsRejected) {
  // The robot anywhere along the table's back edge, turned anyhow: the set moves with it.
  auto program = CompileOrDie(std::string(kPrologue) + R"(
r = Robot on t, with yaw (-3.1, 3.1)
c = Cube on t, reachable by r
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int checked = 0;
  for (int i = 0; i < 1000; ++i) {
    const SampledScene s = sampler.Sample(1, i);
    // A robot placed where the cube has no room on the table rejects the scene; the cube's own
    // draw never is.
    for (const auto& [key, n] : s.rejections.by_culprit) {
      EXPECT_NE(key.first, lang::RejectionKind::kOutsideRegion) << key.second;
    }
    const SceneObject& c = Find(s.scene, "c");
    ASSERT_TRUE(IsReachableFrom(BaseOf(Find(s.scene, "r")), c.p_WO))
        << "scene " << i << ": " << c.p_WO.transpose();
    ++checked;
  }
  EXPECT_EQ(checked, 1000);
}

TEST(ReachTest, ApproachAndMarginHold) {
  auto program = CompileOrDie(std::string(kPrologue) + R"(
r = Robot on (top back t)
c = Cube on t, reachable by r with approach 0.15
d = Cube on t, reachable by r with margin 0.05
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  for (int i = 0; i < 150; ++i) {
    const SampledScene s = sampler.Sample(2, i);
    const Eigen::Isometry3d X_WBase = BaseOf(Find(s.scene, "r"));
    const Vector3d p_c = Find(s.scene, "c").p_WO;
    for (double up : {0.0, 0.05, 0.1, 0.15}) {
      ASSERT_TRUE(IsReachableFrom(X_WBase, p_c + Vector3d(0, 0, up))) << "scene " << i << " up " << up;
    }
    const Vector3d p_d = Find(s.scene, "d").p_WO;
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {-1.0, 1.0}) {
        ASSERT_TRUE(IsReachableFrom(X_WBase, p_d + sign * 0.049 * Vector3d::Unit(axis)))
            << "scene " << i << ": 4.9 cm from d along axis " << axis;
      }
    }
  }
}

TEST(ReachTest, PositionsAreUniformOverTheReachableSet) {
  // The table top within reach of a fixed robot: the sampler's positions against a brute-force
  // sampler (uniform on the table top, kept when inside the reachable set's cells): two-sample
  // KS on x and on y.
  auto program = CompileOrDie(std::string(kPrologue) + R"(
r = Robot on (top back t) - V3D(0.4, 0, 0)
c = Cube on t, reachable by r
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  std::vector<double> xs, ys;
  for (int i = 0; i < 3000; ++i) {
    const SampledScene sampled = sampler.Sample(3, i);
    const SceneObject& c = Find(sampled.scene, "c");
    xs.push_back(c.p_WO.x());
    ys.push_back(c.p_WO.y());
  }
  // The cells, as the program builds them, placed at the robot's base.
  const SampledScene first = sampler.Sample(3, 0);
  const kinematics::ReachLoad cells = kinematics::LoadOrComputeReachableSet(
      kinematics::MakePandaChain(), kinematics::ReachOptions{}, lang::DefaultCacheDir());
  const geometry::RegionUnion reach(std::make_shared<const geometry::PieceSet>(cells.set->cells_Base),
                                    BaseOf(Find(first.scene, "r")));
  geometry::Rng rng(4, 0);
  std::vector<double> bx, by;
  while (bx.size() < 3000) {
    const Vector3d p(rng.Uniform(-0.9, 0.9), rng.Uniform(-0.4, 0.4), 0.825);
    if (!reach.Contains(p, 0)) continue;
    bx.push_back(p.x());
    by.push_back(p.y());
  }
  // 1.95 · sqrt(2 / 3000): the two-sample KS statistic's 0.001 critical value.
  EXPECT_LT(KolmogorovSmirnov(xs, bx), 1.95 * std::sqrt(2.0 / 3000));
  EXPECT_LT(KolmogorovSmirnov(ys, by), 1.95 * std::sqrt(2.0 / 3000));
}

TEST(ReachTest, AGraspFromTheSideReachesOnlyWhatASideGraspReaches) {
  auto program = CompileOrDie(std::string(kPrologue) + R"(
r = Robot on (top back t)
c = Cube on t, reachable by r with grasp "side"
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  static const kinematics::Chain panda = kinematics::MakePandaChain();
  for (int i = 0; i < 100; ++i) {
    const SampledScene s = sampler.Sample(5, i);
    const Vector3d p_Base = BaseOf(Find(s.scene, "r")).inverse() * Find(s.scene, "c").p_WO;
    ASSERT_TRUE(kinematics::IsReachable(panda, p_Base, kinematics::Grasp::kSide, 20)) << i;
  }
}

}  // namespace
}  // namespace prs::sampling
