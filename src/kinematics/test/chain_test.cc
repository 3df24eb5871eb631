// Chains: the Panda's chain equals its DH table at random joints, the flange sits where Franka
// publishes it, the Jacobian matches finite differences, limits and validation, the arm mount.
#include "kinematics/chain.h"

#include <gtest/gtest.h>

#include <numbers>

#include "geometry/random.h"
#include "kinematics/mount.h"
#include "kinematics/panda.h"

namespace prs::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::VectorXd RandomJoints(const Chain& chain, geometry::Rng& rng) {
  Eigen::VectorXd q(chain.num_joints());
  for (int i = 0; i < chain.num_joints(); ++i) {
    q[i] = rng.Uniform(chain.joints[i].lower, chain.joints[i].upper);
  }
  return q;
}

// A chain with a prismatic joint and tilted axes, for the Jacobian.
Chain MakeMixedChain() {
  Chain chain;
  chain.name = "mixed";
  Joint lift{"lift",
             JointType::kPrismatic,
             Eigen::Isometry3d::Identity(),
             Eigen::Vector3d(0, 0.6, 0.8),
             -0.2,
             0.5};
  lift.X_PJ.translation() << 0.1, -0.2, 0.3;
  Joint turn{
      "turn", JointType::kRevolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d(1, 0, 0), -2, 2};
  turn.X_PJ = Eigen::Translation3d(0.2, 0, 0.1) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  Joint bend{
      "bend", JointType::kRevolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d(0, 0, 1), -2, 2};
  bend.X_PJ = Eigen::Translation3d(0, 0.4, 0) * Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitX());
  chain.joints = {lift, turn, bend};
  chain.X_LastTool =
      Eigen::Translation3d(0.15, 0.05, -0.1) * Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ());
  return chain;
}

