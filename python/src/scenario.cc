// Scenario: a compiled program and its sampling options, with sample(), sample_batch() (on
// worker threads, without the GIL, identical to `prs sample`) and check() (the compiled outline
// and the properties seen to vary, as `prs check` prints them).
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "analysis/property_variation.h"
#include "analysis/scenario_outline.h"
#include "bindings.h"
#include "dataset/dataset.h"
#include "harness/harness.h"
#include "sampling/batch.h"
#include "sampling/gibbs.h"
#include "sampling/partial_rejection.h"
#include "sim/settle.h"

namespace prs::python {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kMaxThreads = 1024;

std::string RenderErrors(const lang::DiagnosticEngine& diagnostics,
                         const lang::SourceManager& sources) {
  std::string text;
  for (const lang::Diagnostic& d : diagnostics.diagnostics()) {
    if (d.severity == lang::Severity::kError) text += lang::RenderDiagnostic(d, sources);
  }
  return text;
}

// Thrown from a batch's consume callback when Python has an exception pending (Ctrl-C).
struct PythonErrorPending {};

class Scenario {
 public:
  Scenario(ProgramPtr program, std::string path, sampling::SampleOptions options,
           double stable_s = 0, double settle_s = 0, std::string scene_options = "")
      : program_(std::move(program)),
        path_(std::move(path)),
        options_(options),
        stable_s_(stable_s),
        settle_s_(settle_s),
        scene_options_(std::move(scene_options)),
        sampler_(*program_, options_) {}

  const lang::CompiledProgram& program() const { return *program_; }

  ScenePtr Sample(const py::object& seed_arg, const py::object& index_arg) {
    const uint64_t seed = ToSceneNumber(seed_arg, "seed"),
                   index = ToSceneNumber(index_arg, "index");
    // The GIL stays held: it is what keeps two Python threads off the one cached sampler.
    return Wrap(Call([&] { return sampler_.Sample(seed, index); }));
  }

  std::vector<ScenePtr> SampleBatch(int64_t count, const py::object& seed_arg,
                                    const py::object& start_arg, std::optional<int> threads) {
    const uint64_t seed = ToSceneNumber(seed_arg, "seed"),
                   start = ToSceneNumber(start_arg, "start");
    std::vector<sampling::SampledScene> sampled;
    sampled.reserve(size_t(std::clamp<int64_t>(count, 0, 1 << 16)));  // n may be a guess
    RunBatch(count, seed, start, threads,
             [&](sampling::BatchScene&& scene) { sampled.push_back(std::move(scene.sampled)); });
    std::vector<ScenePtr> scenes;
    scenes.reserve(sampled.size());
    for (auto& s : sampled) scenes.push_back(Wrap(std::move(s)));
    return scenes;
  }

  py::dict Check(int64_t count, const py::object& seed_arg, std::optional<int> threads) {
    const uint64_t seed = ToSceneNumber(seed_arg, "seed");
    const analysis::ScenarioOutline outline = analysis::OutlineScenario(*program_);
    analysis::VariationObserver observer;
    RunBatch(count, seed, 0, threads,
             [&](sampling::BatchScene&& scene) { observer.Observe(scene.sampled.scene); });
    py::dict summary;
    summary["file"] = path_;
    summary["modules"] = program_->modules.size();
    summary["seed"] = seed;
    summary["scenes_observed"] = observer.scenes();
    summary["sites"] = DescribeSites(outline, observer);
    summary["classes"] = DescribeClasses(outline);
    return summary;
  }

  py::list Coordinates() const { return ListCoordinates(*program_, options_); }

  py::list Search(const py::function& controller, int64_t budget, const std::string& strategy,
                  const py::object& seed_arg, std::optional<int64_t> batch) {
    return RunPythonSearch(program_, options_, controller, budget, strategy,
                           ToSceneNumber(seed_arg, "seed"), batch, scene_options_);
  }

  py::dict Estimate(const py::object& controller, int64_t budget, const py::object& seed_arg,
                    int threads) {
    return RunPythonEstimate(program_, options_, controller, budget,
                             ToSceneNumber(seed_arg, "seed"), threads, scene_options_);
  }

