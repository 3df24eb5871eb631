// Inverse kinematics on the Panda's chain: each kind of target is reached from the ready pose
// within the limits, an out-of-reach target is reported, held joints stay, restarts are
// deterministic for a seed, and bad arguments throw.
#include "kinematics/ik.h"

#include <gtest/gtest.h>

#include <numbers>

#include "geometry/random.h"
#include "kinematics/panda.h"

namespace prs::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;

const Eigen::VectorXd kReady = ToVector(kPandaReadyPose_rad);

Eigen::Matrix3d CalcDownward(double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

void ExpectWithinLimits(const Chain& chain, const Eigen::VectorXd& q) {
  for (int i = 0; i < chain.num_joints(); ++i) {
    EXPECT_GE(q[i], chain.joints[i].lower) << "joint " << i;
    EXPECT_LE(q[i], chain.joints[i].upper) << "joint " << i;
  }
}

TEST(IkTest, ReachesPoseTargetsInFrontOfTheArm) {
  const Chain chain = MakePandaChain();
  int reached = 0;
  for (double x : {0.35, 0.5, 0.65}) {
    for (double y : {-0.25, 0.0, 0.25}) {
      Eigen::Isometry3d X_target = Eigen::Isometry3d::Identity();
      X_target.linear() = CalcDownward(0.3);
      X_target.translation() = Eigen::Vector3d(x, y, 0.05);
      const IkResult r = SolveIk(chain, MakePoseTarget(X_target), kReady);
      EXPECT_TRUE(r.converged) << x << " " << y << ": " << r.position_error_m;
      if (!r.converged) continue;
      ++reached;
      const Eigen::Isometry3d X = CalcToolPose(chain, r.q);
      EXPECT_LT((X.translation() - X_target.translation()).norm(), 0.002);
      EXPECT_LT(Eigen::AngleAxisd(X.linear().transpose() * X_target.linear()).angle(), 0.02);
      EXPECT_NEAR(r.position_error_m, (X.translation() - X_target.translation()).norm(), 1e-12);
      ExpectWithinLimits(chain, r.q);
    }
  }
  EXPECT_EQ(reached, 9);
}

TEST(IkTest, AxisTargetLeavesTheRotationAboutTheAxisFree) {
  const Chain chain = MakePandaChain();
  IkOptions options;
  options.position_tolerance_m = 1e-4;
  options.rotation_tolerance_rad = 1e-3;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.2, -1).normalized();
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.5, 0.2, 0.2), Eigen::Vector3d(0.3, -0.4, 0.4)}) {
    const IkResult r = SolveIk(chain, MakeAxisTarget(p, axis), kReady, options);
    ASSERT_TRUE(r.converged) << r.position_error_m << " " << r.rotation_error_rad;
    const Eigen::Isometry3d X = CalcToolPose(chain, r.q);
    EXPECT_LT((X.translation() - p).norm(), 1e-4);
    EXPECT_LT(std::acos(std::min(1.0, X.linear().col(2).dot(axis))), 1e-3);
    ExpectWithinLimits(chain, r.q);
  }
  // The full-pose solver would have to turn the hand; the axis target does not.
  Eigen::Isometry3d X_ready = CalcToolPose(chain, kReady);
  const Eigen::Vector3d p_nearby = X_ready.translation() + Eigen::Vector3d(0.05, 0, 0);
  const IkResult r =
      SolveIk(chain, MakeAxisTarget(p_nearby, -Eigen::Vector3d::UnitZ()), kReady, options);
  ASSERT_TRUE(r.converged);
  EXPECT_LT(r.iterations, 20);
}

TEST(IkTest, PositionTargetIgnoresOrientation) {
  const Chain chain = MakePandaChain();
  const Eigen::Vector3d p(-0.3, 0.45, 0.6);
  const IkResult r = SolveIk(chain, MakePositionTarget(p), kReady);
  ASSERT_TRUE(r.converged) << r.position_error_m;
  EXPECT_LT((CalcToolPose(chain, r.q).translation() - p).norm(), 0.002);
  EXPECT_EQ(r.rotation_error_rad, 0);
  ExpectWithinLimits(chain, r.q);
}

