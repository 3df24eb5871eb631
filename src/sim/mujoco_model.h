// MuJoCo handles for the simulation: the loader and owning handles are render's
// (render/mujoco_model.h, shared with the renderer); FindId looks elements up by name.
#pragma once

#include <string>

#include "render/mujoco_model.h"

namespace prs::sim {

using render::DataPtr;
using render::LoadModelFromXml;
using render::MakeData;
using render::ModelPtr;

/// The id of a named element (mjOBJ_JOINT, mjOBJ_SITE, ...). Throws std::out_of_range naming
/// the element when the model has none of that name.
int FindId(const mjModel& model, mjtObj type, const std::string& name);

}  // namespace prs::sim
