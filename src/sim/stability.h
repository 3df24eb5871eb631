// Does a scene stay as drawn once a simulator starts? Its physics model as `prs export --format
// mjcf` writes it (free bodies are the objects with a positive mass, the rest static) is
// simulated under gravity until every free body is at rest, one moves or turns past the
// tolerance, or the time runs out; each free body's motion is reported (docs/physics.md).
// The sampler takes CheckStable as an acceptance test handed down from the command line
// (sampling::SampleOptions::accept), so sampling never includes this stage.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "export/export.h"
#include "lang/scene.h"

namespace prs::sim {

/// The least simulated time in which rest can be decided. --stable: every body must have been
/// at rest for 0.1 s, judged from 0.1 s on (every body starts at rest). Settling: every body
/// must be where it was 0.5 s before, so nothing can be found at rest sooner than 0.5 s. A
/// shorter time would reject every scene, at rest or not (docs/physics.md).
inline constexpr double kMinStableDuration_s = 0.2;
inline constexpr double kMinSettleDuration_s = 0.5;
/// Settling: a pile found at rest is started again from standstill (every velocity zero) and
/// stepped this long; it has settled if every body then ends within 1 cm and 0.1 rad of where
/// it started, and is written there: what its export does in MuJoCo. The window alone let a
/// body creeping at under 2 cm/s, or one about to tip off an edge, pass (16 bin piles of 100;
/// docs/physics.md, "Confirmed from standstill").
inline constexpr double kSettleConfirm_s = 1.0;

struct StabilityOptions {
  double duration_s = 1.0;             // simulated time at most (kMinStableDuration_s at least)
  double max_move_m = 0.01;            // a free body whose centre moves further is unstable
  double max_turn_rad = 0.0872664626;  // ... or that turns further (5°)
  double timestep_s = 0;               // physics step; 0: the model's (MuJoCo's 2 ms)
  /// The room for contacts first tried (exporting::ExportScene::contacts_per_free_body; 0: the
  /// scene's own). MuJoCo 2.2's data grows with the square of the constraint rows it has room
  /// for: a 25-body pile with the exports' room of 20 contacts a body takes 56 MB, 32 ms to
  /// compile and 25 ms to allocate, a tenth of its settling, and never used more than 5.2 a
  /// body (130 contacts, 492 rows, bin_pile). A simulation in which a step ran out of this room
  /// is run again with the scene's own, so the result does not depend on it.
  int first_contacts_per_free_body = 8;
};

/// Throws std::invalid_argument naming the option when a value is not a positive finite
/// number, or duration_s is below kMinStableDuration_s (the command line refuses such values
/// as usage errors first).
void CheckStabilityOptions(const StabilityOptions& options);

/// How one free body moved from where the scene drew it.
struct BodyMotion {
  int object = -1;  // its index in the scene (and in ExportScene::bodies)
  Eigen::Vector3d p_moved_W = Eigen::Vector3d::Zero();  // displacement of its centre
  double turned_rad = 0;                                // angle of its rotation
  double speed_m_s = 0;                                 // at the end
  double spin_rad_s = 0;                                // at the end
  /// --stable: the last time it was moving (faster than 5 mm/s or 0.05 rad/s), 0 if never.
  double moving_until_s = 0;
  /// Settling: how far it moved and turned over the last rest window compared (0.5 s), or,
  /// when recent_from_standstill, in the last confirmation (1 s from standstill).
  double recent_move_m = 0;
  double recent_turn_rad = 0;
  bool recent_from_standstill = false;
  /// Where it ended: the pose of the object's frame (lang::SceneObject::p_WO, R_WO).
  Eigen::Vector3d p_end_WO = Eigen::Vector3d::Zero();
  Eigen::Quaterniond R_end_WO = Eigen::Quaterniond::Identity();
};

struct StabilityReport {
  std::vector<BodyMotion> free_bodies;  // in scene order; empty: nothing was simulated
  double simulated_s = 0;
  /// Every free body had been at rest (below 5 mm/s and 0.05 rad/s for 0.1 s) when the
  /// simulation stopped; false when one moved past the tolerance first, or time ran out.
  bool at_rest = false;
  /// The free body (index into free_bodies) that decided an unstable scene, else -1: the one
  /// past the tolerance; when time ran out, the one that moved last (--stable) or that was
  /// furthest from rest over the last window (settling).
  int culprit = -1;
};

/// Simulates `scene` under gravity (MuJoCo, 2 ms steps unless options say) as described above.
/// Deterministic. A scene without a free body is not simulated (at rest at once). With
/// `stop_past_tolerance` false (for settling, sim/settle.h) only rest or the time limit stops
/// it, the tolerances are unused, and rest is judged by position: every free body within 1 cm
/// and 0.1 rad of where it was 0.5 s before, checked every 0.1 s (round and mesh shapes rock in
/// place in MuJoCo 2.2 and are never still), and then again after the pile is started from
/// standstill there and stepped kSettleConfirm_s (it ends at the poses that second started
/// from). Throws std::runtime_error with MuJoCo's message when it refuses the model;
/// std::invalid_argument for options CheckStabilityOptions refuses, and when settling, for a
/// duration_s below kMinSettleDuration_s.
StabilityReport SimulateUnderGravity(const exporting::ExportScene& scene,
                                     const StabilityOptions& options,
                                     bool stop_past_tolerance = true);

/// Settling: how a body not at rest when time ran out was moving, from its recent_move_m and
/// recent_turn_rad: "moved 2.3 cm and turned 4.1° in the last 0.5 s (at rest: under 1 cm and
/// 5.7°)".
std::string DescribeUnsettledMotion(const BodyMotion& m);

/// Throws lang::ScenarioError ("physics-without-contacts", at the object) when a free body of
/// `model` (made from `scene` by MakeExportScene) has no contacts: an object with a `mass` and
/// `allowCollisions: True`, which falls through its support, so that no scene with it could
/// pass `check` ("--stable", "--settle").
void CheckFreeBodiesCollide(const lang::Scene& scene, const exporting::ExportScene& model,
                            const char* check);

/// The rejection of a scene some free body of which does not stay put ("unstable", culprit the
/// object's display name, detail e.g. "Cube#5 fell 2.04 m in 0.66 s"), or nullopt. Throws
/// what SimulateUnderGravity and CheckFreeBodiesCollide throw.
std::optional<lang::Rejection> CheckStable(const lang::Scene& scene,
                                           const StabilityOptions& options);

/// CheckStable with `options` as a scene test for the sampler (sampling::SceneTest is this
/// function type). Checks the options first (CheckStabilityOptions).
std::function<std::optional<lang::Rejection>(const lang::Scene&)> MakeStabilityTest(
    const StabilityOptions& options);

}  // namespace prs::sim
