// MuJoCo models from MJCF text, loaded through MuJoCo's in-memory file system, with owning
// handles and MuJoCo's messages routed to stderr. Shared by the renderer (its fixed picture
// model) and src/sim (worlds from scenes).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

namespace prs::render {

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

/// Routes MuJoCo's warnings and errors to stderr instead of its defaults, which write
/// MUJOCO_LOG.TXT into the working directory. Called by LoadModelFromXml.
void InstallMujocoMessageHandlers();

namespace internal {
/// The fixed model every scene picture shares (sky, checker floor texture, sun light).
ModelPtr LoadRenderModel();
}  // namespace internal

}  // namespace prs::render
