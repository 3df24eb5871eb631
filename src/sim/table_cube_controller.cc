// The Table-Cube controller and its outcome classification (see table_cube_controller.h).
#include "sim/table_cube_controller.h"

#include <fmt/format.h>

#include <limits>
#include <optional>

#include "export/export.h"
#include "render/model_renderer.h"
#include "sim/control.h"
#include "sim/motion.h"
#include "sim/perception.h"

namespace prs::sim {

namespace {

constexpr double kApproachHeight_m = 0.12;  // above the cube before descending
constexpr double kLiftHeight_m = 0.15;
constexpr double kMove_s = 1.2;
constexpr double kDescend_s = 0.8;
// The ready pose turned to face backwards (joint 1 near its limit): the arm no longer reaches
// over the table.
PandaJointVector CalcClearViewPose() {
  PandaJointVector q = kPandaReadyPose_rad;
  q[0] = 2.8;
  return q;
}

// Thrown inside an episode to end it with an outcome.
struct EpisodeEnd {
  TaskOutcome outcome;
};

[[noreturn]] void End(std::string outcome, std::string detail) {
  throw EpisodeEnd{TaskOutcome{std::move(outcome), std::move(detail), {}}};
}

}  // namespace

struct TableCubeController::Episode {
  const TableCubeOptions& options;
  World world;
  render::ModelRenderer* renderer = nullptr;
  int camera_id = -1;
  std::string cube = {};  // the cube's body name, for the classification only
  double last_sighting_error_m = 0;
  std::vector<std::pair<std::string, double>> metrics = {};

  Eigen::Vector3d TrueCubePosition() const {
    return Eigen::Map<const Eigen::Vector3d>(world.data->xpos + 3 * world.body(cube));
  }

  // The cube's centre as the camera sees it, or a perception fault. `metric` names the
  // sighting's error in the outcome's metrics.
  Eigen::Vector3d See(const std::string& when, const std::string& metric) {
    if (options.clear_view_before_sighting) SetAllArms(CalcClearViewPose());
    render::DepthImage depth;
    const render::Image image = renderer->Render(*world.data, camera_id, &depth);
    const PinholeCamera camera = GetMujocoCamera(*world.model, *world.data, camera_id, image.width, image.height);
    const std::optional<ColorBlob> blob = FindLargestBlob(image, IsBluePixel);
    if (!blob) End("perception-fault", "no blue blob in the camera image " + when);
    const double d = MedianDepth(depth, *blob);
    const Eigen::Vector3d p_top = BackProject(camera, blob->centroid_px, d);
    const Eigen::Vector3d p_center = p_top - Eigen::Vector3d::UnitZ() * (options.cube_size_m / 2);
    last_sighting_error_m = (p_center - TrueCubePosition()).norm();
    metrics.emplace_back(metric, last_sighting_error_m);
    if (options.clear_view_before_sighting) SetAllArms(kPandaReadyPose_rad);
    return p_center;
  }

  void SetAllArms(const PandaJointVector& q_rad) {
    for (const WorldArm& arm : world.arms) MoveJointsTo(world, arm, q_rad, kMove_s);
  }

  // A failure of the arm is the camera's fault when the cube was not where it was seen.
  [[noreturn]] void FailAfterSighting(std::string outcome, std::string detail) {
    if (last_sighting_error_m > options.perception_tolerance_m) {
      End("perception-fault",
          fmt::format("the cube was seen {:.1f} cm from where it was (hidden or partly out of view), "
                      "so {}", 100 * last_sighting_error_m, detail));
    }
    End(std::move(outcome), std::move(detail));
  }

  const WorldArm& NearestArm(const Eigen::Vector3d& p_W, const WorldArm* except = nullptr) const {
    const WorldArm* best = nullptr;
    double best_distance = std::numeric_limits<double>::infinity();
    for (const WorldArm& arm : world.arms) {
      const double distance = (arm.X_WBase.translation() - p_W).head<2>().norm();
      if (&arm != except && distance < best_distance) best = &arm, best_distance = distance;
    }
    if (!best) End("no-path", "no arm is left to reach the cube");
    return *best;
  }

