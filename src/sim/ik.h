// One Panda arm in a MuJoCo model: where its joints, servos and tool centre point live, and
// setting and reading its joints. Inverse kinematics is kinematics/ik.h's, on the arm's chain
// (motion.h's PlanDownwardPath), independent of MuJoCo.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "sim/mujoco_model.h"
#include "sim/panda.h"

namespace prs::sim {

/// Where one arm's joints and tool centre point live in a model.
struct ArmIndex {
  std::array<int, kPandaJoints> qpos_address{};
  std::array<int, kPandaJoints> dof_address{};
  std::array<int, kPandaJoints> actuator{};
  int tcp_site = -1;
  int gripper_actuator = -1;
  std::array<int, 2> finger_qpos_address{};
};

/// Looks up an arm's elements by name. Throws std::out_of_range if one is missing.
ArmIndex FindArm(const mjModel& model, const PandaNames& names);

/// Sets the arm's joint angles in `data` (and its servos' targets to hold them) and updates the
/// kinematics.
void SetArmJoints(const mjModel& model, mjData& data, const ArmIndex& arm, const PandaJointVector& q_rad);
PandaJointVector GetArmJoints(const mjData& data, const ArmIndex& arm);

/// X_WTcp: the tool centre point's world pose in `data` (after kinematics).
Eigen::Isometry3d GetTcpPose(const mjData& data, const ArmIndex& arm);

}  // namespace prs::sim
