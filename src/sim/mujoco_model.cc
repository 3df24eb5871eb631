// Looking MuJoCo elements up by name (see mujoco_model.h).
#include "sim/mujoco_model.h"

#include <stdexcept>

namespace prs::sim {

int FindId(const mjModel& model, mjtObj type, const std::string& name) {
  const int id = mj_name2id(&model, type, name.c_str());
  if (id < 0) throw std::out_of_range("the simulated world has no element named '" + name + "'");
  return id;
}

}  // namespace prs::sim