TEST(PandaChainTest, EqualsTheDhTableAtRandomJoints) {
  const Chain chain = MakePandaChain();
  ASSERT_EQ(chain.num_joints(), kPandaJoints);
  geometry::Rng rng(11, 0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = RandomJoints(chain, rng);
    const Eigen::Isometry3d expected = CalcPandaTcpPose(ToPandaJoints(q));
    const Eigen::Isometry3d actual = CalcToolPose(chain, q);
    EXPECT_LT((actual.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12) << trial;
  }
}

TEST(PandaChainTest, FlangeAtZeroIsWherePublishedKinematicsPutIt) {
  // At q = 0 the flange is at (0.088, 0, 0.926) in the base frame, pointing down; the tool
  // centre point is 0.1034 m below it.
  const Eigen::Isometry3d X_BaseTcp = CalcToolPose(MakePandaChain(), Eigen::VectorXd::Zero(7));
  const Eigen::Vector3d z_tcp = X_BaseTcp.linear().col(2);
  const Eigen::Vector3d p_flange = X_BaseTcp.translation() - kPandaFlangeToTcp_m * z_tcp;
  EXPECT_NEAR((p_flange - Eigen::Vector3d(0.088, 0, 0.926)).norm(), 0, 1e-12);
  EXPECT_NEAR(z_tcp.z(), -1, 1e-12);
  EXPECT_NEAR(X_BaseTcp.translation().z(), 0.926 - 0.1034, 1e-12);
  // The hand is turned −45° about the flange's z axis: the fingers close along (1, 1, 0)/√2.
  const Eigen::Vector3d y_tcp = X_BaseTcp.linear().col(1);
  EXPECT_NEAR(std::abs(y_tcp.x()), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(std::abs(y_tcp.y()), std::sqrt(0.5), 1e-12);
}

TEST(PandaChainTest, JointVectorConversionsRoundTripAndCheckTheSize) {
  EXPECT_EQ(ToPandaJoints(ToVector(kPandaReadyPose_rad)), kPandaReadyPose_rad);
  EXPECT_THROW(ToPandaJoints(Eigen::VectorXd::Zero(6)), KinematicsError);
}

void ExpectJacobianMatchesFiniteDifferences(const Chain& chain, uint64_t seed) {
  geometry::Rng rng(seed, 0);
  constexpr double h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = RandomJoints(chain, rng);
    const Jacobian J = CalcToolJacobian(chain, q);
    const Eigen::Isometry3d X = CalcToolPose(chain, q);
    for (int i = 0; i < chain.num_joints(); ++i) {
      Eigen::VectorXd q_plus = q, q_minus = q;
      q_plus[i] += h;
      q_minus[i] -= h;
      const Eigen::Isometry3d Xp = CalcToolPose(chain, q_plus), Xm = CalcToolPose(chain, q_minus);
      const Eigen::Vector3d v = (Xp.translation() - Xm.translation()) / (2 * h);
      // ω from dR/dq = [ω]× R.
      const Eigen::Matrix3d W = (Xp.linear() - Xm.linear()) / (2 * h) * X.linear().transpose();
      const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
      EXPECT_LT((J.col(i).head<3>() - v).norm(), 1e-7) << chain.name << " joint " << i;
      EXPECT_LT((J.col(i).tail<3>() - w).norm(), 1e-7) << chain.name << " joint " << i;
    }
  }
}

TEST(ChainTest, JacobianMatchesFiniteDifferences) {
  ExpectJacobianMatchesFiniteDifferences(MakePandaChain(), 5);
  ExpectJacobianMatchesFiniteDifferences(MakeMixedChain(), 6);
}

TEST(ChainTest, PrismaticJointTranslatesAlongItsAxis) {
  const Chain chain = MakeMixedChain();
  const Eigen::Vector3d p0 = CalcToolPose(chain, Eigen::Vector3d(0, 0.4, -0.3)).translation();
  const Eigen::Vector3d p1 = CalcToolPose(chain, Eigen::Vector3d(0.25, 0.4, -0.3)).translation();
  EXPECT_NEAR((p1 - p0 - 0.25 * Eigen::Vector3d(0, 0.6, 0.8)).norm(), 0, 1e-12);
}

TEST(ChainTest, LimitHelpers) {
  const Chain chain = MakePandaChain();
  const Eigen::VectorXd ready = ToVector(kPandaReadyPose_rad);
  EXPECT_TRUE(IsWithinLimits(chain, ready));
  EXPECT_FALSE(IsWithinLimits(chain, Eigen::VectorXd::Zero(7)));  // joint 4 must be < -0.0698
  EXPECT_FALSE(IsWithinLimits(chain, Eigen::VectorXd::Zero(6)));
  Eigen::VectorXd q = ready;
  q[3] = 0.5;
  q[5] = -4;
  const Eigen::VectorXd clamped = ClampToLimits(chain, q);
  EXPECT_EQ(clamped[3], kPandaUpperLimit_rad[3]);
  EXPECT_EQ(clamped[5], kPandaLowerLimit_rad[5]);
  EXPECT_EQ(clamped[0], ready[0]);
  EXPECT_NEAR(CalcMidRange(chain)[5], 0.5 * (kPandaLowerLimit_rad[5] + kPandaUpperLimit_rad[5]),
              1e-15);
  EXPECT_THROW(ClampToLimits(chain, Eigen::VectorXd::Zero(3)), KinematicsError);
  EXPECT_THROW(CalcToolPose(chain, Eigen::VectorXd::Zero(3)), KinematicsError);
}

TEST(ChainTest, ValidationNamesTheJointAndTheProblem) {
  Chain chain = MakeMixedChain();
  EXPECT_NO_THROW(ValidateChain(chain));
  chain.joints[1].lower = 3;
  try {
    ValidateChain(chain);
    FAIL() << "expected an error";
  } catch (const KinematicsError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'turn'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lower limit"), std::string::npos) << e.what();
  }
  chain = MakeMixedChain();
  chain.joints[2].axis_J = Eigen::Vector3d(0, 0, 2);
  EXPECT_THROW(ValidateChain(chain), KinematicsError);
  chain.joints.clear();
  EXPECT_THROW(ValidateChain(chain), KinematicsError);
}

TEST(ArmMountTest, BaseStandsAtTheBottomFaceFacingTheObjectsForward) {
  const Eigen::Vector3d p_WO(1.0, -0.5, 1.3), dimensions(0.4, 0.5, 1.0);
  const Eigen::Matrix3d R_WO =
      Eigen::AngleAxisd(kPi / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Isometry3d X_WBase = CalcArmMount(p_WO, R_WO, dimensions);
  EXPECT_NEAR((X_WBase.translation() - Eigen::Vector3d(1.0, -0.5, 0.8)).norm(), 0, 1e-12);
  EXPECT_NEAR((X_WBase.linear().col(0) - R_WO.col(1)).norm(), 0, 1e-12);  // base x = object +y
  EXPECT_NEAR((X_WBase.linear().col(2) - R_WO.col(2)).norm(), 0, 1e-12);  // base z = object up
  // A tilted object: the base stands on the bottom face along the object's own z.
  const Eigen::Matrix3d R_tilted =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Isometry3d X_tilted = CalcArmMount(p_WO, R_tilted, dimensions);
  EXPECT_NEAR((X_tilted.translation() - (p_WO - 0.5 * R_tilted.col(2))).norm(), 0, 1e-12);
}

}  // namespace
}  // namespace prs::kinematics
