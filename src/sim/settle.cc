// Scenes let come to rest (see settle.h).
#include "sim/settle.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "lang/lang.h"

namespace prs::sim {

void CheckSettleOptions(const SettleOptions& options) {
  if (!(std::isfinite(options.duration_s) && options.duration_s > 0)) {
    throw std::invalid_argument(fmt::format(
        "the simulated time of --settle must be a positive number, not {}", options.duration_s));
  }
  if (options.duration_s < kMinSettleDuration_s) {
    throw std::invalid_argument(fmt::format(
        "the simulated time of --settle must be at least {} s, not {}: a scene is at rest once "
        "every body is where it was {} s before (docs/physics.md)",
        kMinSettleDuration_s, options.duration_s, kMinSettleDuration_s));
  }
  if (!(std::isfinite(options.timestep_s) && options.timestep_s > 0 &&
        options.timestep_s <= 0.01)) {
    throw std::invalid_argument(fmt::format(
        "the settling step must be a positive number of seconds up to 0.01, not {}",
        options.timestep_s));
  }
}

StabilityReport SettleScene(lang::Scene& scene, const SettleOptions& options) {
  CheckSettleOptions(options);
  StabilityOptions simulate;
  simulate.duration_s = options.duration_s;
  simulate.timestep_s = options.timestep_s;
  exporting::ExportScene model = exporting::MakeExportScene(scene, "settle");
  CheckFreeBodiesCollide(scene, model, "--settle");
  model.settled = true;  // settled with the contact model its exports will carry
  const StabilityReport report =
      SimulateUnderGravity(model, simulate, /*stop_past_tolerance=*/false);
  for (const BodyMotion& m : report.free_bodies) {
    lang::MoveObject(scene.objects[m.object], m.p_end_WO, m.R_end_WO);
  }
  scene.settled_s = report.simulated_s;
  return report;
}

std::optional<lang::Rejection> SettleAndCheck(lang::Scene& scene, const SettleOptions& options) {
  const StabilityReport report = SettleScene(scene, options);
  if (!report.at_rest) {
    const BodyMotion& m = report.free_bodies[report.culprit];
    const lang::SceneObject& object = scene.objects[m.object];
    lang::Rejection rejection;
    rejection.kind = lang::RejectionKind::kUnsettled;
    rejection.culprit = object.DisplayName(m.object) + " not at rest";
    rejection.span = object.span;
    rejection.detail =
        fmt::format("{} was still moving after {:.2f} s: it {}", object.DisplayName(m.object),
                    report.simulated_s, DescribeUnsettledMotion(m));
    return rejection;
  }
  return lang::CheckSettledScene(scene);
}

std::function<std::optional<lang::Rejection>(lang::Scene&)> MakeSettleTest(
    const SettleOptions& options) {
  CheckSettleOptions(options);
  return [options](lang::Scene& scene) { return SettleAndCheck(scene, options); };
}

std::function<std::optional<lang::Rejection>(lang::Scene&)> MakePhysicsTest(
    const PhysicsCheck& check) {
  if (check.stable_s != 0 && check.settle_s != 0) {
    throw std::invalid_argument("--stable and --settle cannot be used together: settling "
                                "already lets the scene come to rest");
  }
  if (check.settle_s != 0) return MakeSettleTest({check.settle_s});
  if (check.stable_s == 0) return nullptr;
  return MakeStabilityTest(
      {check.stable_s, check.stable_move_m, check.stable_turn_deg * M_PI / 180});
}

}  // namespace prs::sim
