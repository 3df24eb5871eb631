// The Franka Emika Panda's published kinematics: modified Denavit–Hartenberg parameters
// (Craig's convention) and joint limits from Franka's robot documentation, the tool centre
// point between the fingertips, and the arm as a Chain.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "kinematics/chain.h"

namespace prs::kinematics {

inline constexpr int kPandaJoints = 7;
using PandaJointVector = std::array<double, kPandaJoints>;

/// One row of the modified DH table: frame i from frame i-1 is RotX(alpha) TransX(a) RotZ(q_i)
/// TransZ(d); the last row is the flange (no joint).
struct PandaDhRow {
  double a_m, d_m, alpha_rad;
};
extern const std::array<PandaDhRow, kPandaJoints + 1> kPandaDh;
extern const PandaJointVector kPandaLowerLimit_rad;
extern const PandaJointVector kPandaUpperLimit_rad;
/// A comfortable pose above the table: elbow up, hand pointing down.
extern const PandaJointVector kPandaReadyPose_rad;

/// Tool centre point (between the fingertips) from the flange, along the flange's z axis.
inline constexpr double kPandaFlangeToTcp_m = 0.1034;
/// Each finger's travel from closed; the gripper opens to twice this.
inline constexpr double kPandaFingerTravel_m = 0.04;

/// X_BaseTcp: the tool centre point's pose in the base frame at joint angles q, from the DH
/// table alone: the flange, turned −45° about its z axis (the hand's mounting), then
/// kPandaFlangeToTcp_m along z.
Eigen::Isometry3d CalcPandaTcpPose(const PandaJointVector& q_rad);

/// The Panda as a Chain named "panda" (joints "panda_joint1".."panda_joint7", the DH table's
/// limits) whose tool is the tool centre point: CalcToolPose equals CalcPandaTcpPose.
Chain MakePandaChain();

/// Conversions between the fixed-size joint vector and the Chain's.
Eigen::VectorXd ToVector(const PandaJointVector& q_rad);
/// Throws KinematicsError when q does not have kPandaJoints values.
PandaJointVector ToPandaJoints(const Eigen::VectorXd& q_rad);

}  // namespace prs::kinematics
