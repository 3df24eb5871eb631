// Arm motions for the controller: plan top-down tool paths (inverse kinematics for every
// waypoint at one grasp yaw), move the joints there (servo targets interpolated in joint space
// while the world is simulated), and open or close the gripper. Every motion simulates the
// whole world, so contacts happen as they would.
#pragma once

#include <string>
#include <vector>

#include "kinematics/ik.h"
#include "sim/world.h"

namespace prs::sim {

/// The tool pointing straight down, fingers closing along world x rotated by `yaw_rad`.
Eigen::Matrix3d CalcDownwardGrasp(double yaw_rad);

/// A tool position of a planned top-down motion, and what it is for (in messages).
struct TcpWaypoint {
  Eigen::Vector3d p_W;
  std::string what;  // "above the cube"
};

/// Joint angles for each waypoint of a top-down path, or the waypoint none were found for.
struct TcpPlan {
  std::vector<PandaJointVector> q;  // one per waypoint when the plan succeeded
  int failed = -1;                  // the first waypoint without joint angles, or -1
  kinematics::IkResult failure;     // the nearest attempt at it
  double yaw_rad = 0;               // the grasp's turn about the vertical
};

/// Plans a path through `waypoints` with the tool pointing down at one yaw for the whole path,
/// each waypoint solved from the previous one's joint angles and the first from the arm's
/// current servo targets (kinematics::SolveIk in the arm's base frame, to 2 mm and 0.02 rad).
/// The yaws 0, π/2, −π/2 and π are tried in turn (a cube's faces are a quarter turn apart, so
/// each is the same grasp), then each again from `restarts` deterministic random starts.
/// Returns the first plan that reaches every waypoint, else the one that got furthest.
TcpPlan PlanDownwardPath(const World& world, const WorldArm& arm,
                         const std::vector<TcpWaypoint>& waypoints, int restarts = 8);

/// Moves the arm's joints to q over `duration_s` and settles.
void MoveJointsTo(World& world, const WorldArm& arm, const PandaJointVector& q_rad, double duration_s);

/// Sets the gripper's target opening and simulates `duration_s` for the fingers to get there.
void MoveGripper(World& world, const WorldArm& arm, double opening_m, double duration_s = 0.6);

}  // namespace prs::sim
