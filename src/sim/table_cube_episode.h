// Inside a Table-Cube episode (table_cube_controller.h): the world, the camera, the arm
// motions both variants of the controller share, and how an episode ends with an outcome.
// Internal to src/sim: table_cube_controller.cc runs the realistic variant, table_cube_paper.cc
// the original tool's.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "render/model_renderer.h"
#include "sim/motion.h"
#include "sim/table_cube_controller.h"
#include "sim/world.h"

namespace prs::sim::internal {

inline constexpr double kMove_s = 1.2;     // a move between two waypoints
inline constexpr double kDescend_s = 0.8;  // a short move down to or up from the cube

/// Thrown inside an episode to end it with an outcome.
struct EpisodeEnd {
  TaskOutcome outcome;
};

[[noreturn]] void End(std::string outcome, std::string detail);

/// The cube rests inside the tray: within its footprint, and below its walls' tops.
bool IsInTray(const exporting::Body& tray, const Eigen::Vector3d& p_cube_W);

struct Episode {
  const TableCubeOptions& options;
  World world;
  render::ModelRenderer* renderer = nullptr;
  int camera_id = -1;
  std::string cube = {};  // the cube's body name, for the classification only
  double last_sighting_error_m = 0;
  std::vector<std::pair<std::string, double>> metrics = {};
  std::vector<std::pair<std::string, bool>> flags = {};

  Eigen::Vector3d TrueCubePosition() const;
  const exporting::Body& CubeBody() const;

  /// Records a sighting's error against the true point it should have seen (the cube's centre
  /// or the centre of its top face) under `metric`.
  void RecordSightingError(const Eigen::Vector3d& p_seen_W, const Eigen::Vector3d& p_true_W,
                           const std::string& metric);

  /// A failure of the arm is the camera's fault when the cube was not where it was seen.
  [[noreturn]] void FailAfterSighting(std::string outcome, std::string detail) const;

  /// Joint angles for every waypoint at one grasp yaw, or a no-path ending naming the first
  /// waypoint no joint angles were found for.
  TcpPlan PlanOrFail(const WorldArm& arm, const std::vector<TcpWaypoint>& waypoints) const;

  /// Above the cube, down to it, grip, and up: planned together, so the grasp's yaw is one
  /// that reaches all three (any quarter turn grips a cube the same way). A poor-grip ending
  /// unless the cube rose at least half as far as the tool did from `p_grasp` to `p_rise`.
  void Pick(const WorldArm& arm, const Eigen::Vector3d& p_above, const Eigen::Vector3d& p_grasp,
            const Eigen::Vector3d& p_rise);

  /// Moves the tool to `p_W`, pointing down; a no-path ending naming `what` if no joint
  /// angles reach it.
  void MoveAboveOrFail(const WorldArm& arm, const Eigen::Vector3d& p_W, const std::string& what);
};

/// The two variants' tasks, run on a world that has two arms, a camera and a cube. They end
/// by returning (a success) or by throwing EpisodeEnd.
void RunRealisticTask(Episode& episode, TaskOutcome& outcome);
void RunPaperTask(Episode& episode, TaskOutcome& outcome);

}  // namespace prs::sim::internal