  const std::string& path() const { return path_; }
  int64_t max_attempts() const { return options_.max_attempts; }
  bool naive() const { return options_.run.mode == lang::SamplingMode::kNaive; }
  std::optional<double> stable() const {
    return stable_s_ > 0 ? std::optional<double>(stable_s_) : std::nullopt;
  }
  std::optional<double> settle() const {
    return settle_s_ > 0 ? std::optional<double>(settle_s_) : std::nullopt;
  }
  std::string sampler() const {
    return options_.gibbs               ? "gibbs"
           : options_.partial_rejection ? "partial-rejection"
                                        : "rejection";
  }
  /// --sampler partial-rejection: the sites and the pilot once scenes were drawn, else None.
  py::object partial_rejection() const {
    if (!options_.partial_rejection) return py::none();
    const std::optional<sampling::PartialRejectionPlan> plan = options_.partial_rejection->plan();
    if (!plan) return py::none();
    py::list sites;
    for (const sampling::ClutterSite& site : plan->sites) {
      py::dict d;
      d["site"] = site.name;
      d["objects"] = site.ordinals.size();
      d["coordinates"] = site.coordinates;
      d["intensity"] = site.intensity;
      sites.append(d);
    }
    py::dict d;
    d["sites"] = sites;
    d["mean_rounds"] = plan->mean_rounds;
    d["mean_probe_runs"] = plan->mean_probes;
    d["count_acceptance"] = plan->count_acceptance;
    return d;
  }
  /// --sampler gibbs: the chain's schedule once scenes were drawn, else None.
  py::object gibbs() const {
    if (!options_.gibbs) return py::none();
    const std::optional<sampling::GibbsPlan> plan = options_.gibbs->plan();
    if (!plan) return py::none();
    py::dict d;
    d["autocorrelation_sweeps"] = plan->tau_sweeps;
    d["slowest_statistic"] = plan->tau_statistic;
    d["slowest_statistic_sweeps"] = plan->tau_worst_sweeps;
    d["autocorrelation_scenes"] = plan->tau_scenes;
    d["thin_sweeps"] = plan->thin_sweeps;
    d["burn_in_sweeps"] = plan->burn_in_sweeps;
    d["blocks"] = plan->blocks;
    d["scenes_per_chain"] = plan->scenes_per_chain;
    return d;
  }

 private:
  ScenePtr Wrap(sampling::SampledScene sampled) const {
    return std::make_shared<Scene>(Scene{program_, std::move(sampled)});
  }

  // Runs `body`, turning the engine's ScenarioError into probrobscene.ScenarioError.
  template <typename Body>
  auto Call(Body body) -> decltype(body()) {
    try {
      return body();
    } catch (const lang::ScenarioError& error) {
      RaiseScenarioError(error.diagnostic(), program_->sources,
                         lang::RenderDiagnostic(error.diagnostic(), program_->sources));
    }
  }

  template <typename Consume>
  void RunBatch(int64_t count, uint64_t seed, uint64_t start, std::optional<int> threads,
                Consume consume);

  py::list DescribeSites(const analysis::ScenarioOutline& outline,
                         const analysis::VariationObserver& observer) const;
  py::list DescribeClasses(const analysis::ScenarioOutline& outline) const;
  py::dict DescribeWhere(lang::FileId file, uint32_t offset) const;

