// The Table-Cube controller: the episode's set-up and classification, and the realistic
// variant's task (see table_cube_controller.h; the original tool's is table_cube_paper.cc).
#include "sim/table_cube_controller.h"

#include <fmt/format.h>

#include <limits>
#include <optional>

#include "export/export.h"
#include "render/model_renderer.h"
#include "sim/control.h"
#include "sim/motion.h"
#include "sim/perception.h"
#include "sim/table_cube_episode.h"

namespace prs::sim {

using internal::End;
using internal::Episode;
using internal::EpisodeEnd;

namespace {

constexpr double kApproachHeight_m = 0.12;  // above the cube before descending
constexpr double kLiftHeight_m = 0.15;

// The ready pose turned to face backwards (joint 1 near its limit): the arm no longer reaches
// over the table.
PandaJointVector CalcClearViewPose() {
  PandaJointVector q = kPandaReadyPose_rad;
  q[0] = 2.8;
  return q;
}

void SetAllArms(Episode& ep, const PandaJointVector& q_rad) {
  for (const WorldArm& arm : ep.world.arms) MoveJointsTo(ep.world, arm, q_rad, internal::kMove_s);
}

constexpr const char* kHandoverMetric = "sighting_error_handover_m";

// The cube's centre as the options' perception answers `request`: an ending when it has none,
// or when the answer is off the table's top (the arm is never sent there).
Eigen::Vector3d AskPerception(Episode& ep, const CubeSightingRequest& request,
                              const std::string& when) {
  CubeSightingAnswer answer = ep.options.perception(request);
  if (!answer.p_WCube) {
    End(answer.outcome.empty() ? "perception-fault" : answer.outcome,
        fmt::format("the perception found no cube {}: {}", when, answer.detail));
  }
  const Eigen::Vector3d p = *answer.p_WCube;
  const exporting::Body* table = ep.world.FindFirst("Table");
  if (table) {
    const Eigen::Vector3d offset = table->R_WO.conjugate() * (p - table->p_WO);
    const double above_top_m = offset.z() - table->size.z() / 2;
    const bool over =
        std::abs(offset.x()) <= table->size.x() / 2 && std::abs(offset.y()) <= table->size.y() / 2;
    if (!over || above_top_m < -ep.options.cube_size_m || above_top_m > kMaxAboveTable_m) {
      End("perception-fault",
          fmt::format(
              "the perception placed the cube {} at ({:.3f}, {:.3f}, {:.3f}) m, off the "
              "table's top ({})",
              when, p.x(), p.y(), p.z(),
              over ? fmt::format("{:.3f} m above it", above_top_m) : "outside its footprint"));
    }
  }
  return p;
}

// The cube's centre as the camera sees it in its full image (by the options' perception when
// there is one), or a perception fault. `metric` names the sighting's error in the outcome's
// metrics.
Eigen::Vector3d SeeBlueBlob(Episode& ep, const std::string& when, const std::string& metric) {
  const TableCubeOptions& options = ep.options;
  if (options.clear_view_before_sighting) SetAllArms(ep, CalcClearViewPose());
  render::DepthImage depth;
  const render::Image image = ep.renderer->Render(*ep.world.data, ep.camera_id, &depth);
  const PinholeCamera camera =
      GetMujocoCamera(*ep.world.model, *ep.world.data, ep.camera_id, image.width, image.height);
  Eigen::Vector3d p_center;
  if (options.perception) {
    p_center = AskPerception(ep, {image, depth, camera, metric == kHandoverMetric}, when);
  } else {
    const std::optional<ColorBlob> blob = FindLargestBlob(image, IsBluePixel);
    if (!blob) End("perception-fault", "no blue blob in the camera image " + when);
    const double d = MedianDepth(depth, *blob);
    const Eigen::Vector3d p_top = BackProject(camera, blob->centroid_px, d);
    p_center = p_top - Eigen::Vector3d::UnitZ() * (options.cube_size_m / 2);
  }
  ep.RecordSightingError(p_center, ep.TrueCubePosition(), metric);
  if (options.clear_view_before_sighting) SetAllArms(ep, kPandaReadyPose_rad);
  return p_center;
}

const WorldArm& NearestArm(const Episode& ep, const Eigen::Vector3d& p_W,
                           const WorldArm* except = nullptr) {
  const WorldArm* best = nullptr;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const WorldArm& arm : ep.world.arms) {
    const double distance = (arm.X_WBase.translation() - p_W).head<2>().norm();
    if (&arm != except && distance < best_distance) best = &arm, best_distance = distance;
  }
  if (!best) End("no-path", "no arm is left to reach the cube");
  return *best;
}

void Release(Episode& ep, const WorldArm& arm, const Eigen::Vector3d& p_W) {
  const TcpPlan plan =
      ep.PlanOrFail(arm, {{p_W + Eigen::Vector3d(0, 0, 0.1), "the put-down point"},
                          {p_W, "the put-down point"},
                          {p_W + Eigen::Vector3d(0, 0, 0.15), "away from the cube"}});
  MoveJointsTo(ep.world, arm, plan.q[0], internal::kMove_s);
  MoveJointsTo(ep.world, arm, plan.q[1], internal::kDescend_s);
  MoveGripper(ep.world, arm, kPandaFingerTravel_m);
  MoveJointsTo(ep.world, arm, plan.q[2], internal::kDescend_s);
  MoveJointsTo(ep.world, arm, kPandaReadyPose_rad, internal::kMove_s);  // out of the camera's way
}

const exporting::Body* FindNearest(const exporting::ExportScene& scene,
                                   const std::string& class_name, const Eigen::Vector3d& p_W) {
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

void PickCube(Episode& ep, const WorldArm& arm, const Eigen::Vector3d& p_cube) {
  ep.Pick(arm, p_cube + Eigen::Vector3d(0, 0, kApproachHeight_m), p_cube,
          p_cube + Eigen::Vector3d(0, 0, kLiftHeight_m));
}

}  // namespace

namespace internal {

void RunRealisticTask(Episode& ep, TaskOutcome& outcome) {
  World& world = ep.world;
  const Eigen::Vector3d p_seen = SeeBlueBlob(ep, "at the start", "sighting_error_start_m");
  const WorldArm& first = NearestArm(ep, p_seen);
  PickCube(ep, first, p_seen);
  const Eigen::Vector3d p_handover = CalcHandoverPoint(world, ep.options.cube_size_m);
  Release(ep, first, p_handover);
  const double slip = (ep.TrueCubePosition() - p_handover).head<2>().norm();
  if (slip > 0.05) {
    End("poor-grip",
        fmt::format("the cube came down {:.1f} cm from the hand-over point", 100 * slip));
  }
  const Eigen::Vector3d p_seen_again = SeeBlueBlob(ep, "after the hand-over", kHandoverMetric);
  const WorldArm& second = NearestArm(ep, p_seen_again, &first);
  PickCube(ep, second, p_seen_again);
  const exporting::Body* tray = FindNearest(world.scene, "Tray", second.X_WBase.translation());
  if (!tray) End("missed-tray", "the scene has no tray to drop the cube into");
  const Eigen::Vector3d p_drop = tray->p_WO + Eigen::Vector3d(0, 0, tray->size.z() / 2 + 0.1);
  ep.MoveAboveOrFail(second, p_drop, "above the destination tray");
  MoveGripper(world, second, kPandaFingerTravel_m, 1.0);
  if (!IsInTray(*tray, ep.TrueCubePosition())) {
    End("missed-tray", fmt::format("the cube ended outside {} after the drop", tray->name));
  }
  outcome.detail = fmt::format("the cube rests in {}", tray->name);
}

}  // namespace internal

TableCubeOptions MakePaperTableCubeOptions() {
  TableCubeOptions options;
  options.variant = TableCubeVariant::kPaper;
  options.image_width = options.image_height = 256;
  options.default_fovy_deg = 60;
  return options;
}

TableCubeController::TableCubeController(TableCubeOptions options) : options_(options) {}
TableCubeController::~TableCubeController() = default;

namespace {

// The scene as the simulation builds it: the cube made free if it has no mass (a warning in
// `warnings`, its mass in `metrics`), a camera without a field of view given the options'.
exporting::ExportScene PrepareScene(const lang::Scene& scene, const TableCubeOptions& options,
                                    TaskOutcome& outcome) {
  exporting::ExportScene exported = exporting::MakeExportScene(scene, "case study");
  bool cube_seen = false;
  for (size_t i = 0; i < exported.bodies.size(); ++i) {  // one body per object, in order
    exporting::Body& body = exported.bodies[i];
    if (body.class_name == "Camera" && options.default_fovy_deg &&
        !scene.objects[i].FindProperty("fovy_deg")) {
      body.fovy_deg = *options.default_fovy_deg;
    }
    if (body.class_name != "Cube" || cube_seen) continue;
    cube_seen = true;
    if (std::optional<std::string> warning = MakePickTargetFree(body)) {
      outcome.warnings.push_back(std::move(*warning));
      outcome.flags.emplace_back("cube_mass_assumed", true);
    }
    outcome.metrics.emplace_back("cube_mass_kg", body.mass_kg);
  }
  return exported;
}

}  // namespace

TaskOutcome TableCubeController::Run(const lang::Scene& scene) {
  TaskOutcome setup;
  std::optional<Episode> episode;
  try {
    episode.emplace(Episode{options_, BuildWorld(PrepareScene(scene, options_, setup))});
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
    renderer_ =
        std::make_unique<render::ModelRenderer>(options_.image_width, options_.image_height);
  }
  renderer_->SetModel(*world.model);
  ep.renderer = renderer_.get();

  TaskOutcome outcome{"success", "", {}};
  try {
    SimulateFor(*world.model, *world.data, world.arm_indices(), 0.3);
    if (options_.variant == TableCubeVariant::kPaper) {
      internal::RunPaperTask(ep, outcome);
    } else {
      internal::RunRealisticTask(ep, outcome);
    }
  } catch (EpisodeEnd& end) {
    outcome = std::move(end.outcome);
  }
  outcome.metrics = std::move(setup.metrics);
  outcome.metrics.insert(outcome.metrics.end(), ep.metrics.begin(), ep.metrics.end());
  const Eigen::Vector3d p_end = ep.TrueCubePosition();
  outcome.metrics.emplace_back("cube_final_x_m", p_end.x());
  outcome.metrics.emplace_back("cube_final_y_m", p_end.y());
  outcome.metrics.emplace_back("cube_final_z_m", p_end.z());
  outcome.metrics.emplace_back("simulated_s", world.data->time);
  outcome.flags = std::move(setup.flags);
  outcome.flags.insert(outcome.flags.end(), ep.flags.begin(), ep.flags.end());
  outcome.warnings = std::move(setup.warnings);
  return outcome;
}

}  // namespace prs::sim
