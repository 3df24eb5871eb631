// MuJoCo models from MJCF text, loaded through MuJoCo's in-memory file system, with owning
// handles and MuJoCo's messages routed to stderr. Shared by the renderer (its fixed picture
// model) and src/sim (worlds from scenes).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace prs::shapes {
struct MeshShape;  // shapes/mesh.h
}

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
/// names the element and line) when the document is rejected. Installs the box-box guard
/// (box_box_guard.h) first.
ModelPtr LoadModelFromXml(const std::string& xml);

/// A fresh mjData for `model`, at the model's initial state.
DataPtr MakeData(const mjModel& model);

/// While one is alive, MuJoCo's warnings raised on this thread are not printed (errors still
/// are): for a simulation that is run again, with more room, when it raises one
/// (sim/stability.cc). The warnings are still counted in mjData::warning.
class MujocoWarningsMuted {
 public:
  MujocoWarningsMuted();
  ~MujocoWarningsMuted();
  MujocoWarningsMuted(const MujocoWarningsMuted&) = delete;
  MujocoWarningsMuted& operator=(const MujocoWarningsMuted&) = delete;

 private:
  bool was_muted_;
};

/// Routes MuJoCo's warnings and errors to stderr instead of its defaults, which write
/// MUJOCO_LOG.TXT into the working directory. Called by LoadModelFromXml.
void InstallMujocoMessageHandlers();

namespace internal {
/// A mesh at a scale, as the render model holds it.
using MeshKey = std::pair<const shapes::MeshShape*, double>;
/// The model scene pictures share (sky, checker floor texture, sun light), with `meshes` as
/// assets: mesh i is asset RenderMeshName(i), drawn by a static world geom of that name at the
/// identity pose (so that the geom's compiled pose is where MuJoCo moved the mesh's frame).
ModelPtr LoadRenderModel(const std::vector<MeshKey>& meshes = {});
std::string RenderMeshName(size_t index);
}  // namespace internal

}  // namespace prs::render