  ProgramPtr program_;
  std::string path_;
  sampling::SampleOptions options_;
  double stable_s_ = 0;             // --stable's seconds (the check is options_.accept), 0 when off
  double settle_s_ = 0;             // --settle's seconds (options_.accept settles), 0 when off
  std::string scene_options_;       // harness::SceneOptionsOf the options above, for the records
  sampling::SceneSampler sampler_;  // for sample(): its caches persist between calls
};

// Samples scenes start..start+count-1 on `threads` workers (default: every hardware thread)
// with the GIL released, handing each to `consume` in index order on this thread. Checks for a
// pending Python signal (Ctrl-C) between scenes, at most every 100 ms; one stops the batch.
template <typename Consume>
void Scenario::RunBatch(int64_t count, uint64_t seed, uint64_t start, std::optional<int> threads,
                        Consume consume) {
  if (count < 0) throw py::value_error("n must be >= 0, got " + std::to_string(count));
  if (threads && (*threads < 1 || *threads > kMaxThreads)) {  // the same bounds as `prs`
    throw py::value_error("threads must be from 1 to " + std::to_string(kMaxThreads) + ", got " +
                          std::to_string(*threads));
  }
  sampling::BatchOptions options;
  options.sample = options_;
  options.seed = seed;
  options.start = start;
  options.count = count;
  options.threads = threads ? *threads : int(std::max(1u, std::thread::hardware_concurrency()));
  auto next_check = Clock::now() + std::chrono::milliseconds(100);
  const sampling::BatchCallbacks callbacks{
      .prepare = {}, .consume = [&](sampling::BatchScene&& scene) {
        consume(std::move(scene));
        if (Clock::now() < next_check) return;
        next_check = Clock::now() + std::chrono::milliseconds(100);
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw PythonErrorPending{};
      }};
  try {
    Call([&] {
      py::gil_scoped_release no_gil;
      sampling::SampleBatch(*program_, options, callbacks);
    });
  } catch (const PythonErrorPending&) {
    throw py::error_already_set();
  }
}

py::dict Scenario::DescribeWhere(lang::FileId file, uint32_t offset) const {
  py::dict where;
  if (file >= program_->sources.file_count()) return where;
  where["file"] = program_->sources.path(file);
  where["line"] = program_->sources.CalcLineColumn(file, offset).line;
  return where;
}

py::list Scenario::DescribeSites(const analysis::ScenarioOutline& outline,
                                 const analysis::VariationObserver& observer) const {
  py::list sites;
  for (const analysis::CreationSite& site : outline.sites) {
    py::dict entry = DescribeWhere(site.key.first, site.key.second);
    entry["name"] = site.variable;
    entry["class"] = site.class_name;
    entry["position_specifiers"] = site.position_specifiers;
    entry["position_region"] = site.position_region;
    const auto found = observer.sites().find(site.key);
    const bool created = found != observer.sites().end();
    const analysis::SiteVariation none;
    const analysis::SiteVariation& variation = created ? found->second : none;
    // A site absent from some scenes created no object there: its minimum count is 0.
    entry["min_objects"] = variation.scenes_present < observer.scenes() ? 0 : variation.min_objects;
    entry["max_objects"] = variation.max_objects;
    entry["varied"] = variation.varied;
    sites.append(entry);
  }
  return sites;
}

py::list Scenario::DescribeClasses(const analysis::ScenarioOutline& outline) const {
  py::list classes;
  for (const analysis::ClassOutline& cls : outline.classes) {
    py::dict entry = DescribeWhere(cls.span.file, cls.span.begin);
    entry["name"] = cls.name;
    entry["parent"] = cls.parent;
    entry["own_properties"] = cls.own_properties;
    classes.append(entry);
  }
  return classes;
}

std::unique_ptr<Scenario> Compile(const std::string& path, const std::optional<std::string>& text,
                                  const LoadOptions& load) {
  std::vector<std::string> words = {path};
  for (const std::string& word : MakeSceneOptionWords(load)) words.push_back(word);
  std::shared_ptr<lang::CompiledProgram> program = CompileProgram(path, text, load);
  sampling::SampleOptions sample;
  sample.max_attempts = load.max_attempts;
  sample.run.mode = load.naive ? lang::SamplingMode::kNaive : lang::SamplingMode::kRegion;
  if (load.sampler == "gibbs") {
    sample.gibbs = std::make_shared<sampling::GibbsRequest>();
  } else if (load.sampler == "partial-rejection") {
    sample.partial_rejection = std::make_shared<sampling::PartialRejectionRequest>();
  } else if (load.sampler != "rejection") {
    throw py::value_error("sampler must be 'rejection', 'partial-rejection' or 'gibbs', got '" +
                          load.sampler + "'");
  }
  try {
    sample.accept = sim::MakePhysicsTest(
        {load.stable_s, load.stable_move_m, load.stable_turn_deg, load.settle_s});
  } catch (const std::invalid_argument& error) {
    throw py::value_error(error.what());
  }
  return std::make_unique<Scenario>(std::move(program), path, sample, load.stable_s, load.settle_s,
                                    harness::SceneOptionsOf(words));
}

}  // namespace

