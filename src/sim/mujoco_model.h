// Owning handles for MuJoCo's model and data, and loading an MJCF document from a string
// (through MuJoCo's in-memory file system), with MuJoCo's message turned into an exception.
#pragma once

#include <memory>
#include <string>

#include <mujoco/mujoco.h>

namespace prs::sim {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// Compiles an MJCF document. Throws std::runtime_error with MuJoCo's compiler message (which
/// names the element and line) when the document is rejected.
ModelPtr LoadModelFromXml(const std::string& xml);

/// A fresh mjData for `model`, at the model's initial state.
DataPtr MakeData(const mjModel& model);

/// The id of a named element (mjOBJ_JOINT, mjOBJ_SITE, ...). Throws std::out_of_range naming
/// the element when the model has none of that name.
int FindId(const mjModel& model, mjtObj type, const std::string& name);

}  // namespace prs::sim