TEST(IkTest, ReportsATargetOutOfReach) {
  const Chain chain = MakePandaChain();
  Eigen::Isometry3d X_target = Eigen::Isometry3d::Identity();
  X_target.translation() = Eigen::Vector3d(1.5, 0, 0.05);  // the arm reaches about 0.855 m
  const IkResult r = SolveIk(chain, MakePoseTarget(X_target), kReady);
  EXPECT_FALSE(r.converged);
  EXPECT_GT(r.position_error_m, 0.5);
  EXPECT_EQ(r.iterations, 300);
  ExpectWithinLimits(chain, r.q);
  const IkResult restarted =
      SolveIkWithRestarts(chain, MakePositionTarget(X_target.translation()), kReady, {}, 5, 3);
  EXPECT_FALSE(restarted.converged);
}

TEST(IkTest, StaysWithinLimitsForRandomTargets) {
  const Chain chain = MakePandaChain();
  geometry::Rng rng(21, 0);
  for (int trial = 0; trial < 30; ++trial) {
    const Eigen::Vector3d p(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-0.5, 1.2));
    IkOptions options;
    options.max_iterations = 100;
    const IkResult r =
        SolveIk(chain, MakeAxisTarget(p, -Eigen::Vector3d::UnitZ()), kReady, options);
    ExpectWithinLimits(chain, r.q);
  }
}

TEST(IkTest, HeldJointsKeepTheirValue) {
  const Chain chain = MakePandaChain();
  IkOptions options;
  options.held_joints = {0, 6};
  // Straight ahead of the arm: reachable without turning joint 1.
  const IkResult r =
      SolveIk(chain, MakeAxisTarget({0.55, 0, 0.1}, -Eigen::Vector3d::UnitZ()), kReady, options);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.q[0], kReady[0]);
  EXPECT_EQ(r.q[6], kReady[6]);
  // Behind the arm the held joint 1 stays put whatever the solver does with the others.
  const IkResult behind = SolveIk(
      chain,
      MakePoseTarget(Eigen::Translation3d(-0.5, 0.0, 0.1) * Eigen::Isometry3d(CalcDownward(0))),
      kReady, options);
  EXPECT_EQ(behind.q[0], kReady[0]);
  EXPECT_EQ(behind.q[6], kReady[6]);
  options.held_joints = {7};
  EXPECT_THROW(SolveIk(chain, MakePositionTarget({0.5, 0, 0.3}), kReady, options), KinematicsError);
}

TEST(IkTest, RestartsAreDeterministicForASeed) {
  const Chain chain = MakePandaChain();
  // From every joint at its lower limit the solver does not get there in 60 steps; restarts do.
  const IkTarget target = MakeAxisTarget({0.5, 0.3, 0.15}, -Eigen::Vector3d::UnitZ());
  const Eigen::VectorXd q_start = GetLowerLimits(chain);
  IkOptions options;
  options.max_iterations = 60;
  ASSERT_FALSE(SolveIk(chain, target, q_start, options).converged);
  const IkResult a = SolveIkWithRestarts(chain, target, q_start, options, 40, 42);
  const IkResult b = SolveIkWithRestarts(chain, target, q_start, options, 40, 42);
  ASSERT_TRUE(a.converged);
  EXPECT_EQ(a.q, b.q);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_GT(a.iterations, options.max_iterations);  // the first attempt's steps count too
  const IkResult c = SolveIkWithRestarts(chain, target, q_start, options, 40, 43);
  ASSERT_TRUE(c.converged);
  EXPECT_NE(a.q, c.q);  // another seed starts elsewhere and ends at another solution
}

TEST(IkTest, BadArgumentsThrow) {
  const Chain chain = MakePandaChain();
  EXPECT_THROW(SolveIk(chain, MakePositionTarget({0.5, 0, 0.3}), Eigen::VectorXd::Zero(6)),
               KinematicsError);
  EXPECT_THROW(MakeAxisTarget({0.5, 0, 0.3}, Eigen::Vector3d::Zero()), KinematicsError);
  EXPECT_THROW(MakePositionTarget({NAN, 0, 0}), KinematicsError);
  IkOptions options;
  options.max_step = 0;
  EXPECT_THROW(SolveIk(chain, MakePositionTarget({0.5, 0, 0.3}), kReady, options), KinematicsError);
  EXPECT_THROW(SolveIkWithRestarts(chain, MakePositionTarget({0.5, 0, 0.3}), kReady, {}, -1, 0),
               KinematicsError);
}

}  // namespace
}  // namespace prs::kinematics
