// Adapters from the simulated controllers' own result types to the harness's Controller
// interface, so that src/sim and src/harness need not know each other.
#include "controllers/builtin.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "controllers/perception_worker.h"
#include "export/export.h"
#include "harness/exec_controller.h"
#include "harness/persistent_controller.h"
#include "harness/registry.h"
#include "sim/table_cube_controller.h"

namespace prs::controllers {
namespace {

// The paper's case-study controller (MuJoCo, camera perception, inverse kinematics); one per
// worker thread, each with its own simulation and rendering context.
// With a perception pool (--perception), each one holds a perception worker too.
class TableCubeEpisodes : public harness::Controller {
 public:
  explicit TableCubeEpisodes(sim::TableCubeOptions options = {},
                             std::shared_ptr<harness::LineWorkerPool> perception = nullptr)
      : perception_(perception ? std::make_unique<PerceptionClient>(std::move(perception))
                               : nullptr),
        controller_(WithPerception(std::move(options), perception_.get())) {}
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                                    const std::string& /*scene_json*/) override {
    if (perception_) perception_->SetScene(scene.seed, scene.index);
    sim::TaskOutcome outcome = controller_.Run(scene.scene);
    nlohmann::json extra = nlohmann::json::object();
    for (const auto& [name, value] : outcome.metrics) extra[name] = value;
    for (const auto& [name, value] : outcome.flags) extra[name] = value;
    harness::EpisodeResult result{outcome.outcome, outcome.detail, std::move(extra)};
    result.warnings = std::move(outcome.warnings);
    return result;
  }

 private:
  static sim::TableCubeOptions WithPerception(sim::TableCubeOptions options,
                                              PerceptionClient* client) {
    if (client) {
      options.perception = [client](const sim::CubeSightingRequest& request) {
        return client->Ask(request);
      };
    }
    return options;
  }

  std::unique_ptr<PerceptionClient> perception_;  // before controller_, whose options use it
  sim::TableCubeController controller_;
};

// The user's own controller (--exec) reads the scene as `prs export` writes it, where only
// objects with a positive mass are free bodies: warn when a scene has none, since a simulated
// controller can then move nothing.
class ExecWithSceneCheck : public harness::Controller {
 public:
  explicit ExecWithSceneCheck(std::unique_ptr<harness::Controller> exec) : exec_(std::move(exec)) {}
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                                    const std::string& scene_json) override {
    harness::EpisodeResult result = exec_->RunEpisode(scene, scene_json);
    if (!HasFreeBody(scene.scene)) result.warnings.push_back(kNoFreeBodyWarning);
    return result;
  }

 private:
  static bool HasFreeBody(const lang::Scene& scene) {
    const exporting::ExportScene exported = exporting::MakeExportScene(scene, "");
    return std::any_of(exported.bodies.begin(), exported.bodies.end(),
                       [](const exporting::Body& b) { return b.is_free(); });
  }
  std::unique_ptr<harness::Controller> exec_;
};

}  // namespace

const char* const kNoFreeBodyWarning =
    "a scene has no free body: no object in it has a positive `mass`, so a simulator that loads "
    "it as `prs export` writes it (docs/export.md) fixes every object in place. Give what the "
    "controller must move a mass in kilograms (`mass: 0.1` in its class)";

void RegisterBuiltInControllers() {
  static std::once_flag registered;
  std::call_once(registered, [] {
    harness::RegisterController(
        "table-cube",
        "the paper's case study in MuJoCo: find the cube in the ceiling camera, pick, hand over, "
        "drop in the right tray",
        [] { return std::make_unique<TableCubeEpisodes>(); });
    harness::RegisterController(
        "table-cube-paper",
        "the original tool's case study in MuJoCo: the cube seen alone by the depth camera, the "
        "original's motions and its success criterion (within 0.453 m of the tray)",
        [] { return std::make_unique<TableCubeEpisodes>(sim::MakePaperTableCubeOptions()); });
    harness::RegisterController(
        "table-cube-clear-view",
        "table-cube with the fix of docs/case_study.md: both arms turn away before each picture",
        [] {
          sim::TableCubeOptions options;
          options.clear_view_before_sighting = true;
          return std::make_unique<TableCubeEpisodes>(options);
        });
  });
}

std::string ListControllerNames() {
  RegisterBuiltInControllers();
  std::string names;
  for (const harness::ControllerInfo& info : harness::ListControllers()) {
    names += (names.empty() ? "" : ", ") + info.name;
  }
  return names;
}

std::optional<harness::ControllerFactory> MakeControllerFactory(const ControllerChoice& choice,
                                                                const std::atomic<bool>* cancel) {
  if (!choice.perception.empty()) {
    if (choice.name != "table-cube" && choice.name != "table-cube-clear-view") {
      throw std::invalid_argument(
          "--perception: only --controller table-cube and table-cube-clear-view take a "
          "perception worker" +
          (choice.name.empty() ? std::string(", and no --controller was given")
                               : ", not '" + choice.name + "'"));
    }
    sim::TableCubeOptions options;
    options.clear_view_before_sighting = choice.name == "table-cube-clear-view";
    const auto pool =
        MakePerceptionPool({choice.perception, choice.timeout_s, choice.startup_timeout_s, cancel});
    return [options, pool] { return std::make_unique<TableCubeEpisodes>(options, pool); };
  }
  if (!choice.exec.empty() && choice.persistent) {
    harness::ControllerFactory workers = harness::MakePersistentControllerFactory(
        {choice.exec, choice.timeout_s, choice.startup_timeout_s, cancel});
    return [workers] { return std::make_unique<ExecWithSceneCheck>(workers()); };
  }
  if (!choice.exec.empty()) {
    const harness::ExecOptions options{choice.exec, choice.timeout_s, cancel};
    return [options] {
      return std::make_unique<ExecWithSceneCheck>(
          std::make_unique<harness::ExecController>(options));
    };
  }
  RegisterBuiltInControllers();
  if (const harness::ControllerInfo* info = harness::FindController(choice.name)) {
    return info->factory;
  }
  return std::nullopt;
}

}  // namespace prs::controllers
