// Arm motions for the controller: move the tool centre point to a pose (inverse kinematics,
// then servo targets interpolated in joint space while the world is simulated), and open or
// close the gripper. Every motion simulates the whole world, so contacts happen as they would.
#pragma once

#include "kinematics/ik.h"
#include "sim/world.h"

namespace prs::sim {

/// The tool pointing straight down, fingers closing along world x rotated by `yaw_rad`.
Eigen::Matrix3d CalcDownwardGrasp(double yaw_rad);

/// Solves IK for X_WTarget (kinematics::SolveIk on the Panda's chain, in the arm's base frame:
/// X_BaseTarget = X_WBase⁻¹·X_WTarget) from the arm's current servo targets, to 2 mm and
/// 0.02 rad; when it converges, moves there over `duration_s` (smooth joint interpolation) and
/// lets the arm settle for 0.2 s. Returns the IK result: converged false means the arm did not
/// move (no path to the target).
kinematics::IkResult MoveTcpTo(World& world, const WorldArm& arm,
                               const Eigen::Isometry3d& X_WTarget, double duration_s);

/// Moves the arm's joints to q over `duration_s` and settles.
void MoveJointsTo(World& world, const WorldArm& arm, const PandaJointVector& q_rad, double duration_s);

/// Sets the gripper's target opening and simulates `duration_s` for the fingers to get there.
void MoveGripper(World& world, const WorldArm& arm, double opening_m, double duration_s = 0.6);

}  // namespace prs::sim
