// Gravity-compensated stepping (see control.h).
#include "sim/control.h"

#include <cmath>

namespace prs::sim {

void StepWorld(const mjModel& model, mjData& data, const std::vector<ArmIndex>& arms) {
  // mj_step1 computes positions and velocities (so qfrc_bias is this step's); the applied
  // forces set between the halves enter this same step's dynamics.
  mj_step1(&model, &data);
  for (const ArmIndex& arm : arms) {
    for (int dof : arm.dof_address) data.qfrc_applied[dof] = data.qfrc_bias[dof];
  }
  mj_step2(&model, &data);
}

void SimulateFor(const mjModel& model, mjData& data, const std::vector<ArmIndex>& arms, double seconds) {
  const int steps = static_cast<int>(std::ceil(seconds / model.opt.timestep));
  for (int i = 0; i < steps; ++i) StepWorld(model, data, arms);
}

}  // namespace prs::sim
