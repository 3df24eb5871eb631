// The simulated Panda: its MuJoCo body tree matches the published kinematics (kinematics/
// panda.h), the kinematics stage's inverse kinematics puts MuJoCo's tool where it was asked and
// reports what is out of reach, and the servos with gravity compensation hold a pose.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <numbers>

#include "geometry/random.h"
#include "kinematics/ik.h"
#include "sim/control.h"
#include "sim/ik.h"

namespace prs::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// A floor and one arm whose base is at X_WBase.
std::string WriteOneArmWorld(const PandaNames& names, const Eigen::Vector3d& p_WBase,
                             const Eigen::Quaterniond& R_WBase) {
  return fmt::format(R"(<mujoco><compiler angle="radian" autolimits="true"/>
<option timestep="0.002"/>
<worldbody><geom type="plane" size="3 3 0.1"/>{}</worldbody>
<equality>{}</equality><actuator>{}</actuator></mujoco>)",
                     WritePandaBody(names, p_WBase, R_WBase), WritePandaEqualities(names),
                     WritePandaActuators(names));
}

PandaJointVector RandomJoints(geometry::Rng& rng) {
  PandaJointVector q;
  for (int i = 0; i < kPandaJoints; ++i) q[i] = rng.Uniform(kPandaLowerLimit_rad[i], kPandaUpperLimit_rad[i]);
  return q;
}

TEST(PandaTest, MujocoBodyTreeMatchesTheDhTable) {
  const PandaNames names{"left_"};
  const Eigen::Vector3d p_WBase(0.3, -0.4, 0.85);
  const Eigen::Quaterniond R_WBase(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  ModelPtr model = LoadModelFromXml(WriteOneArmWorld(names, p_WBase, R_WBase));
  DataPtr data = MakeData(*model);
  const ArmIndex arm = FindArm(*model, names);
  geometry::Rng rng(3, 0);
  for (int trial = 0; trial < 50; ++trial) {
    const PandaJointVector q = RandomJoints(rng);
    SetArmJoints(*model, *data, arm, q);
    const Eigen::Isometry3d expected =
        Eigen::Translation3d(p_WBase) * R_WBase * CalcPandaTcpPose(q);
    const Eigen::Isometry3d actual = GetTcpPose(*data, arm);
    EXPECT_LT((actual.translation() - expected.translation()).norm(), 1e-9);
    EXPECT_LT((actual.linear() - expected.linear()).norm(), 1e-9);
  }
}

// The simulator's inverse kinematics is kinematics::SolveIk on the Panda's chain in the arm's
// base frame (motion.h's PlanDownwardPath): its solutions put MuJoCo's tool centre point on the target.
TEST(PandaTest, InverseKinematicsReachesTargetsInFrontOfTheArm) {
  const PandaNames names{"a_"};
  const Eigen::Isometry3d X_WBase(Eigen::Translation3d(0.1, -0.2, 0.8) *
                                  Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  ModelPtr model = LoadModelFromXml(
      WriteOneArmWorld(names, X_WBase.translation(), Eigen::Quaterniond(X_WBase.linear())));
  DataPtr data = MakeData(*model);
  const ArmIndex arm = FindArm(*model, names);
  const kinematics::Chain chain = kinematics::MakePandaChain();
  Eigen::Isometry3d X_BaseTarget = Eigen::Isometry3d::Identity();
  // Pointing down.
  X_BaseTarget.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  int reached = 0;
  for (double x : {0.35, 0.5, 0.65}) {
    for (double y : {-0.25, 0.0, 0.25}) {
      X_BaseTarget.translation() = Eigen::Vector3d(x, y, 0.05);
      const kinematics::IkResult r =
          kinematics::SolveIk(chain, kinematics::MakePoseTarget(X_BaseTarget),
                              kinematics::ToVector(kPandaReadyPose_rad));
      EXPECT_TRUE(r.converged) << x << " " << y << ": " << r.position_error_m;
      if (!r.converged) continue;
      ++reached;
      SetArmJoints(*model, *data, arm, kinematics::ToPandaJoints(r.q));
      const Eigen::Isometry3d X_WTarget = X_WBase * X_BaseTarget;
      EXPECT_LT((GetTcpPose(*data, arm).translation() - X_WTarget.translation()).norm(), 0.002);
      for (int i = 0; i < kPandaJoints; ++i) {
        EXPECT_GE(r.q[i], kPandaLowerLimit_rad[i]);
        EXPECT_LE(r.q[i], kPandaUpperLimit_rad[i]);
      }
    }
  }
  EXPECT_EQ(reached, 9);
}

TEST(PandaTest, InverseKinematicsReportsATargetOutOfReach) {
  Eigen::Isometry3d X_BaseTarget = Eigen::Isometry3d::Identity();
  X_BaseTarget.translation() = Eigen::Vector3d(1.5, 0, 0.05);  // the arm reaches about 0.855 m
  const kinematics::IkResult r =
      kinematics::SolveIk(kinematics::MakePandaChain(), kinematics::MakePoseTarget(X_BaseTarget),
                          kinematics::ToVector(kPandaReadyPose_rad));
  EXPECT_FALSE(r.converged);
  EXPECT_GT(r.position_error_m, 0.5);
}

TEST(PandaTest, ServosWithGravityCompensationHoldThePose) {
  const PandaNames names{"a_"};
  ModelPtr model = LoadModelFromXml(WriteOneArmWorld(names, Eigen::Vector3d(0, 0, 0.8), Eigen::Quaterniond::Identity()));
  DataPtr data = MakeData(*model);
  const ArmIndex arm = FindArm(*model, names);
  SetArmJoints(*model, *data, arm, kPandaReadyPose_rad);
  mj_forward(model.get(), data.get());
  const Eigen::Vector3d p_start = GetTcpPose(*data, arm).translation();
  SimulateFor(*model, *data, {arm}, 1.0);
  EXPECT_LT((GetTcpPose(*data, arm).translation() - p_start).norm(), 0.001);
}

TEST(PandaTest, BadModelTextGivesMujocosMessage) {
  try {
    LoadModelFromXml("<mujoco><worldbody><geom type=\"nonsense\"/></worldbody></mujoco>");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("MuJoCo rejected the model"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace prs::sim
