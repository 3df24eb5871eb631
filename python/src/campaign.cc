// Campaigns from Python (docs/cluster.md): the same campaign directories, shard files, status and
// merge as `prs campaign` (test, sample and search campaigns), for probrobscene.campaign, which
// maps shards over a Dask cluster.
#include "campaign/campaign.h"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "dataset/dataset.h"
#include "campaign/search_campaign.h"
#include "campaign/slurm.h"
#include "controllers/builtin.h"
#include "output/line_writer.h"
#include "sim/settle.h"

namespace prs::python {
namespace {

// CampaignError (not a campaign, a changed spec, a shard out of range, shards not done) is a
// ValueError; a scenario error in the copied spec is a ScenarioError.
template <typename Body>
auto CallCampaign(Body body) -> decltype(body()) {
  try {
    return body();
  } catch (const campaign::CampaignError& error) {
    throw py::value_error(error.what());
  }
}

harness::ControllerFactory ChooseFactory(const campaign::CampaignSpec& spec) {
  const controllers::ControllerChoice choice{spec.controller, spec.exec, spec.timeout_s,
                                             spec.persistent, spec.startup_timeout_s};
  if (auto factory = controllers::MakeControllerFactory(choice, nullptr)) return *factory;
  throw py::value_error("unknown controller '" + spec.controller +
                        "' (controllers: " + controllers::ListControllerNames() + ")");
}

std::string Init(const std::string& dir, const std::string& path, const LoadOptions& load,
                 uint64_t count, uint64_t shard_size, const py::object& seed_arg,
                 const std::string& controller, const std::string& exec, double timeout_s,
                 bool persistent, double startup_timeout_s, const std::string& strategy,
                 uint64_t batch, bool estimate, const py::object& dataset) {
  campaign::CampaignSpec spec;
  spec.kind = controller.empty() && exec.empty() ? "sample" : "test";
  if (!dataset.is_none()) {
    // probrobscene.campaign.init's dataset=dict(cameras=..., size=..., format=..., labels=...).
    if (spec.kind != "sample" || !strategy.empty() || estimate)
      throw py::value_error("a dataset campaign takes no controller, exec, search or estimate");
    const py::dict d = dataset.cast<py::dict>();
    spec.kind = "dataset";
    spec.dataset.cameras = d["cameras"].cast<std::vector<std::string>>();
    spec.dataset.width = d["width"].cast<int>();
    spec.dataset.height = d["height"].cast<int>();
    spec.dataset.bop = d["bop"].cast<bool>();
    spec.dataset.coco = d["coco"].cast<bool>();
    spec.dataset.labels = d["labels"].cast<std::vector<std::string>>();
    spec.dataset.jpeg = d["jpeg"].cast<bool>();
  }
  if (!strategy.empty()) {
    if (spec.kind == "sample") throw py::value_error("a search needs a controller or exec");
    spec.kind = "search";
    spec.strategy = strategy;
    spec.batch = batch;  // 0: as prs search picks
  }
  if (estimate) {
    if (spec.kind != "test") {
      throw py::value_error(spec.kind == "search" ? "give search= or estimate=True, not both"
                                                  : "an estimate needs a controller or exec");
    }
    if (count < uint64_t(search::kMinEstimateBudget)) {
      throw py::value_error("an estimate's budget n must be >= " +
                            std::to_string(search::kMinEstimateBudget));
    }
    spec.kind = "estimate";
  }
  spec.controller = controller;
  spec.exec = exec;
  spec.timeout_s = timeout_s;
  spec.persistent = persistent;
  spec.startup_timeout_s = startup_timeout_s;
  if (persistent && exec.empty()) throw py::value_error("persistent=True needs exec");
  if (!(timeout_s > 0) || !(startup_timeout_s > 0)) {
    throw py::value_error("timeout and startup_timeout must be above 0 seconds");
  }
  if (!controller.empty() && !exec.empty()) {
    throw py::value_error("give a controller or exec, not both");
  }
  if (!controller.empty()) ChooseFactory(spec);  // an unknown name fails now, not in a shard
  const std::shared_ptr<lang::CompiledProgram> program = CompileProgram(path, std::nullopt, load);
  // The words of `prs test FILE -I DIR -p NAME=VALUE --naive`, as the records' regenerate
  // commands name the scenario.
  spec.scenario_words = {path};
  for (const std::string& dir_name : load.search_path) {
    spec.scenario_words.insert(spec.scenario_words.end(), {"-I", dir_name});
  }
  for (const auto& [name, value] : load.params) {
    spec.scenario_words.insert(spec.scenario_words.end(), {"-p", name + "=" + value});
  }
  const std::vector<std::string> scene_words = MakeSceneOptionWords(load);
  spec.scenario_words.insert(spec.scenario_words.end(), scene_words.begin(), scene_words.end());
  spec.params = load.params;
  spec.naive = load.naive;
  spec.sampler = load.sampler;
  spec.stable_s = load.stable_s;
  spec.stable_move_m = load.stable_move_m;
  spec.stable_turn_deg = load.stable_turn_deg;
  spec.settle_s = load.settle_s;
  spec.max_attempts = load.max_attempts;
  spec.seed = ToSceneNumber(seed_arg, "seed");
  spec.count = count;
  spec.shard_size = shard_size;
  spec.version = PRS_VERSION;
  return CallCampaign([&] {
    try {
      if (spec.kind == "dataset" && spec.dataset.cameras.empty()) {
        spec.dataset.cameras =
            dataset::ListDefaultCameras(*program, campaign::MakeSampleOptions(spec), spec.seed);
        if (spec.dataset.cameras.empty())
          throw py::value_error("scene 0 of the seed has no camera object: name one in cameras=");
      }
      return campaign::InitCampaign(dir, *program, spec).id;
    } catch (const lang::ScenarioError& error) {  // a search's trial attempts
      RaiseScenarioError(error.diagnostic(), program->sources,
                         lang::RenderDiagnostic(error.diagnostic(), program->sources));
    }
  });
}

// Runs shard k with the GIL released (a Dask worker keeps answering its scheduler meanwhile).
void RunShard(const std::string& dir, uint64_t k, int threads) {
  if (threads < 1) throw py::value_error("threads must be >= 1, got " + std::to_string(threads));
  CallCampaign([&] {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(dir);
    const std::unique_ptr<lang::CompiledProgram> program = campaign::CompileCampaign(dir, spec);
    std::optional<harness::ControllerFactory> factory;
    if (spec.kind != "sample" && spec.kind != "dataset") factory = ChooseFactory(spec);
    std::vector<std::string> warnings;
    try {
      py::gil_scoped_release release;
      // The physics check of a campaign made with stable= or settle=.
      const sampling::SceneTest physics = sim::MakePhysicsTest(
          {spec.stable_s, spec.stable_move_m, spec.stable_turn_deg, spec.settle_s});
      const auto collect = [&](const std::string& warning) { warnings.push_back(warning); };
      campaign::RunShard(dir, spec, *program, k, factory ? &*factory : nullptr, threads, nullptr,
                         {collect, physics});
    } catch (const lang::ScenarioError& error) {
      RaiseScenarioError(error.diagnostic(), program->sources,
                         lang::RenderDiagnostic(error.diagnostic(), program->sources));
    }
    // Each distinct warning of the shard's episodes, as a Python warning (the GIL is held).
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& warning : warnings) warn(warning);
  });
}

py::dict Status(const std::string& dir) {
  return CallCampaign([&] {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(dir);
    const campaign::SlurmQueue queue = campaign::QuerySlurmQueue(dir, spec);
    const std::vector<campaign::ShardState> states = campaign::DescribeShards(dir, spec, queue);
    py::dict counts;
    for (int kind = 0; kind < campaign::kShardStateKinds; ++kind) {
      counts[campaign::ShardStateName(static_cast<campaign::ShardState::Kind>(kind))] = 0;
    }
    py::list shards, to_run;
    for (uint64_t k = 0; k < states.size(); ++k) {
      // Not done and not left to Slurm: what probrobscene.campaign.run runs.
      const auto task = queue.tasks.find(k);
      if (states[k].kind != campaign::ShardState::Kind::kDone &&
          states[k].kind != campaign::ShardState::Kind::kWaiting &&
          (task == queue.tasks.end() || !task->second.active())) {
        to_run.append(k);
      }
      const char* name = campaign::ShardStateName(states[k].kind);
      counts[name] = counts[name].cast<int64_t>() + 1;
      py::dict shard;
      shard["shard"] = k;
      shard["state"] = name;
      shard["why"] = states[k].why;
      shards.append(shard);
    }
    py::dict status;
    status["campaign"] = spec.id;
    status["kind"] = spec.kind;
    status["count"] = spec.count;
    status["shards"] = shards;
    status["counts"] = counts;
    status["to_run"] = to_run;
    status["queue"] = queue.available ? py::object(py::none()) : py::str(queue.why_not);
    return status;
  });
}

// Search and estimate campaigns: plans the first generation that is not done (when the one
// before it is), and returns whether the last is planned. Other campaigns: always "finished".
bool Plan(const std::string& dir) {
  return CallCampaign([&] {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(dir);
    if (!spec.planned()) return true;
    const std::unique_ptr<lang::CompiledProgram> program = campaign::CompileCampaign(dir, spec);
    return campaign::PlanSearchStep(dir, spec, *program).finished;
  });
}

py::dict Merge(const std::string& dir, const std::string& output, bool partial) {
  return CallCampaign([&] {
    const campaign::CampaignSpec spec = campaign::ReadCampaign(dir);
    if (spec.kind == "estimate") {
      // The records with their weights, as prs estimate -o writes them, and the estimate.
      if (partial) throw py::value_error("an estimate's shards merge only when all are done");
      const campaign::EstimateMerge merge =
          campaign::MergeEstimate(dir, spec, *campaign::CompileCampaign(dir, spec));
      output::LineWriter out(output);
      for (const std::string& line : merge.lines) out.AddLine(line);
      out.Commit();
      py::dict result;
      result["lines"] = merge.lines.size();
      result["skipped"] = py::list();
      result["estimate"] = ToPythonEstimate(merge.summary.estimate);
      return result;
    }
    if (spec.kind == "dataset") {
      if (partial) throw py::value_error("a dataset campaign merges when every shard is done");
      campaign::MergeDatasetShards(dir, spec, output);
      py::dict result;
      result["lines"] = spec.count;  // scenes
      result["skipped"] = py::list();
      result["dataset"] = output;
      return result;
    }
    std::vector<uint64_t> skipped;
    const std::vector<std::string> lines = campaign::MergeShards(dir, spec, partial, &skipped);
    output::LineWriter out(output);
    for (const std::string& line : lines) out.AddLine(line);
    out.Commit();
    py::dict result;
    result["lines"] = lines.size();
    result["skipped"] = skipped;
    return result;
  });
}

}  // namespace

void BindCampaign(py::module_& m) {
  m.def("campaign_init", &Init, py::arg("dir"), py::arg("path"), py::arg("options"),
        py::arg("count"), py::arg("shard_size"), py::arg("seed"), py::arg("controller"),
        py::arg("exec"), py::arg("timeout_s"), py::arg("persistent"), py::arg("startup_timeout_s"),
        py::arg("strategy"), py::arg("batch"), py::arg("estimate"), py::arg("dataset"));
  m.def("campaign_plan", &Plan, py::arg("dir"));
  m.def("campaign_run_shard", &RunShard, py::arg("dir"), py::arg("shard"), py::arg("threads"));
  m.def("campaign_status", &Status, py::arg("dir"));
  m.def("campaign_merge", &Merge, py::arg("dir"), py::arg("output"), py::arg("partial"));
}

}  // namespace prs::python
