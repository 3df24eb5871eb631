// Stepping the simulated world with the arms held by their joint servos: each arm's gravity
// and velocity-dependent forces are cancelled exactly (MuJoCo 2.2 has no gravcomp attribute),
// so a servo target is held without sag.
#pragma once

#include <vector>

#include "sim/ik.h"

namespace prs::sim {

/// One physics step (model.opt.timestep seconds) with gravity compensation for `arms`.
void StepWorld(const mjModel& model, mjData& data, const std::vector<ArmIndex>& arms);

/// Steps for `seconds` of simulated time.
void SimulateFor(const mjModel& model, mjData& data, const std::vector<ArmIndex>& arms, double seconds);

}  // namespace prs::sim