  // Joint angles for every waypoint at one grasp yaw, or a no-path ending naming the first
  // waypoint no joint angles were found for.
  TcpPlan PlanOrFail(const WorldArm& arm, const std::vector<TcpWaypoint>& waypoints) {
    TcpPlan plan = PlanDownwardPath(world, arm, waypoints);
    if (plan.failed >= 0) {
      FailAfterSighting("no-path", fmt::format("{} found no joint angles to {} ({:.1f} cm short)",
                                               arm.robot_name, waypoints[plan.failed].what,
                                               100 * plan.failure.position_error_m));
    }
    return plan;
  }

  // Above the cube, down to it, grip, and lift: planned together, so the grasp's yaw is one
  // that reaches all three (any quarter turn grips a cube the same way).
  void Pick(const WorldArm& arm, const Eigen::Vector3d& p_cube) {
    const double z_before = TrueCubePosition().z();
    const TcpPlan plan = PlanOrFail(arm, {{p_cube + Eigen::Vector3d(0, 0, kApproachHeight_m), "above the cube"},
                                          {p_cube, "the cube"},
                                          {p_cube + Eigen::Vector3d(0, 0, kLiftHeight_m), "lift the cube"}});
    MoveJointsTo(world, arm, plan.q[0], kMove_s);
    MoveJointsTo(world, arm, plan.q[1], kDescend_s);
    MoveGripper(world, arm, 0.0);
    MoveJointsTo(world, arm, plan.q[2], kDescend_s);
    const double lifted = TrueCubePosition().z() - z_before;
    if (lifted < kLiftHeight_m / 2) {
      FailAfterSighting("poor-grip", fmt::format("{} closed on the cube but lifted it only {:.1f} cm",
                                                 arm.robot_name, 100 * lifted));
    }
  }

  void Release(const WorldArm& arm, const Eigen::Vector3d& p_W) {
    const TcpPlan plan = PlanOrFail(arm, {{p_W + Eigen::Vector3d(0, 0, 0.1), "the put-down point"},
                                          {p_W, "the put-down point"},
                                          {p_W + Eigen::Vector3d(0, 0, 0.15), "away from the cube"}});
    MoveJointsTo(world, arm, plan.q[0], kMove_s);
    MoveJointsTo(world, arm, plan.q[1], kDescend_s);
    MoveGripper(world, arm, kPandaFingerTravel_m);
    MoveJointsTo(world, arm, plan.q[2], kDescend_s);
    MoveJointsTo(world, arm, kPandaReadyPose_rad, kMove_s);  // out of the camera's way
  }

