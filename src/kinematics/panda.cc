// The Panda's kinematic data and its Chain (see panda.h).
#include "kinematics/panda.h"

#include <numbers>
#include <string>

namespace prs::kinematics {

namespace {

constexpr double kPi = std::numbers::pi;

// The flange's hand mounting and the tool centre point beyond it.
Eigen::Isometry3d CalcFlangeToTcp() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X = X * Eigen::AngleAxisd(-kPi / 4, Eigen::Vector3d::UnitZ()) *
      Eigen::Translation3d(0, 0, kPandaFlangeToTcp_m);
  return X;
}

// RotX(alpha) TransX(a) TransZ(d): a DH row's fixed part (TransZ(d) commutes with RotZ(q)).
Eigen::Isometry3d CalcDhFixed(const PandaDhRow& row) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X = X * Eigen::AngleAxisd(row.alpha_rad, Eigen::Vector3d::UnitX()) *
      Eigen::Translation3d(row.a_m, 0, 0) * Eigen::Translation3d(0, 0, row.d_m);
  return X;
}

}  // namespace

const std::array<PandaDhRow, kPandaJoints + 1> kPandaDh = {{
    {0, 0.333, 0},
    {0, 0, -kPi / 2},
    {0, 0.316, kPi / 2},
    {0.0825, 0, kPi / 2},
    {-0.0825, 0.384, -kPi / 2},
    {0, 0, kPi / 2},
    {0.088, 0, kPi / 2},
    {0, 0.107, 0},  // flange
}};
const PandaJointVector kPandaLowerLimit_rad = {-2.8973, -1.7628, -2.8973, -3.0718,
                                               -2.8973, -0.0175, -2.8973};
const PandaJointVector kPandaUpperLimit_rad = {2.8973, 1.7628, 2.8973, -0.0698,
                                               2.8973, 3.7525, 2.8973};
const PandaJointVector kPandaReadyPose_rad = {0, -kPi / 4, 0, -3 * kPi / 4, 0, kPi / 2, kPi / 4};

Eigen::Isometry3d CalcPandaTcpPose(const PandaJointVector& q_rad) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int i = 0; i <= kPandaJoints; ++i) {
    const PandaDhRow& row = kPandaDh[i];
    const double q = i < kPandaJoints ? q_rad[i] : 0.0;
    X = X * Eigen::AngleAxisd(row.alpha_rad, Eigen::Vector3d::UnitX()) *
        Eigen::Translation3d(row.a_m, 0, 0) * Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()) *
        Eigen::Translation3d(0, 0, row.d_m);
  }
  return X * CalcFlangeToTcp();
}

Chain MakePandaChain() {
  Chain chain;
  chain.name = "panda";
  for (int i = 0; i < kPandaJoints; ++i) {
    Joint joint;
    joint.name = "panda_joint" + std::to_string(i + 1);
    joint.type = JointType::kRevolute;
    joint.X_PJ = CalcDhFixed(kPandaDh[i]);
    joint.axis_J = Eigen::Vector3d::UnitZ();
    joint.lower = kPandaLowerLimit_rad[i];
    joint.upper = kPandaUpperLimit_rad[i];
    chain.joints.push_back(joint);
  }
  chain.X_LastTool = CalcDhFixed(kPandaDh[kPandaJoints]) * CalcFlangeToTcp();
  return chain;
}

Eigen::VectorXd ToVector(const PandaJointVector& q_rad) {
  return Eigen::Map<const Eigen::VectorXd>(q_rad.data(), kPandaJoints);
}

PandaJointVector ToPandaJoints(const Eigen::VectorXd& q_rad) {
  if (q_rad.size() != kPandaJoints) {
    throw KinematicsError("a Panda has 7 joints but " + std::to_string(q_rad.size()) +
                          " joint values were given");
  }
  PandaJointVector q{};
  for (int i = 0; i < kPandaJoints; ++i) q[i] = q_rad[i];
  return q;
}

}  // namespace prs::kinematics