std::vector<std::string> MakeSceneOptionWords(const LoadOptions& load) {
  std::vector<std::string> words;
  if (load.naive) words.push_back("--naive");
  if (load.sampler != "rejection") words.insert(words.end(), {"--sampler", load.sampler});
  if (load.stable_s > 0) {
    words.push_back(fmt::format("--stable={}", load.stable_s));
    if (load.stable_move_m != LoadOptions{}.stable_move_m) {
      words.insert(words.end(), {"--stable-move", fmt::format("{}", load.stable_move_m)});
    }
    if (load.stable_turn_deg != LoadOptions{}.stable_turn_deg) {
      words.insert(words.end(), {"--stable-turn", fmt::format("{}", load.stable_turn_deg)});
    }
  }
  if (load.settle_s > 0) words.push_back(fmt::format("--settle={}", load.settle_s));
  return words;
}

std::shared_ptr<lang::CompiledProgram> CompileProgram(const std::string& path,
                                                      const std::optional<std::string>& text,
                                                      const LoadOptions& load) {
  if (load.max_attempts < 1) {
    throw py::value_error("max_attempts must be >= 1, got " + std::to_string(load.max_attempts));
  }
  lang::CompileOptions options;
  options.search_path = load.search_path;
  options.param_overrides = load.params;
  lang::DiagnosticEngine diagnostics;
  std::shared_ptr<lang::CompiledProgram> program =
      text ? lang::CompileText(path, *text, options, diagnostics)
           : lang::CompileFile(path, options, diagnostics);
  if (diagnostics.has_errors()) {
    for (const lang::Diagnostic& d : diagnostics.diagnostics()) {
      if (d.severity != lang::Severity::kError) continue;
      RaiseScenarioError(d, program->sources, RenderErrors(diagnostics, program->sources), path);
    }
  }
  return program;
}

