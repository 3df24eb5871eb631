// Scene coordinates, failure search and failure reports from Python (docs/python.md,
// docs/search.md): Scenario.coordinates(), Scenario.search() with a Python callable as the
// controller, and report() over records.
#include "search/search.h"

#include <pybind11/stl.h>

#include <atomic>

#include "bindings.h"
#include "controllers/builtin.h"
#include "harness/harness.h"
#include "search/estimate.h"
#include "search/like.h"
#include "search/report.h"

namespace prs::python {
namespace {

// A Python callable as a controller: called with the Scene, it returns an outcome name or a
// dict {"outcome": ..., "detail": ..., "score": ..., anything else -> extra}. Runs on the
// calling thread with the GIL held (the search runs with one thread).
class PythonController : public harness::Controller {
 public:
  PythonController(ProgramPtr program, py::function function, std::atomic<bool>* cancel)
      : program_(std::move(program)), function_(std::move(function)), cancel_(cancel) {}

  harness::EpisodeResult RunEpisode(const sampling::SampledScene& sampled,
                                    const std::string&) override {
    auto scene = std::make_shared<Scene>(Scene{program_, sampled});
    py::object answer;
    try {
      answer = function_(scene);
    } catch (py::error_already_set& error) {
      // Ctrl-C (or a KeyboardInterrupt raised by the controller) stops the search; any other
      // exception is this episode's controller-error.
      if (error.matches(PyExc_KeyboardInterrupt)) cancel_->store(true);
      throw;
    }
    return ConvertControllerAnswer(answer);
  }

 private:
  ProgramPtr program_;
  py::function function_;
  std::atomic<bool>* cancel_;
};

// Called in a catch block: Ctrl-C (the run was cancelled) as KeyboardInterrupt, nothing to
// search as ValueError, a scenario error as ScenarioError; anything else as it is.
[[noreturn]] void RaiseSearchError(const lang::CompiledProgram& program) {
  try {
    throw;
  } catch (const sampling::BatchCancelled&) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  } catch (const search::NothingToSearch& error) {
    throw py::value_error(error.what());
  } catch (const lang::ScenarioError& error) {
    RaiseScenarioError(error.diagnostic(), program.sources,
                       lang::RenderDiagnostic(error.diagnostic(), program.sources));
  }
}

}  // namespace

py::list ToPythonRecords(const std::vector<harness::EpisodeRecord>& records) {
  const py::object loads = py::module_::import("json").attr("loads");
  py::list out;
  for (const harness::EpisodeRecord& record : records) {
    out.append(loads(harness::FormatRecordJson(record)));
  }
  return out;
}

harness::EpisodeResult ConvertControllerAnswer(const py::object& answer) {
  harness::EpisodeResult result;
  if (py::isinstance<py::str>(answer)) {
    result.outcome = answer.cast<std::string>();
    result.detail = "the controller returned " + result.outcome;
    return result;
  }
  if (!py::isinstance<py::dict>(answer)) {
    return {"bad-answer",
            "the controller must return an outcome name or a dict with "
            "\"outcome\", not " +
                std::string(py::str(answer.get_type().attr("__name__")))};
  }
  py::dict dict = answer.cast<py::dict>();
  if (!dict.contains("outcome") || !py::isinstance<py::str>(dict["outcome"])) {
    return {"bad-answer", "the controller's dict has no \"outcome\" string"};
  }
  result.outcome = dict["outcome"].cast<std::string>();
  result.detail = dict.contains("detail") ? std::string(py::str(dict["detail"]))
                                          : "the controller returned " + result.outcome;
  if (dict.contains("score")) {
    const py::object score = dict["score"];
    const bool number = py::isinstance<py::float_>(score) || py::isinstance<py::int_>(score);
    if (!number || !std::isfinite(score.cast<double>())) {
      return {"bad-answer",
              "the controller's \"score\" must be a finite number (larger is "
              "safer, 0 or less a failure)"};
    }
    result.score = score.cast<double>();
  }
  const py::object dumps = py::module_::import("json").attr("dumps");
  for (const auto& [key, value] : dict) {
    const std::string name = py::str(key);
    if (name == "outcome" || name == "detail" || name == "score") continue;
    result.extra[name] = nlohmann::json::parse(
        dumps(value, py::arg("default") = py::module_::import("builtins").attr("str"))
            .cast<std::string>());
  }
  return result;
}

py::list ListCoordinates(const lang::CompiledProgram& program,
                         const sampling::SampleOptions& options) {
  py::list out;
  for (const lang::CoordinateInfo& c : sampling::DescribeCoordinates(program, options)) {
    const lang::LineColumn where = program.sources.CalcLineColumn(c.span.file, c.span.begin);
    py::dict d;
    d["name"] = c.name;
    d["draw"] = c.draw;
    d["file"] = program.sources.path(c.span.file);
    d["line"] = where.line;
    d["column"] = where.column;
    out.append(d);
  }
  return out;
}

