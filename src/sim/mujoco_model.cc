// MuJoCo model loading from memory (see mujoco_model.h).
#include "sim/mujoco_model.h"

#include <cstring>
#include <stdexcept>

namespace prs::sim {

ModelPtr LoadModelFromXml(const std::string& xml) {
  // mjVFS holds fixed arrays of file names (megabytes): keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* kName = "scene.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("MuJoCo could not make room for the model in memory");
  }
  const int file = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
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

int FindId(const mjModel& model, mjtObj type, const std::string& name) {
  const int id = mj_name2id(&model, type, name.c_str());
  if (id < 0) throw std::out_of_range("the simulated world has no element named '" + name + "'");
  return id;
}

}  // namespace prs::sim