void BindScenario(py::module_& m) {
  py::class_<Scenario>(m, "Scenario", "A compiled scenario; sample scenes from it.")
      .def("_dataset_classes",
           [](const Scenario& s) { return dataset::ListClassIds(s.program()); },
           "The classes a dataset numbers its objects by (probrobscene.dataset's classes=).")
      .def("sample", &Scenario::Sample, py::arg("seed") = 0, py::arg("index") = 0,
           "Scene `index` of `seed`: the scene `prs sample -s SEED --start INDEX` prints first.\n"
           "Raises SamplingError when no valid scene is found within max_attempts, and\n"
           "ScenarioError for errors that show only when the program runs.")
      .def("sample_batch", &Scenario::SampleBatch, py::arg("n"), py::arg("seed") = 0,
           py::arg("start") = 0, py::arg("threads") = py::none(),
           "Scenes start..start+n-1 of `seed`, in index order, sampled on `threads` worker\n"
           "threads (None: every hardware thread) with the GIL released. The scenes are those\n"
           "of `prs sample -n N -s SEED --start START`, whatever the thread count. Ctrl-C\n"
           "stops the batch (KeyboardInterrupt). Errors as for sample().")
      .def("check", &Scenario::Check, py::arg("n") = 20, py::arg("seed") = 0,
           py::arg("threads") = py::none(),
           "The summary `prs check` prints, as a dict: 'file', 'modules', 'seed',\n"
           "'scenes_observed' (n), 'sites' (one dict per object-creation site: file, line,\n"
           "name, class, position_specifiers, position_region, min_objects, max_objects,\n"
           "varied = the properties that differed between the n scenes sampled) and\n"
           "'classes' (name, parent, file, line, own_properties). n=0 samples nothing.\n"
           "Raises as sample_batch() when sampling fails.")
      .def("coordinates", &Scenario::Coordinates,
           "The scene coordinates (docs/search.md): one dict per number an attempt draws, with\n"
           "'name' (e.g. 'Cube#5.position[0]'), 'draw', 'file', 'line', 'column'; as\n"
           "`prs check --coordinates` lists them.")
      .def("search", &Scenario::Search, py::arg("controller"), py::arg("budget"),
           py::arg("strategy") = "ce", py::arg("seed") = 0, py::arg("batch") = py::none(),
           "Searches for scenes where `controller` fails, as `prs search` (docs/search.md).\n"
           "`controller(scene)` returns an outcome name ('success', 'no-path', ...) or a dict\n"
           "with 'outcome' and optionally 'detail', 'score' (finite; larger is safer, <= 0 a\n"
           "failure) and anything else (the record's 'extra'). Runs on this thread. Returns\n"
           "the records as dicts, as `prs search -o` writes them.")
      .def("estimate", &Scenario::Estimate, py::arg("controller"), py::arg("budget"),
           py::arg("seed") = 0, py::arg("threads") = 1,
           "How often `controller` fails under the scenario's own law, as `prs estimate`\n"
           "(docs/search.md): a dict with 'episodes', 'ess', 'reliable', 'estimates' (per\n"
           "failure outcome: 'p', 'ci95', 'ess', 'failing_episodes',\n"
           "'iid_episodes_for_same_precision'), 'upper_bound_95' when nothing failed, and\n"
           "'records'. `controller` is a function (as for search(); runs on this thread) or a\n"
           "built-in controller's name (run on `threads` threads).")
      .def_property_readonly("path", &Scenario::path, "The file (or loads()' name).")
      .def_property_readonly("max_attempts", &Scenario::max_attempts,
                             "Attempts per scene before sampling fails.")
      .def_property_readonly("sampler", &Scenario::sampler,
                             "'rejection' (exact, the default), 'partial-rejection' (exact, for "
                             "clutter) or 'gibbs' (load(sampler=...)).")
      .def_property_readonly("gibbs", &Scenario::gibbs,
                             "With sampler='gibbs', once scenes were drawn: the chain's "
                             "schedule (autocorrelation time in sweeps, thinning, burn-in); "
                             "else None.")
      .def_property_readonly("partial_rejection", &Scenario::partial_rejection,
                             "With sampler='partial-rejection', once scenes were drawn: the "
                             "sites (their objects, coordinates and Poisson intensities) and "
                             "the pilot's rounds and probe runs a draw; else None.")
      .def_property_readonly("naive", &Scenario::naive, "True in the naive sampling mode.")
      .def_property_readonly("stable", &Scenario::stable,
                             "The simulated seconds of the physics check (stable=), or None.")
      .def_property_readonly("settle", &Scenario::settle,
                             "The most simulated seconds scenes get to settle (settle=), or None.");
  m.def(
      "compile_file",
      [](const std::string& path, const LoadOptions& options) {
        return Compile(path, std::nullopt, options);
      },
      py::arg("path"), py::arg("options"));
  m.def(
      "compile_text",
      [](const std::string& text, const std::string& name, const LoadOptions& options) {
        return Compile(name, text, options);
      },
      py::arg("text"), py::arg("name"), py::arg("options"));
  py::class_<LoadOptions>(m, "LoadOptions", "Compile options (internal; see load()).")
      .def(py::init<>())
      .def_readwrite("search_path", &LoadOptions::search_path)
      .def_readwrite("params", &LoadOptions::params)
      .def_readwrite("max_attempts", &LoadOptions::max_attempts)
      .def_readwrite("naive", &LoadOptions::naive)
      .def_readwrite("stable_s", &LoadOptions::stable_s)
      .def_readwrite("stable_move_m", &LoadOptions::stable_move_m)
      .def_readwrite("stable_turn_deg", &LoadOptions::stable_turn_deg)
      .def_readwrite("settle_s", &LoadOptions::settle_s)
      .def_readwrite("sampler", &LoadOptions::sampler);
}

}  // namespace prs::python
