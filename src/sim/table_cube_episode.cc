// What both Table-Cube controllers do inside an episode (see table_cube_episode.h).
#include "sim/table_cube_episode.h"

#include <fmt/format.h>

namespace prs::sim::internal {

[[noreturn]] void End(std::string outcome, std::string detail) {
  throw EpisodeEnd{TaskOutcome{std::move(outcome), std::move(detail), {}}};
}

bool IsInTray(const exporting::Body& tray, const Eigen::Vector3d& p_cube_W) {
  const Eigen::Vector3d p_T = tray.R_WO.inverse() * (p_cube_W - tray.p_WO);
  return std::abs(p_T.x()) <= tray.size.x() / 2 && std::abs(p_T.y()) <= tray.size.y() / 2 &&
         p_T.z() > tray.size.z() / 2 && p_T.z() < tray.size.z() / 2 + kTrayWallHeight_m + 0.03;
}

Eigen::Vector3d Episode::TrueCubePosition() const {
  return Eigen::Map<const Eigen::Vector3d>(world.data->xpos + 3 * world.body(cube));
}

const exporting::Body& Episode::CubeBody() const {
  for (const exporting::Body& b : world.scene.bodies) {
    if (b.name == cube) return b;
  }
  throw std::logic_error("the episode's cube " + cube + " is not in its world");
}

void Episode::RecordSightingError(const Eigen::Vector3d& p_seen_W, const Eigen::Vector3d& p_true_W,
                                  const std::string& metric) {
  last_sighting_error_m = (p_seen_W - p_true_W).norm();
  metrics.emplace_back(metric, last_sighting_error_m);
}

void Episode::FailAfterSighting(std::string outcome, std::string detail) const {
  if (last_sighting_error_m > options.perception_tolerance_m) {
    End("perception-fault",
        fmt::format("the cube was seen {:.1f} cm from where it was (hidden or partly out of view), "
                    "so {}",
                    100 * last_sighting_error_m, detail));
  }
  End(std::move(outcome), std::move(detail));
}

TcpPlan Episode::PlanOrFail(const WorldArm& arm, const std::vector<TcpWaypoint>& waypoints) const {
  TcpPlan plan = PlanDownwardPath(world, arm, waypoints);
  if (plan.failed >= 0) {
    FailAfterSighting(
        "no-path", fmt::format("{} found no joint angles to {} ({:.1f} cm short)", arm.robot_name,
                               waypoints[plan.failed].what, 100 * plan.failure.position_error_m));
  }
  return plan;
}

void Episode::Pick(const WorldArm& arm, const Eigen::Vector3d& p_above,
                   const Eigen::Vector3d& p_grasp, const Eigen::Vector3d& p_rise) {
  const double z_before = TrueCubePosition().z();
  const TcpPlan plan = PlanOrFail(
      arm, {{p_above, "above the cube"}, {p_grasp, "the cube"}, {p_rise, "lift the cube"}});
  MoveJointsTo(world, arm, plan.q[0], kMove_s);
  MoveJointsTo(world, arm, plan.q[1], kDescend_s);
  MoveGripper(world, arm, 0.0);
  MoveJointsTo(world, arm, plan.q[2], kDescend_s);
  const double lifted = TrueCubePosition().z() - z_before;
  if (lifted < (p_rise.z() - p_grasp.z()) / 2) {
    FailAfterSighting("poor-grip", fmt::format("{} closed on the cube but lifted it only {:.1f} cm",
                                               arm.robot_name, 100 * lifted));
  }
}

void Episode::MoveAboveOrFail(const WorldArm& arm, const Eigen::Vector3d& p_W,
                              const std::string& what) {
  MoveJointsTo(world, arm, PlanOrFail(arm, {{p_W, what}}).q[0], kMove_s);
}

}  // namespace prs::sim::internal
