// Scene.export and Scene.render: a scene as a simulator file (the export library, as
// `prs export`) or as a PNG picture (the render library, as `prs render`).
#include <fstream>

#include "bindings.h"
#include "export/export.h"
#include "render/render.h"
#include "render/scene_input.h"

namespace prs::python {
namespace {

std::string Title(const Scene& s) {
  return "seed " + std::to_string(s.sampled.seed) + " index " + std::to_string(s.sampled.index);
}

void ExportScene(const Scene& s, const std::string& format_name, const std::string& path) {
  const std::optional<exporting::Format> format = exporting::ParseFormat(format_name);
  if (!format) {
    throw py::value_error("unknown format '" + format_name + "'; use one of " +
                          exporting::ListFormatNames());
  }
  exporting::ExportScene scene = exporting::MakeExportScene(s.sampled.scene, Title(s));
  scene.seed = s.sampled.seed;
  scene.index = s.sampled.index;
  const std::string bytes = exporting::WriteScene(scene, *format);
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out.flush()) throw py::value_error("cannot write " + path);
}

void RenderScene(const Scene& s, const std::string& path, int width, int height,
                 const std::string& view) {
  render::RenderOptions options;
  try {
    options.view = render::ParseView(view);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  if (width < 16 || height < 16 || width > 8192 || height > 8192) {
    throw py::value_error("width and height must be from 16 to 8192 pixels");
  }
  options.width = width;
  options.height = height;
  const render::RenderScene scene = render::MakeRenderScene(s.sampled.scene);
  render::Image image;
  {
    py::gil_scoped_release no_gil;  // software rendering takes a few tenths of a second
    // One OpenGL context per thread, made on first use and kept to the end of the process
    // (tearing EGL down at interpreter exit is not safe, and a context is current on one
    // thread only).
    thread_local render::Renderer* renderer = new render::Renderer();
    try {
      image = renderer->Render(scene, options);
    } catch (const std::invalid_argument& e) {  // an unknown camera name
      py::gil_scoped_acquire gil;
      throw py::value_error(e.what());
    }
  }
  render::WritePng(image, path);
}

}  // namespace

void BindSceneFiles(py::class_<Scene, ScenePtr>& scene) {
  scene.def("export", &ExportScene, py::arg("format"), py::arg("path"),
            "Writes the scene for a simulator or viewer, as `prs export` does: format is one of "
            "'mjcf', 'urdf', 'sdf', 'usda', 'gltf', 'glb' (docs/export.md).");
  scene.def("render", &RenderScene, py::arg("path"), py::arg("width") = 640,
            py::arg("height") = 480, py::arg("view") = "overview",
            "Draws the scene offscreen into a PNG, as `prs render` does: view is 'overview', "
            "'top', 'front' or 'camera:NAME' (docs/render.md).");
}

}  // namespace prs::python
