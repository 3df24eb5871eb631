// EpisodeRunner and its controller pool (episode_runner.h).
#include "harness/episode_runner.h"

#include <chrono>
#include <fstream>
#include <stdexcept>

#include "output/scene_json.h"

namespace prs::harness::internal {
namespace {

EpisodeResult RunGuarded(Controller& controller, const sampling::SampledScene& scene,
                         const std::string& scene_json) {
  try {
    EpisodeResult result = controller.RunEpisode(scene, scene_json);
    if (!IsOutcomeName(result.outcome)) {
      return {"bad-answer", "the controller named its outcome '" + result.outcome +
                                "', which is not a lowercase-hyphenated name"};
    }
    return result;
  } catch (const ControllerStartError&) {
    throw;  // stops the run: every later episode would fail the same way
  } catch (const std::exception& error) {
    return {"controller-error", error.what()};
  }
}

// DIR/seed-S-index-I.json holds the scene line; returns the stem DIR/seed-S-index-I.
std::string SaveFailedScene(const std::string& dir, const sampling::SampledScene& scene,
                            const std::string& scene_json) {
  const std::string stem =
      dir + "/seed-" + std::to_string(scene.seed) + "-index-" + std::to_string(scene.index);
  const std::string path = stem + ".json";
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file << scene_json << '\n';
  file.close();
  if (!file) throw std::runtime_error("cannot write the failing scene to " + path);
  return stem;
}

}  // namespace

std::unique_ptr<Controller> ControllerPool::Take() {
  {
    std::lock_guard lock(mutex_);
    if (!idle_.empty()) {
      std::unique_ptr<Controller> controller = std::move(idle_.back());
      idle_.pop_back();
      return controller;
    }
  }
  std::unique_ptr<Controller> controller = factory_();
  if (!controller) throw std::runtime_error("the controller factory returned no controller");
  return controller;
}

void ControllerPool::Give(std::unique_ptr<Controller> controller) {
  std::lock_guard lock(mutex_);
  idle_.push_back(std::move(controller));
}

EpisodeRecord EpisodeRunner::Run(const sampling::SampledScene& scene, std::string scene_json) {
  if (scene_json.empty()) scene_json = output::FormatSceneJson(scene);
  EpisodeRecord record;
  record.seed = scene.seed;
  record.index = scene.index;
  record.coordinates = scene.coordinates;
  record.features = CalcSceneFeatures(scene.scene);
  if (!options_.spec_hash.empty()) {
    record.spec = options_.spec_hash;
    record.scene_options = options_.scene_options;
  }
  std::unique_ptr<Controller> controller = pool_.Take();
  const auto begin = std::chrono::steady_clock::now();
  record.result = RunGuarded(*controller, scene, scene_json);
  record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  pool_.Give(std::move(controller));
  if (record.result.outcome != "success") RecordFailure(scene, scene_json, record);
  return record;
}

void EpisodeRunner::RecordFailure(const sampling::SampledScene& scene,
                                  const std::string& scene_json, EpisodeRecord& record) {
  if (!options_.scenario_args.empty()) {
    record.regenerate = FormatRegenerateCommand(options_.scenario_args, scene.seed, scene.index);
  }
  if (options_.save_failures_dir.empty()) return;
  const std::string stem = SaveFailedScene(options_.save_failures_dir, scene, scene_json);
  record.saved_scene = stem + ".json";
  if (options_.on_failure) options_.on_failure(scene, stem);
}

}  // namespace prs::harness::internal
