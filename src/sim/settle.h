// Scenes let come to rest: the free bodies of a scene (the objects with a positive mass, as
// `prs export --format mjcf` makes them) are simulated under gravity until they are at rest,
// and moved to where they stopped; then what must still hold is checked (the workspace, the
// program's `require settled`: lang::CheckSettledScene). The sampler takes SettleAndCheck as
// its scene test (sampling::SampleOptions::accept), so a scene that breaks it is rejected as
// `unsettled` and another attempt is made (docs/physics.md).
#pragma once

#include <functional>
#include <optional>

#include "lang/scene.h"
#include "sim/stability.h"

namespace prs::sim {

/// The physics step settling takes unless told otherwise: a little over three times MuJoCo's
/// 2 ms, and a divisor of the 0.1 s between rest checks (docs/physics.md, "Step", says what it
/// was chosen on: bench/settle_profile --check).
inline constexpr double kSettleTimestep_s = 0.00625;

struct SettleOptions {
  /// Simulated time to find rest in: a scene not found at rest by then is unsettled. The 1 s
  /// confirmation of a pile found at rest in time may take the simulation past it.
  double duration_s = 4.0;
  double timestep_s = kSettleTimestep_s;  // MuJoCo's step while settling
};

/// Throws std::invalid_argument when duration_s is not a positive finite number, or is below
/// kMinSettleDuration_s (0.5 s: rest is judged over the last 0.5 s; sim/stability.h), or
/// timestep_s is not a positive number of at most 10 ms.
void CheckSettleOptions(const SettleOptions& options);

/// Simulates the scene's free bodies under gravity until every one is at rest (within 1 cm and
/// 0.1 rad of where it was 0.5 s before, and again 1 s after being started from standstill
/// there; sim/stability.h) or the time runs out, and moves each to where it ended
/// (lang::MoveObject); sets scene.settled_s. Returns the motion
/// (StabilityReport::at_rest false when time ran out, culprit the body furthest from rest).
/// Deterministic. Throws what SimulateUnderGravity and CheckFreeBodiesCollide throw.
StabilityReport SettleScene(lang::Scene& scene, const SettleOptions& options);

/// SettleScene, then the checks of the settled scene: the rejection (kind kUnsettled) of a
/// scene not at rest in time ("cube_2 was still moving after 3.00 s: it moved 2.3 cm and turned
/// 0.4° in the last 0.5 s (at rest: under 1.0 cm and 5.7°)"), with an object outside the
/// workspace, or breaking a `require settled`; nullopt when it passes.
std::optional<lang::Rejection> SettleAndCheck(lang::Scene& scene, const SettleOptions& options);

/// SettleAndCheck with `options` as a scene test for the sampler (sampling::SceneTest is this
/// function type). Checks the options first (CheckSettleOptions).
std::function<std::optional<lang::Rejection>(lang::Scene&)> MakeSettleTest(
    const SettleOptions& options);

/// What the command line (--stable, --settle), campaign specs and Python's load(stable=,
/// settle=) ask for, as one scene test: settling when settle_s > 0, the stability check when
/// stable_s > 0, else none (an empty function). Throws std::invalid_argument for both at once
/// and for a bad number (the check's own message).
struct PhysicsCheck {
  double stable_s = 0;
  double stable_move_m = 0.01;
  double stable_turn_deg = 5;
  double settle_s = 0;
};
std::function<std::optional<lang::Rejection>(lang::Scene&)> MakePhysicsTest(
    const PhysicsCheck& check);

}  // namespace prs::sim
