// Shared declarations of the probrobscene extension module (_core): a sampled scene as Python
// holds it, the conversion of language values to Python objects, and raising ScenarioError.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "harness/harness.h"
#include "lang/lang.h"
#include "sampling/sampler.h"
#include "search/estimate.h"

namespace prs::python {

namespace py = pybind11;

using ProgramPtr = std::shared_ptr<const lang::CompiledProgram>;

/// One sampled scene. Holds its program because objects and values point into it (classes).
struct Scene {
  ProgramPtr program;
  sampling::SampledScene sampled;
};
using ScenePtr = std::shared_ptr<Scene>;

/// One object of a scene, seen through the scene (which it keeps alive).
struct SceneObjectView {
  ScenePtr scene;
  int index = 0;

  const lang::SceneObject& object() const { return scene->sampled.scene.objects[index]; }
};

/// A language value as a Python object: numbers, booleans, strings and None as themselves,
/// vectors as numpy arrays of 3, tuples, lists and dicts element by element; anything else
/// (a region, a class, ...) as its short description, as the JSON output writes it.
py::object ToPython(const lang::Value& value);

/// A new 1-D float64 numpy array holding `numbers`.
py::array_t<double> MakeArray(std::initializer_list<double> numbers);

/// The canonical quaternion (w, x, y, z) and yaw, pitch, roll of an object, as in spec §8.
Eigen::Vector4d CalcQuaternionWxyz(const lang::SceneObject& object);
Eigen::Vector3d CalcObjectYawPitchRoll(const lang::SceneObject& object);

/// Raises probrobscene.ScenarioError (SamplingError when the id is "sampling-failed") carrying
/// the diagnostic's message, id and location; `text` is the full Clang-style rendering.
/// A diagnostic without a location (an unreadable main file) names `file` instead.
[[noreturn]] void RaiseScenarioError(const lang::Diagnostic& diagnostic,
                                     const lang::SourceManager& sources, const std::string& text,
                                     const std::string& file = "");

/// A seed or scene index from Python: an int from 0 to 2**64 - 1. Raises TypeError (not an
/// int) or ValueError (out of range) naming the argument, instead of pybind11's generic
/// "incompatible function arguments".
uint64_t ToSceneNumber(const py::object& value, const char* name);

/// What load() and loads() pass to the compiler and the sampler (probrobscene.load's arguments).
struct LoadOptions {
  std::vector<std::string> search_path;
  std::vector<std::pair<std::string, std::string>> params;
  int64_t max_attempts = 10'000;
  bool naive = false;
  double stable_s = 0;  // --stable: simulated seconds of the physics check; 0 off
  double stable_move_m = 0.01;
  double stable_turn_deg = 5;
  double settle_s = 0;                // --settle: most simulated seconds to come to rest; 0 off
  std::string sampler = "rejection";  // --sampler: "rejection" or "gibbs"
};

/// scenario.cc: the words of prs's options that `load` sets and that shape the scenes
/// (--naive, --sampler, --stable[=T] with its tolerances, --settle=T), as prs takes them.
std::vector<std::string> MakeSceneOptionWords(const LoadOptions& load);

/// scenario.cc: compiles `text` (or the file `path` when `text` is null), raising
/// ScenarioError for the first error, with every error rendered in its text.
std::shared_ptr<lang::CompiledProgram> CompileProgram(const std::string& path,
                                                      const std::optional<std::string>& text,
                                                      const LoadOptions& load);

/// Registers Scene, SceneObject and the batch helpers (scene.cc).
void BindScene(py::module_& m);
/// Adds Scene.export and Scene.render (scene_files.cc).
void BindSceneFiles(py::class_<Scene, ScenePtr>& scene);
/// Registers Scenario and the compile functions (scenario.cc).
void BindScenario(py::module_& m);

/// search.cc: the program's scene coordinates as dicts (name, draw, file, line, column).
py::list ListCoordinates(const lang::CompiledProgram& program,
                         const sampling::SampleOptions& options);
/// search.cc: a failure search with a Python callable as the controller; the records as dicts.
py::list RunPythonSearch(const ProgramPtr& program, const sampling::SampleOptions& sample,
                         const py::function& controller, int64_t budget,
                         const std::string& strategy, uint64_t seed, std::optional<int64_t> batch,
                         const std::string& scene_options);
/// search.cc: what a Python controller returned, as an episode result: an outcome name, or a
/// dict with "outcome" and optionally "detail", "score" and anything else (the extra);
/// "bad-answer" for anything else. Needs the GIL.
harness::EpisodeResult ConvertControllerAnswer(const py::object& answer);
/// search.cc: records as dicts, as `prs test -o` writes them (needs the GIL).
py::list ToPythonRecords(const std::vector<harness::EpisodeRecord>& records);
/// replay.cc: read_scene_lines (scenes files as Scenes) and test_scenes (a controller on them).
void BindReplay(py::module_& m);
/// search.cc: prs estimate with a Python callable (on this thread) or a built-in controller's
/// name (on `threads` threads, without the GIL): the estimate and the records as a dict.
/// An estimate as Python sees it (probrobscene.estimate's dict without "records").
py::dict ToPythonEstimate(const search::Estimate& estimate);

py::dict RunPythonEstimate(const ProgramPtr& program, const sampling::SampleOptions& sample,
                           const py::object& controller, int64_t budget, uint64_t seed, int threads,
                           const std::string& scene_options);
/// search.cc: report_markdown(lines, title).
void BindSearch(py::module_& m);
/// dataset.cc: write_dataset (probrobscene.dataset).
void BindDataset(py::module_& m);
/// campaign.cc: campaign_init, campaign_run_shard, campaign_status, campaign_merge.
void BindCampaign(py::module_& m);

}  // namespace prs::python
