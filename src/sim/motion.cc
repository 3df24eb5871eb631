// Arm motions (see motion.h).
#include "sim/motion.h"

#include <cmath>
#include <numbers>
#include <optional>

#include "sim/control.h"

namespace prs::sim {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kSettle_s = 0.2;
// The gripper's target moves from open to closed over this time (0.2 m/s per finger), as a
// real gripper's fingers move at a finite speed. Set at once, it slammed the fingers into the
// cube; with the soft finger contacts of before (panda.cc), a light cube squirted out.
constexpr double kGripperRamp_s = 0.2;
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

namespace {

// The waypoints at one yaw, the first from q_start (after `restarts` random starts if needed).
TcpPlan PlanAtYaw(const WorldArm& arm, const std::vector<TcpWaypoint>& waypoints, double yaw,
                  const PandaJointVector& q_start, int restarts) {
  static const kinematics::Chain panda = kinematics::MakePandaChain();
  TcpPlan plan;
  plan.yaw_rad = yaw;
  Eigen::VectorXd q = kinematics::ToVector(q_start);
  for (size_t i = 0; i < waypoints.size(); ++i) {
    Eigen::Isometry3d X_WTarget = Eigen::Isometry3d::Identity();
    X_WTarget.translation() = waypoints[i].p_W;
    X_WTarget.linear() = CalcDownwardGrasp(yaw);
    const kinematics::IkTarget target = kinematics::MakePoseTarget(arm.X_WBase.inverse() * X_WTarget);
    const kinematics::IkResult ik =
        i == 0 && restarts > 0
            ? kinematics::SolveIkWithRestarts(panda, target, q, {}, restarts, /*seed=*/1)
            : kinematics::SolveIk(panda, target, q);
    if (!ik.converged) {
      plan.failed = static_cast<int>(i);
      plan.failure = ik;
      return plan;
    }
    q = ik.q;
    plan.q.push_back(kinematics::ToPandaJoints(q));
  }
  return plan;
}

}  // namespace

TcpPlan PlanDownwardPath(const World& world, const WorldArm& arm,
                         const std::vector<TcpWaypoint>& waypoints, int restarts) {
  PandaJointVector q_now;
  for (int i = 0; i < kPandaJoints; ++i) q_now[i] = world.data->ctrl[arm.index.actuator[i]];
  std::optional<TcpPlan> best;
  for (int tries : {0, restarts}) {
    for (double yaw : {0.0, kPi / 2, -kPi / 2, kPi}) {
      TcpPlan plan = PlanAtYaw(arm, waypoints, yaw, q_now, tries);
      if (plan.failed < 0) return plan;
      const bool further = !best || plan.failed > best->failed ||
                           (plan.failed == best->failed &&
                            plan.failure.position_error_m < best->failure.position_error_m);
      if (further) best = std::move(plan);
    }
    if (restarts <= 0) break;
  }
  return *best;
}

void MoveGripper(World& world, const WorldArm& arm, double opening_m, double duration_s) {
  const mjModel& model = *world.model;
  mjData& data = *world.data;
  const std::vector<ArmIndex> arms = world.arm_indices();
  const double from_m = data.ctrl[arm.index.gripper_actuator];
  const int steps = std::max(1, static_cast<int>(std::ceil(kGripperRamp_s / model.opt.timestep)));
  for (int k = 1; k <= steps; ++k) {
    SetGripper(data, arm.index, from_m + (opening_m - from_m) * k / steps);
    StepWorld(model, data, arms);
  }
  SimulateFor(model, data, arms, std::max(0.0, duration_s - kGripperRamp_s));
}

}  // namespace prs::sim
