// The render model as MJCF text: what is the same in every picture. Objects are not in it:
// they are added per scene as decoration geoms (see renderer.cc), so one model serves all.
#include "render/mujoco_model.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace prs::render::internal {
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
  </asset>
  <worldbody>
    <light name="sun" directional="true" castshadow="true" pos="0 0 10" dir="0.35 0.55 -1"
           diffuse="0.45 0.45 0.45" specular="0.15 0.15 0.15"/>
  </worldbody>
</mujoco>
)";

void PrintMujocoWarning(const char* message) {
  std::fprintf(stderr, "prs: MuJoCo warning: %s\n", message);
}

// MuJoCo's C code cannot unwind an exception, so an error (a bug on our side) ends the run.
void PrintMujocoErrorAndExit(const char* message) {
  std::fprintf(stderr, "prs: error: internal MuJoCo error: %s\n", message);
  std::exit(1);
}

struct VfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};

}  // namespace

void InstallMujocoMessageHandlers() {
  mju_user_warning = PrintMujocoWarning;
  mju_user_error = PrintMujocoErrorAndExit;
}

mjModel* LoadRenderModel() {
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);  // large: ~2000 file slots
  mj_defaultVFS(vfs.get());
  const char* name = "prs_render.xml";
  const int size = static_cast<int>(std::strlen(kRenderModelXml));
  if (mj_makeEmptyFileVFS(vfs.get(), name, size) != 0)
    throw std::runtime_error("cannot make the render model's in-memory file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], kRenderModelXml, size);
  char error[1000] = "";
  mjModel* model = mj_loadXML(name, vfs.get(), error, sizeof error);
  if (!model) throw std::runtime_error(std::string("cannot load the render model: ") + error);
  return model;
}

}  // namespace prs::render::internal
