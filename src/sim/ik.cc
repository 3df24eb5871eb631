// Damped-least-squares inverse kinematics for a Panda arm (see ik.h).
#include "sim/ik.h"

#include <algorithm>
#include <vector>

namespace prs::sim {

ArmIndex FindArm(const mjModel& model, const PandaNames& names) {
  ArmIndex arm;
  for (int i = 0; i < kPandaJoints; ++i) {
    const int joint = FindId(model, mjOBJ_JOINT, names.joint(i));
    arm.qpos_address[i] = model.jnt_qposadr[joint];
    arm.dof_address[i] = model.jnt_dofadr[joint];
    arm.actuator[i] = FindId(model, mjOBJ_ACTUATOR, names.actuator(i));
  }
  for (int side = 0; side < 2; ++side) {
    arm.finger_qpos_address[side] = model.jnt_qposadr[FindId(model, mjOBJ_JOINT, names.finger_joint(side))];
  }
  arm.tcp_site = FindId(model, mjOBJ_SITE, names.tcp_site());
  arm.gripper_actuator = FindId(model, mjOBJ_ACTUATOR, names.gripper_actuator());
  return arm;
}

void SetArmJoints(const mjModel& model, mjData& data, const ArmIndex& arm, const PandaJointVector& q_rad) {
  for (int i = 0; i < kPandaJoints; ++i) {
    data.qpos[arm.qpos_address[i]] = q_rad[i];
    data.qvel[arm.dof_address[i]] = 0;
    data.ctrl[arm.actuator[i]] = q_rad[i];
  }
  mj_kinematics(&model, &data);
  mj_comPos(&model, &data);
}

PandaJointVector GetArmJoints(const mjData& data, const ArmIndex& arm) {
  PandaJointVector q{};
  for (int i = 0; i < kPandaJoints; ++i) q[i] = data.qpos[arm.qpos_address[i]];
  return q;
}

Eigen::Isometry3d GetTcpPose(const mjData& data, const ArmIndex& arm) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Map<const Eigen::Vector3d>(data.site_xpos + 3 * arm.tcp_site);
  // MuJoCo stores rotation matrices row-major.
  X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data.site_xmat + 9 * arm.tcp_site);
  return X;
}

namespace {

// The 6D error [position; weighted rotation] from the current TCP pose to the target.
Eigen::Matrix<double, 6, 1> CalcPoseError(const Eigen::Isometry3d& X_WTcp, const Eigen::Isometry3d& X_WTarget,
                                          double rotation_weight_m) {
  Eigen::Matrix<double, 6, 1> e;
  e.head<3>() = X_WTarget.translation() - X_WTcp.translation();
  const Eigen::AngleAxisd R_error(X_WTarget.linear() * X_WTcp.linear().transpose());
  e.tail<3>() = rotation_weight_m * R_error.angle() * R_error.axis();
  return e;
}

}  // namespace

IkResult SolveArmIk(const mjModel& model, mjData& scratch, const ArmIndex& arm,
                    const Eigen::Isometry3d& X_WTarget, const PandaJointVector& q_start,
                    const IkOptions& options) {
  IkResult result;
  result.q_rad = q_start;
  std::vector<double> jacp(3 * model.nv), jacr(3 * model.nv);
  for (result.iterations = 0; result.iterations <= options.max_iterations; ++result.iterations) {
    SetArmJoints(model, scratch, arm, result.q_rad);
    const Eigen::Isometry3d X_WTcp = GetTcpPose(scratch, arm);
    const Eigen::Matrix<double, 6, 1> e = CalcPoseError(X_WTcp, X_WTarget, options.rotation_weight_m);
    result.position_error_m = e.head<3>().norm();
    result.rotation_error_rad = e.tail<3>().norm() / options.rotation_weight_m;
    if (result.position_error_m <= options.position_tolerance_m &&
        result.rotation_error_rad <= options.rotation_tolerance_rad) {
      result.converged = true;
      return result;
    }
    if (result.iterations == options.max_iterations) break;
    mj_jacSite(&model, &scratch, jacp.data(), jacr.data(), arm.tcp_site);
    Eigen::Matrix<double, 6, kPandaJoints> J;
    for (int i = 0; i < kPandaJoints; ++i) {
      const int dof = arm.dof_address[i];
      for (int r = 0; r < 3; ++r) {
        J(r, i) = jacp[r * model.nv + dof];  // MuJoCo's Jacobians are 3 x nv, row-major
        J(3 + r, i) = options.rotation_weight_m * jacr[r * model.nv + dof];
      }
    }
    const Eigen::Matrix<double, 6, 6> JJt =
        J * J.transpose() + options.damping * options.damping * Eigen::Matrix<double, 6, 6>::Identity();
    const Eigen::Matrix<double, kPandaJoints, 1> dq = J.transpose() * JJt.ldlt().solve(e);
    for (int i = 0; i < kPandaJoints; ++i) {
      const double step = std::clamp(dq[i], -options.max_step_rad, options.max_step_rad);
      result.q_rad[i] = std::clamp(result.q_rad[i] + step, kPandaLowerLimit_rad[i], kPandaUpperLimit_rad[i]);
    }
  }
  return result;
}

}  // namespace prs::sim
