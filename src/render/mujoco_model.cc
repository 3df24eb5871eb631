// MuJoCo models from text (see mujoco_model.h), and the render model: what is the same in
// every picture. Objects are not in it: they are added per scene as decoration geoms (see
// renderer.cc), so one model serves all scenes of the same meshes. A mesh must be an asset of
// the model to be drawn: the render model then also holds the scene's meshes, each with one
// static geom from which the renderer copies the mesh's drawing (see scene_geoms.h).
#include "render/mujoco_model.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "export/export.h"
#include "render/box_box_guard.h"
#include "shapes/mesh.h"

namespace prs::render {
namespace internal {
namespace {

// Floor checks of 0.25 m (texuniform: texrepeat counts per metre); a soft sky gradient; a
// headlight for fill and one shadow-casting sun.
constexpr char kRenderModelXml[] = R"(<mujoco model="prs_render">
  <visual>
    <global fovy="45" offwidth="640" offheight="480"/>
    <quality shadowsize="2048" offsamples="4"/>
    <headlight ambient="0.35 0.35 0.35" diffuse="0.5 0.5 0.5" specular="0.1 0.1 0.1"/>
  </visual>
  <asset>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.95 0.96 0.98"
             rgb2="0.66 0.73 0.82" width="64" height="64"/>
    <texture name="checker" type="2d" builtin="checker" rgb1="0.86 0.86 0.84"
             rgb2="0.78 0.78 0.76" width="64" height="64"/>
    <material name="floor" texture="checker" texrepeat="1 1" texuniform="true"/>
)";
constexpr char kRenderModelXmlMiddle[] = R"(  </asset>
  <worldbody>
    <light name="sun" directional="true" castshadow="true" pos="0 0 10" dir="0.35 0.55 -1"
           diffuse="0.45 0.45 0.45" specular="0.15 0.15 0.15"/>
)";
constexpr char kRenderModelXmlEnd[] = R"(  </worldbody>
</mujoco>
)";

thread_local bool warnings_muted = false;  // MujocoWarningsMuted

void PrintMujocoWarning(const char* message) {
  if (warnings_muted) return;
  std::fprintf(stderr, "prs: MuJoCo warning: %s\n", message);
}

// MuJoCo's C code cannot unwind an exception, so an error (a bug on our side) ends the run.
void PrintMujocoErrorAndExit(const char* message) {
  std::fprintf(stderr, "prs: error: internal MuJoCo error: %s\n", message);
  std::exit(1);
}

}  // namespace

ModelPtr LoadRenderModel(const std::vector<MeshKey>& meshes) {
  std::string assets, geoms;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const std::string name = RenderMeshName(i);
    const shapes::MeshShape& mesh = *meshes[i].first;
    assets += "    " +
              exporting::FormatMjcfMesh(name, mesh.mesh.vertices_O, &mesh.mesh.triangles,
                                        meshes[i].second) +
              "\n";
    geoms += "    <geom name=\"" + name + "\" type=\"mesh\" mesh=\"" + name +
             "\" contype=\"0\" conaffinity=\"0\"/>\n";
  }
  return LoadModelFromXml(kRenderModelXml + assets + kRenderModelXmlMiddle + geoms +
                          kRenderModelXmlEnd);
}

std::string RenderMeshName(size_t index) { return "mesh" + std::to_string(index); }

}  // namespace internal

MujocoWarningsMuted::MujocoWarningsMuted() : was_muted_(internal::warnings_muted) {
  internal::warnings_muted = true;
}
MujocoWarningsMuted::~MujocoWarningsMuted() { internal::warnings_muted = was_muted_; }

void InstallMujocoMessageHandlers() {
  mju_user_warning = internal::PrintMujocoWarning;
  mju_user_error = internal::PrintMujocoErrorAndExit;
}

ModelPtr LoadModelFromXml(const std::string& xml) {
  InstallMujocoMessageHandlers();
  InstallBoxBoxGuard();
  // mjVFS holds fixed arrays of file names (megabytes): keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* kName = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("MuJoCo could not make room for the model in memory");
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), kName)], xml.data(), xml.size());
  char error[1024] = "";
  ModelPtr model(mj_loadXML(kName, vfs.get(), error, sizeof error));
  mj_deleteVFS(vfs.get());
  if (!model) throw std::runtime_error(std::string("MuJoCo rejected the model: ") + error);
  return model;
}

DataPtr MakeData(const mjModel& model) {
  DataPtr data(mj_makeData(&model));
  if (!data) throw std::runtime_error("MuJoCo could not allocate simulation data");
  return data;
}

}  // namespace prs::render
