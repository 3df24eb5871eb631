// One Panda arm's elements in a MuJoCo model (see ik.h).
#include "sim/ik.h"

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

}  // namespace prs::sim
