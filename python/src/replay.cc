// Saved scenes from Python (docs/python.md): read_scene_lines turns the lines of a scenes file
// into Scenes, and test_scenes runs a controller (a Python callable, a built-in name or an
// --exec command, persistent or not) on Scenes as `prs test SCENES.jsonl` does.
#include <pybind11/stl.h>

#include <atomic>

#include "bindings.h"
#include "controllers/builtin.h"
#include "output/scene_reader.h"

namespace prs::python {
namespace {

// The Scenes of a scenes file's lines; ValueError "PATH:LINE: what is wrong". Blank lines are
// skipped, as prs skips them.
py::list ReadSceneLines(const std::vector<std::string>& lines, const std::string& path) {
  output::SceneReader reader;
  std::vector<sampling::SampledScene> scenes;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      scenes.push_back(reader.Read(lines[i]));
    } catch (const std::invalid_argument& error) {
      throw py::value_error(path + ":" + std::to_string(i + 1) + ": " + error.what());
    }
  }
  // The reader's classes live as long as any of its scenes.
  const ProgramPtr classes = reader.classes();
  py::list out;
  for (sampling::SampledScene& scene : scenes) {
    out.append(std::make_shared<Scene>(Scene{classes, std::move(scene)}));
  }
  return out;
}

// A Python callable in a replay: it runs on the replay's one worker thread and takes the GIL
// for each call; it gets the Python Scene of the item the source made last on that thread.
class PythonReplayController : public harness::Controller {
 public:
  PythonReplayController(py::function function, const ScenePtr* current)
      : function_(std::move(function)), current_(current) {}
  ~PythonReplayController() override {
    py::gil_scoped_acquire gil;  // the function's reference is dropped with the GIL held
    function_ = py::function();
  }

  harness::EpisodeResult RunEpisode(const sampling::SampledScene&, const std::string&) override {
    py::gil_scoped_acquire gil;
    try {
      return ConvertControllerAnswer(function_(*current_));
    } catch (py::error_already_set& error) {
      if (error.matches(PyExc_KeyboardInterrupt)) throw;  // not a controller-error: stop
      return {"controller-error", error.what()};
    }
  }

 private:
  py::function function_;
  const ScenePtr* current_;
};

py::list TestScenes(const std::vector<ScenePtr>& scenes, const py::object& controller,
                    const std::string& exec, bool persistent, double timeout_s,
                    double startup_timeout_s, int threads) {
  if (threads < 1) throw py::value_error("threads must be >= 1");
  if (!(timeout_s > 0) || !(startup_timeout_s > 0)) {
    throw py::value_error("timeout and startup_timeout must be above 0 seconds");
  }
  const bool callable = !controller.is_none() && !py::isinstance<py::str>(controller);
  if (callable && !PyCallable_Check(controller.ptr())) {
    throw py::type_error("controller must be a function, a built-in controller's name or None");
  }
  if (persistent && exec.empty()) throw py::value_error("persistent=True needs exec");
  const std::string name =
      py::isinstance<py::str>(controller) ? controller.cast<std::string>() : "";
  if (int(callable) + int(!name.empty()) + int(!exec.empty()) != 1) {
    throw py::value_error("give one controller: a function, a built-in controller's name, or exec");
  }
  ScenePtr current;  // the item being run (a callable runs on one thread)
  harness::ControllerFactory factory;
  if (callable) {
    threads = 1;
    py::function function = controller.cast<py::function>();
    factory = [function, &current] {
      py::gil_scoped_acquire gil;  // copies the function's reference
      return std::make_unique<PythonReplayController>(function, &current);
    };
  } else {
    const controllers::ControllerChoice choice{name, exec, timeout_s, persistent,
                                               startup_timeout_s};
    auto made = controllers::MakeControllerFactory(choice, nullptr);
    if (!made) {
      throw py::value_error("unknown controller '" + name +
                            "' (controllers: " + controllers::ListControllerNames() + ")");
    }
    factory = *made;
  }
  const harness::ReplaySourceFactory sources = [&]() -> harness::ReplaySource {
    return [&](int64_t item) {
      if (callable) current = scenes[size_t(item)];  // one thread: the callable's next scene
      return harness::ReplayScene{scenes[size_t(item)]->sampled, {}};
    };
  };
  harness::RunOptions options;
  options.threads = threads;
  harness::RunSummary summary;
  {
    py::gil_scoped_release no_gil;
    // A worker that cannot start (ControllerStartError) reaches Python as RuntimeError.
    summary = harness::ReplayEpisodes(int64_t(scenes.size()), sources, factory, options);
  }
  factory = nullptr;  // a Python function is released with the GIL held
  return ToPythonRecords(summary.records);
}

}  // namespace

void BindReplay(py::module_& m) {
  m.def("read_scene_lines", &ReadSceneLines, py::arg("lines"), py::arg("path"));
  m.def("test_scenes", &TestScenes, py::arg("scenes"), py::arg("controller"), py::arg("exec"),
        py::arg("persistent"), py::arg("timeout_s"), py::arg("startup_timeout_s"),
        py::arg("threads"));
}

}  // namespace prs::python