  void MoveAboveOrFail(const WorldArm& arm, const Eigen::Vector3d& p_W, const std::string& what) {
    MoveJointsTo(world, arm, PlanOrFail(arm, {{p_W, what}}).q[0], kMove_s);
  }
};

TableCubeController::TableCubeController(TableCubeOptions options) : options_(options) {}
TableCubeController::~TableCubeController() = default;

namespace {

const exporting::Body* FindNearest(const exporting::ExportScene& scene, const std::string& class_name,
                                   const Eigen::Vector3d& p_W) {
  const exporting::Body* best = nullptr;
  for (const exporting::Body& b : scene.bodies) {
    if (b.class_name != class_name) continue;
    if (!best || (b.p_WO - p_W).head<2>().norm() < (best->p_WO - p_W).head<2>().norm()) best = &b;
  }
  return best;
}

// Where the first arm puts the cube down: on the table between the arms, 0.35 m ahead of them.
Eigen::Vector3d CalcHandoverPoint(const World& world, double cube_size_m) {
  Eigen::Vector3d p_mid = Eigen::Vector3d::Zero(), forward = Eigen::Vector3d::Zero();
  for (const WorldArm& arm : world.arms) {
    p_mid += arm.X_WBase.translation() / world.arms.size();
    forward += arm.X_WBase.linear().col(0);
  }
  // The arms' bases stand on the table (CalcArmMount), so p_mid is on its top.
  Eigen::Vector3d p = p_mid + 0.35 * Eigen::Vector3d(forward.x(), forward.y(), 0).normalized();
  p.z() += cube_size_m / 2 + 0.005;
  return p;
}

// The cube rests inside the tray: within its footprint, and below its walls' tops.
bool IsInTray(const exporting::Body& tray, const Eigen::Vector3d& p_cube_W) {
  const Eigen::Vector3d p_T = tray.R_WO.inverse() * (p_cube_W - tray.p_WO);
  return std::abs(p_T.x()) <= tray.size.x() / 2 && std::abs(p_T.y()) <= tray.size.y() / 2 &&
         p_T.z() > tray.size.z() / 2 && p_T.z() < tray.size.z() / 2 + kTrayWallHeight_m + 0.03;
}

}  // namespace

TaskOutcome TableCubeController::Run(const lang::Scene& scene) {
  std::optional<Episode> episode;
  try {
    episode.emplace(Episode{options_, BuildWorld(exporting::MakeExportScene(scene, "case study"))});
  } catch (const std::exception& e) {
    return {"world-error", e.what(), {}};
  }
  Episode& ep = *episode;
  World& world = ep.world;
  if (world.arms.size() < 2) return {"world-error", "the task needs two Robot objects", {}};
  if (world.model->ncam < 1) return {"no-camera", "the scene has no Camera object", {}};
  const exporting::Body* cube = world.FindFirst("Cube");
  if (!cube) return {"no-cube", "the scene has no Cube object", {}};
  ep.cube = cube->name;
  ep.camera_id = 0;
  if (!renderer_) {
    renderer_ = std::make_unique<render::ModelRenderer>(options_.image_width, options_.image_height);
  }
  renderer_->SetModel(*world.model);
  ep.renderer = renderer_.get();

  TaskOutcome outcome{"success", "", {}};
  try {
    SimulateFor(*world.model, *world.data, world.arm_indices(), 0.3);
    const Eigen::Vector3d p_seen = ep.See("at the start", "sighting_error_start_m");
    const WorldArm& first = ep.NearestArm(p_seen);
    ep.Pick(first, p_seen);
    const Eigen::Vector3d p_handover = CalcHandoverPoint(world, options_.cube_size_m);
    ep.Release(first, p_handover);
    const double slip = (ep.TrueCubePosition() - p_handover).head<2>().norm();
    if (slip > 0.05) {
      End("poor-grip", fmt::format("the cube came down {:.1f} cm from the hand-over point", 100 * slip));
    }
    const Eigen::Vector3d p_seen_again = ep.See("after the hand-over", "sighting_error_handover_m");
    const WorldArm& second = ep.NearestArm(p_seen_again, &first);
    ep.Pick(second, p_seen_again);
    const exporting::Body* tray = FindNearest(world.scene, "Tray", second.X_WBase.translation());
    if (!tray) End("missed-tray", "the scene has no tray to drop the cube into");
    const Eigen::Vector3d p_drop = tray->p_WO + Eigen::Vector3d(0, 0, tray->size.z() / 2 + 0.1);
    ep.MoveAboveOrFail(second, p_drop, "above the destination tray");
    MoveGripper(world, second, kPandaFingerTravel_m, 1.0);
    if (!IsInTray(*tray, ep.TrueCubePosition())) {
      End("missed-tray", fmt::format("the cube ended outside {} after the drop", tray->name));
    }
    outcome.detail = fmt::format("the cube rests in {}", tray->name);
  } catch (EpisodeEnd& end) {
    outcome = std::move(end.outcome);
  }
  outcome.metrics = std::move(ep.metrics);
  const Eigen::Vector3d p_end = ep.TrueCubePosition();
  outcome.metrics.emplace_back("cube_final_x_m", p_end.x());
  outcome.metrics.emplace_back("cube_final_y_m", p_end.y());
  outcome.metrics.emplace_back("cube_final_z_m", p_end.z());
  outcome.metrics.emplace_back("simulated_s", world.data->time);
  return outcome;
}

}  // namespace prs::sim