py::list RunPythonSearch(const ProgramPtr& program, const sampling::SampleOptions& sample,
                         const py::function& controller, int64_t budget,
                         const std::string& strategy, uint64_t seed, std::optional<int64_t> batch,
                         const std::string& scene_options) {
  search::SearchOptions options;
  options.run.scene_options = scene_options;
  if (strategy == "bo") {
    // Bayesian optimisation: the points of each generation come from probrobscene._bo (a
    // Gaussian process on scikit-learn), called on this thread with the GIL held.
    options.strategy = search::Strategy::kExternal;
    options.external_name = "bo";
    const py::object propose = py::module_::import("probrobscene._bo").attr("propose");
    options.propose = [propose, seed](const std::vector<harness::EpisodeRecord>& so_far,
                                      int64_t count, int dimension, int generation) {
      py::list X, y;
      for (const harness::EpisodeRecord& record : so_far) {
        if (static_cast<int>(record.coordinates.size()) != dimension) continue;
        X.append(py::cast(record.coordinates));
        y.append(search::CalcBadness(record));
      }
      return propose(X, y, count, dimension, seed, generation)
          .cast<std::vector<std::vector<double>>>();
    };
    if (!batch) batch = 10;
  } else if (!search::ParseStrategy(strategy, &options.strategy)) {
    throw py::value_error("unknown strategy '" + strategy +
                          "' (strategies: ce, anneal, random, bo)");
  }
  if (budget < 1) throw py::value_error("budget must be >= 1, got " + std::to_string(budget));
  if (batch && *batch < 1)
    throw py::value_error("batch must be >= 1, got " + std::to_string(*batch));
  options.budget = budget;
  options.batch = batch.value_or(0);
  options.run.sample = sample;
  options.run.seed = seed;
  options.run.threads = 1;  // the Python controller runs on this thread, with the GIL
  std::atomic<bool> cancel{false};
  options.run.cancel = &cancel;
  search::SearchSummary summary;
  try {
    summary = search::RunSearch(
        *program, [&] { return std::make_unique<PythonController>(program, controller, &cancel); },
        options);
  } catch (...) {
    RaiseSearchError(*program);
  }
  return ToPythonRecords(summary.records);
}

py::dict ToPythonEstimate(const search::Estimate& e) {
  py::dict out;
  out["episodes"] = e.episodes;
  out["ess"] = e.ess;
  out["reliable"] = e.reliable;
  if (!e.reliable) out["unreliable_because"] = search::DescribeUnreliable(e);
  py::dict estimates;
  for (const search::OutcomeEstimate& o : e.outcomes) {
    py::dict d;
    d["p"] = o.p;
    d["ci95"] = py::make_tuple(o.ci_low, o.ci_high);
    d["ess"] = e.ess;
    d["failing_episodes"] = o.episodes;
    d["iid_episodes_for_same_precision"] = o.iid_episodes;
    estimates[py::str(o.outcome)] = d;
  }
  out["estimates"] = estimates;
  if (e.outcomes.empty()) out["upper_bound_95"] = e.upper_bound;
  return out;
}

py::dict RunPythonEstimate(const ProgramPtr& program, const sampling::SampleOptions& sample,
                           const py::object& controller, int64_t budget, uint64_t seed, int threads,
                           const std::string& scene_options) {
  if (budget < search::kMinEstimateBudget) {
    throw py::value_error("budget must be >= " + std::to_string(search::kMinEstimateBudget) +
                          " (episodes to adapt a proposal and then sample), got " +
                          std::to_string(budget));
  }
  if (threads < 1) throw py::value_error("threads must be >= 1");
  search::EstimateOptions options;
  options.budget = budget;
  options.run.sample = sample;
  options.run.seed = seed;
  options.run.spec_hash = search::CalcSpecHash(*program);
  options.run.scene_options = scene_options;
  std::atomic<bool> cancel{false};
  options.run.cancel = &cancel;
  search::EstimateSummary summary;
  try {
    if (py::isinstance<py::str>(controller)) {
      const std::string name = controller.cast<std::string>();
      auto factory = controllers::MakeControllerFactory({name, "", 60, false, 120}, nullptr);
      if (!factory) {
        throw py::value_error("unknown controller '" + name +
                              "' (controllers: " + controllers::ListControllerNames() + ")");
      }
      options.run.threads = threads;
      py::gil_scoped_release no_gil;
      summary = search::RunEstimate(*program, *factory, options);
    } else {
      const py::function function = controller.cast<py::function>();
      options.run.threads = 1;  // the Python controller runs on this thread, with the GIL
      summary = search::RunEstimate(
          *program, [&] { return std::make_unique<PythonController>(program, function, &cancel); },
          options);
    }
  } catch (...) {
    RaiseSearchError(*program);
  }
  py::dict out = ToPythonEstimate(summary.estimate);
  out["records"] = ToPythonRecords(summary.records);
  return out;
}

void BindSearch(py::module_& m) {
  m.def(
      "report_markdown",
      [](const std::vector<std::string>& lines, const std::string& title) {
        try {
          return search::FormatFailureReport(search::ParseReportRecords(lines, title), {title, ""},
                                             nullptr);
        } catch (const std::runtime_error& error) {
          throw py::value_error(error.what());
        }
      },
      py::arg("lines"), py::arg("title"));
}

}  // namespace prs::python
