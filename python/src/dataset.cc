// probrobscene.dataset: scenes written as a BOP and COCO dataset (the dataset library, as
// `prs dataset` writes it; docs/dataset.md).
#include "dataset/dataset.h"

#include <pybind11/stl.h>

#include <set>

#include "bindings.h"
#include "render/scene_input.h"

namespace prs::python {
namespace {

py::dict WriteDataset(const std::vector<ScenePtr>& scenes, const std::string& dir,
                      std::vector<std::string> cameras, int width, int height, bool bop, bool coco,
                      bool jpeg, std::vector<std::string> labels,
                      const std::vector<uint64_t>& positions, int threads,
                      std::vector<std::string> class_ids) {
  if (scenes.empty()) throw py::value_error("no scenes to write");
  if (positions.size() != scenes.size()) throw py::value_error("a position per scene");
  if (std::set<uint64_t>(positions.begin(), positions.end()).size() != positions.size()) {
    throw py::value_error(
        "two scenes would make the same images (their indices repeat, as in scenes read from "
        "several files): pass start=0 to number them by their place in the list");
  }
  dataset::DatasetOptions options;
  options.dir = dir;
  options.cameras = std::move(cameras);
  options.width = width;
  options.height = height;
  options.bop = bop;
  options.coco = coco;
  options.jpeg = jpeg;
  options.labels = std::move(labels);
  if (options.cameras.empty()) {
    options.cameras =
        dataset::ListCameraObjects(render::MakeRenderScene(scenes.front()->sampled.scene));
    if (options.cameras.empty()) {
      throw py::value_error(
          "the first scene has no camera object to look through: add one (examples/model.prs's "
          "Camera class has the fovy_deg, aspect, near and far a dataset needs) or name an "
          "object with cameras=[...]");
    }
  }
  // Ids by class: given, or each distinct program's classes in turn (scenes read from several
  // files each have their own), in the scenes' order.
  std::set<const lang::CompiledProgram*> seen;
  const bool given = !class_ids.empty();
  for (const ScenePtr& scene : scenes) {
    if (given) break;
    if (!seen.insert(scene->program.get()).second) continue;
    for (const std::string& name : dataset::ListClassIds(*scene->program)) {
      if (std::find(class_ids.begin(), class_ids.end(), name) == class_ids.end())
        class_ids.push_back(name);
    }
  }
  std::vector<const sampling::SampledScene*> sampled;
  for (const ScenePtr& scene : scenes) sampled.push_back(&scene->sampled);
  int64_t images = 0;
  dataset::StageSeconds stages;
  try {
    py::gil_scoped_release no_gil;
    dataset::DatasetWriter writer(options, class_ids);
    dataset::AddScenes(writer, sampled, positions, threads);
    images = writer.Finish();
    stages = writer.stage_seconds();
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
  py::dict result;
  result["dir"] = dir;
  result["images"] = images;
  result["scenes"] = scenes.size();
  result["cameras"] = options.cameras;
  py::dict seconds;
  seconds["render"] = stages.render;
  seconds["labels"] = stages.labels;
  seconds["pictures"] = stages.pictures;
  seconds["json"] = stages.json;
  result["seconds"] = seconds;
  return result;
}

}  // namespace

void BindDataset(py::module_& m) {
  m.def("write_dataset", &WriteDataset, py::arg("scenes"), py::arg("dir"), py::arg("cameras"),
        py::arg("width"), py::arg("height"), py::arg("bop"), py::arg("coco"), py::arg("jpeg"),
        py::arg("labels"), py::arg("positions"), py::arg("threads"), py::arg("class_ids"));
}

}  // namespace prs::python
