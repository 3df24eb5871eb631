// Arm motions (see motion.h).
#include "sim/motion.h"

#include <cmath>
#include <numbers>

#include "sim/control.h"

namespace prs::sim {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kSettle_s = 0.2;
}  // namespace

Eigen::Matrix3d CalcDownwardGrasp(double yaw_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

void MoveJointsTo(World& world, const WorldArm& arm, const PandaJointVector& q_goal, double duration_s) {
  const mjModel& model = *world.model;
  mjData& data = *world.data;
  PandaJointVector q_start;
  for (int i = 0; i < kPandaJoints; ++i) q_start[i] = data.ctrl[arm.index.actuator[i]];
  const std::vector<ArmIndex> arms = world.arm_indices();
  const int steps = std::max(1, static_cast<int>(std::ceil(duration_s / model.opt.timestep)));
  for (int k = 1; k <= steps; ++k) {
    // Smoothstep in time: no jerk at the start or end of the motion.
    const double t = static_cast<double>(k) / steps, s = t * t * (3 - 2 * t);
    for (int i = 0; i < kPandaJoints; ++i) {
      data.ctrl[arm.index.actuator[i]] = q_start[i] + s * (q_goal[i] - q_start[i]);
    }
    StepWorld(model, data, arms);
  }
  SimulateFor(model, data, arms, kSettle_s);
}

kinematics::IkResult MoveTcpTo(World& world, const WorldArm& arm,
                               const Eigen::Isometry3d& X_WTarget, double duration_s) {
  static const kinematics::Chain panda = kinematics::MakePandaChain();
  PandaJointVector q_now;
  for (int i = 0; i < kPandaJoints; ++i) q_now[i] = world.data->ctrl[arm.index.actuator[i]];
  // The defaults are the tolerances and steps the simulator has always used: 2 mm, 0.02 rad,
  // damping 0.05, 300 iterations, 0.2 rad per joint per step.
  const kinematics::IkTarget target = kinematics::MakePoseTarget(arm.X_WBase.inverse() * X_WTarget);
  const kinematics::IkResult ik = kinematics::SolveIk(panda, target, kinematics::ToVector(q_now));
  if (ik.converged) MoveJointsTo(world, arm, kinematics::ToPandaJoints(ik.q), duration_s);
  return ik;
}

void MoveGripper(World& world, const WorldArm& arm, double opening_m, double duration_s) {
  SetGripper(*world.data, arm.index, opening_m);
  SimulateFor(*world.model, *world.data, world.arm_indices(), duration_s);
}

}  // namespace prs::sim
