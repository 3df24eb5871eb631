// The Franka Emika Panda arm for the simulated case study, written as an MJCF body tree built
// from simple shapes, with a two-finger parallel gripper that grasps by friction. Its
// kinematics (DH table, limits, tool centre point) are kinematics/panda.h's.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "kinematics/panda.h"

namespace prs::sim {

using kinematics::CalcPandaTcpPose;
using kinematics::kPandaDh;
using kinematics::kPandaFingerTravel_m;
using kinematics::kPandaFlangeToTcp_m;
using kinematics::kPandaJoints;
using kinematics::kPandaLowerLimit_rad;
using kinematics::kPandaReadyPose_rad;
using kinematics::kPandaUpperLimit_rad;
using kinematics::PandaDhRow;
using kinematics::PandaJointVector;

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

}  // namespace prs::sim
