// Inverse kinematics for one Panda arm in a MuJoCo model: damped least squares on MuJoCo's
// Jacobian of the tool centre point, within the joint limits. The controller's only way to
// move the arm to a pose it computed (it never reads the true object poses).
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

struct IkOptions {
  int max_iterations = 300;
  double damping = 0.05;                  // λ of (J Jᵀ + λ² I)
  double position_tolerance_m = 0.002;
  double rotation_tolerance_rad = 0.02;
  double rotation_weight_m = 0.2;         // metres of position error worth one radian
  double max_step_rad = 0.2;              // per joint per iteration
};

struct IkResult {
  PandaJointVector q_rad{};
  double position_error_m = 0;
  double rotation_error_rad = 0;
  int iterations = 0;
  bool converged = false;
};

/// Joint angles that put the tool centre point at X_WTarget, starting from q_start and staying
/// within the joint limits. `scratch` is overwritten (pass a copy of the live state's data).
/// converged is false when the tolerances were not met (the target is out of reach, or too
/// close to the base): the caller reports "no path".
IkResult SolveArmIk(const mjModel& model, mjData& scratch, const ArmIndex& arm,
                    const Eigen::Isometry3d& X_WTarget, const PandaJointVector& q_start,
                    const IkOptions& options = {});

}  // namespace prs::sim
