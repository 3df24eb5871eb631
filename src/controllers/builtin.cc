// Adapters from the simulated controllers' own result types to the harness's Controller
// interface, so that src/sim and src/harness need not know each other.
#include "controllers/builtin.h"

#include <mutex>

#include "harness/exec_controller.h"
#include "harness/registry.h"
#include "sim/table_cube_controller.h"

namespace prs::controllers {
namespace {

// The paper's case-study controller (MuJoCo, camera perception, inverse kinematics); one per
// worker thread, each with its own simulation and rendering context.
class TableCubeEpisodes : public harness::Controller {
 public:
  explicit TableCubeEpisodes(sim::TableCubeOptions options = {}) : controller_(options) {}
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                                    const std::string& /*scene_json*/) override {
    const sim::TaskOutcome outcome = controller_.Run(scene.scene);
    nlohmann::json extra = nlohmann::json::object();
    for (const auto& [name, value] : outcome.metrics) extra[name] = value;
    return {outcome.outcome, outcome.detail, std::move(extra)};
  }

 private:
  sim::TableCubeController controller_;
};

}  // namespace

void RegisterBuiltInControllers() {
  static std::once_flag registered;
  std::call_once(registered, [] {
    harness::RegisterController(
        "table-cube",
        "the paper's case study in MuJoCo: find the cube in the ceiling camera, pick, hand over, "
        "drop in the right tray",
        [] { return std::make_unique<TableCubeEpisodes>(); });
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

std::optional<harness::ControllerFactory> MakeControllerFactory(const std::string& name,
                                                                const std::string& exec,
                                                                double timeout_s,
                                                                const std::atomic<bool>* cancel) {
  if (!exec.empty()) {
    const harness::ExecOptions options{exec, timeout_s, cancel};
    return [options] { return std::make_unique<harness::ExecController>(options); };
  }
  RegisterBuiltInControllers();
  if (const harness::ControllerInfo* info = harness::FindController(name)) return info->factory;
  return std::nullopt;
}

}  // namespace prs::controllers
