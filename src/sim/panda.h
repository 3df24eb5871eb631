// The Franka Emika Panda arm for the simulated case study: its published kinematics (modified
// Denavit-Hartenberg parameters, Craig's convention, and joint limits from Franka's robot
// documentation), written as an MJCF body tree built from simple shapes, with a two-finger
// parallel gripper that grasps by friction.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

namespace prs::sim {

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

/// Names of one arm's elements in the model, all starting with the arm's prefix ("left_").
struct PandaNames {
  std::string prefix;
  std::string joint(int i) const { return prefix + "joint" + std::to_string(i + 1); }
  std::string actuator(int i) const { return prefix + "actuator" + std::to_string(i + 1); }
  std::string base() const { return prefix + "link0"; }
  std::string hand() const { return prefix + "hand"; }
  std::string tcp_site() const { return prefix + "tcp"; }
  std::string finger_joint(int side) const { return prefix + (side ? "finger_right" : "finger_left"); }
  std::string gripper_actuator() const { return prefix + "gripper"; }
};

/// The arm as an MJCF <body> tree whose base (link0) sits at p_WBase with orientation R_WBase
/// (the base's x axis is the arm's forward direction, z up). Joints start at zero, outside
/// joint 4's range: set a pose (SetArmJoints in ik.h) before simulating.
std::string WritePandaBody(const PandaNames& names, const Eigen::Vector3d& p_WBase,
                           const Eigen::Quaterniond& R_WBase);
/// The <equality> entries that couple the two fingers.
std::string WritePandaEqualities(const PandaNames& names);
/// The <actuator> entries: a position servo per joint and one for the gripper opening (metres
/// per finger, 0 closed to kPandaFingerTravel_m open).
std::string WritePandaActuators(const PandaNames& names);

/// X_BaseTcp: the tool centre point's pose in the base frame at joint angles q, from the DH
/// table alone (independent of MuJoCo).
Eigen::Isometry3d CalcPandaTcpPose(const PandaJointVector& q_rad);

}  // namespace prs::sim
