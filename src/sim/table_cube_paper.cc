// The original tool's Table-Cube controller (the paper's case study, its coppeliaTest.py), on
// our arms and motions: the cube seen alone by the depth camera (paper_perception.h), the
// first Robot grasps 2.1 cm below the point seen, rises 0.1 m, drops the cube from 0.2 m above
// the trays' midpoint and moves 0.45 m away along −x; the second Robot grasps it from a new
// estimate and opens 0.1 m above the second tray's top. Success is the paper's criterion.
#include <fmt/format.h>

#include "sim/control.h"
#include "sim/paper_perception.h"
#include "sim/table_cube_episode.h"

namespace prs::sim::internal {

namespace {

constexpr double kGraspBelowSeen_m = 0.021;    // the original's z offset of the grasp
constexpr double kRiseAboveSeen_m = 0.1;       // ... of the rise after it
constexpr double kApproachAboveSeen_m = 0.12;  // ours: above the cube first (see Pick)
constexpr double kDropAboveTrays_m = 0.2;      // the first arm opens this high over the trays
constexpr double kMoveAway_m = 0.45;           // ... then moves this far along −x
constexpr double kDropAboveTray_m = 0.1;       // the second opens this high over its tray's top
constexpr double kSuccessReach_m = 0.453;      // success: within this of the tray in x and in y
constexpr double kHandoverReach_m = 0.1;       // ours: the dropped cube lands within this

// The point on the cube the camera sees (the centre of its top face, seen from above) as the
// original estimated it, or a perception fault.
Eigen::Vector3d SeeCubeAlone(Episode& ep, const std::string& when, const std::string& metric) {
  render::DepthImage depth;
  ep.renderer->Render(*ep.world.data, ep.camera_id, &depth, ep.world.body(ep.cube));
  MaskCamera camera;
  camera.X_WC.translation() =
      Eigen::Map<const Eigen::Vector3d>(ep.world.data->cam_xpos + 3 * ep.camera_id);
  camera.X_WC.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
      ep.world.data->cam_xmat + 9 * ep.camera_id);
  const render::ModelRenderer::ClippingPlanes planes = ep.renderer->GetClippingPlanes();
  camera.near_m = planes.near_m;
  camera.far_m = planes.far_m;
  camera.perspective_angle_rad = ep.world.model->cam_fovy[ep.camera_id] * M_PI / 180;
  const std::optional<MaskEstimate> estimate = EstimateFromMask(depth, camera);
  if (!estimate) End("perception-fault", "the cube is not in the camera image " + when);
  const Eigen::Vector3d p_top_true =
      ep.TrueCubePosition() + Eigen::Vector3d(0, 0, ep.CubeBody().size.z() / 2);
  ep.RecordSightingError(estimate->p_W, p_top_true, metric);
  return estimate->p_W;
}

const exporting::Body* FindNth(const exporting::ExportScene& scene, const std::string& class_name,
                               int n) {
  for (const exporting::Body& b : scene.bodies) {
    if (b.class_name == class_name && n-- == 0) return &b;
  }
  return nullptr;
}

// Grasps at the original's offsets below and above the point seen.
void PickSeen(Episode& ep, const WorldArm& arm, const Eigen::Vector3d& p_seen) {
  ep.Pick(arm, p_seen + Eigen::Vector3d(0, 0, kApproachAboveSeen_m),
          p_seen - Eigen::Vector3d(0, 0, kGraspBelowSeen_m),
          p_seen + Eigen::Vector3d(0, 0, kRiseAboveSeen_m));
}

}  // namespace

void RunPaperTask(Episode& ep, TaskOutcome& outcome) {
  World& world = ep.world;
  const exporting::Body* tray_1 = FindNth(world.scene, "Tray", 0);
  const exporting::Body* tray_2 = FindNth(world.scene, "Tray", 1);
  if (!tray_2) End("missed-tray", "the task needs two Tray objects");
  const WorldArm& first = world.arms[0];
  const WorldArm& second = world.arms[1];

  PickSeen(ep, first, SeeCubeAlone(ep, "at the start", "sighting_error_start_m"));
  const Eigen::Vector3d p_release =
      (tray_1->p_WO + tray_2->p_WO) / 2 + Eigen::Vector3d(0, 0, kDropAboveTrays_m);
  ep.MoveAboveOrFail(first, p_release, "above the trays' midpoint");
  MoveGripper(world, first, kPandaFingerTravel_m);
  ep.MoveAboveOrFail(first, p_release - Eigen::Vector3d(kMoveAway_m, 0, 0),
                     "away from the trays' midpoint");
  // A cube that slipped out on the way, or bounced far, was not handed over well: when the
  // second arm then fails, the failure is the first grip's (the original went on regardless).
  const double landed_m = (ep.TrueCubePosition() - p_release).head<2>().norm();
  ep.metrics.emplace_back("handover_offset_m", landed_m);
  try {
    PickSeen(ep, second, SeeCubeAlone(ep, "after the hand-over", "sighting_error_handover_m"));
    const Eigen::Vector3d p_tray_top = tray_2->p_WO + Eigen::Vector3d(0, 0, tray_2->size.z() / 2);
    ep.MoveAboveOrFail(second, p_tray_top + Eigen::Vector3d(0, 0, kDropAboveTray_m),
                       "above the destination tray");
  } catch (EpisodeEnd& end) {
    if (landed_m <= kHandoverReach_m) throw;
    End("poor-grip", fmt::format("the cube came down {:.1f} cm from the trays' midpoint, where {} "
                                 "let it go, so {}",
                                 100 * landed_m, first.robot_name, end.outcome.detail));
  }
  MoveGripper(world, second, kPandaFingerTravel_m, 1.0);

  const Eigen::Vector3d p_cube = ep.TrueCubePosition();
  const bool in_tray = IsInTray(*tray_2, p_cube);
  ep.flags.emplace_back("in_tray", in_tray);
  const Eigen::Vector2d offset = (p_cube - tray_2->p_WO).head<2>().cwiseAbs();
  if (offset.maxCoeff() > kSuccessReach_m) {
    End("missed-tray", fmt::format("the cube ended {:.1f} cm from {} in x and {:.1f} cm in y "
                                   "(the paper's success: both within 45.3 cm)",
                                   100 * offset.x(), tray_2->name, 100 * offset.y()));
  }
  if (in_tray) {
    outcome.detail = fmt::format("the cube rests in {}", tray_2->name);
  } else {
    outcome.detail =
        fmt::format("the cube ended outside {}, within 45.3 cm of it in x and y", tray_2->name);
  }
}

}  // namespace prs::sim::internal
