// RunEpisodes: episodes run on the batch sampler's worker threads right after their scene is
// sampled (its `prepare` step), each thread with a controller of its own, and the records
// come back through the batch's reordering in index order.
#include <chrono>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>

#include "harness/harness.h"
#include "output/scene_json.h"

namespace prs::harness {
namespace {

// Controllers for the worker threads: a thread takes an idle one or makes a new one, so no
// more are made than episodes run at once, and none is used by two threads at a time.
class ControllerPool {
 public:
  explicit ControllerPool(const ControllerFactory& factory) : factory_(factory) {}

  std::unique_ptr<Controller> Take() {
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

  void Give(std::unique_ptr<Controller> controller) {
    std::lock_guard lock(mutex_);
    idle_.push_back(std::move(controller));
  }

 private:
  const ControllerFactory& factory_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Controller>> idle_;
};

EpisodeResult RunGuarded(Controller& controller, const sampling::SampledScene& scene,
                         const std::string& scene_json) {
  try {
    EpisodeResult result = controller.RunEpisode(scene, scene_json);
    if (!IsOutcomeName(result.outcome)) {
      return {"bad-answer", "the controller named its outcome '" + result.outcome +
                                "', which is not a lowercase-hyphenated name"};
    }
    return result;
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

// Runs one episode on a worker thread and fills in its record.
class EpisodeRunner {
 public:
  EpisodeRunner(const ControllerFactory& factory, const RunOptions& options)
      : pool_(factory), options_(options) {}

  EpisodeRecord Run(const sampling::SampledScene& scene) {
    const std::string scene_json = output::FormatSceneJson(scene);
    EpisodeRecord record;
    record.seed = scene.seed;
    record.index = scene.index;
    record.coordinates = scene.coordinates;
    record.features = CalcSceneFeatures(scene.scene);
    if (!record.coordinates.empty()) record.spec = options_.spec_hash;
    std::unique_ptr<Controller> controller = pool_.Take();
    const auto begin = std::chrono::steady_clock::now();
    record.result = RunGuarded(*controller, scene, scene_json);
    record.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    pool_.Give(std::move(controller));
    if (record.result.outcome != "success") RecordFailure(scene, scene_json, record);
    return record;
  }

 private:
  void RecordFailure(const sampling::SampledScene& scene, const std::string& scene_json,
                     EpisodeRecord& record) {
    if (!options_.scenario_args.empty()) {
      record.regenerate = FormatRegenerateCommand(options_.scenario_args, scene.seed, scene.index);
    }
    if (options_.save_failures_dir.empty()) return;
    const std::string stem = SaveFailedScene(options_.save_failures_dir, scene, scene_json);
    record.saved_scene = stem + ".json";
    if (options_.on_failure) options_.on_failure(scene, stem);
  }

  ControllerPool pool_;
  const RunOptions& options_;
};

sampling::BatchOptions MakeBatchOptions(const RunOptions& options) {
  sampling::BatchOptions batch;
  batch.sample = options.sample;
  batch.seed = options.seed;
  batch.start = options.start;
  batch.count = options.count;
  batch.threads = options.threads;
  batch.cancel = options.cancel;
  // Episodes are slow next to sampling: a short window keeps few finished scenes waiting.
  batch.window_per_thread = 4;
  return batch;
}

}  // namespace

RunSummary RunEpisodes(const lang::CompiledProgram& program, const ControllerFactory& factory,
                       const RunOptions& options) {
  EpisodeRunner runner(factory, options);
  std::mutex finished_mutex;
  std::map<uint64_t, EpisodeRecord> finished;  // by scene index, until consumed in order
  sampling::BatchCallbacks callbacks;
  callbacks.prepare = [&](sampling::BatchScene& item) {
    EpisodeRecord record = runner.Run(item.sampled);
    item.sampled.scene = {};  // freed on the worker; only the record travels on
    std::lock_guard lock(finished_mutex);
    finished.emplace(record.index, std::move(record));
  };
  RunSummary summary;
  std::set<std::string> warned;
  callbacks.consume = [&](sampling::BatchScene&& item) {
    std::unique_lock lock(finished_mutex);
    auto node = finished.extract(item.sampled.index);
    lock.unlock();
    for (const std::string& warning : node.mapped().result.warnings) {
      if (warned.insert(warning).second && options.on_warning) options.on_warning(warning);
    }
    if (options.on_record) options.on_record(node.mapped());
    summary.records.push_back(std::move(node.mapped()));
  };
  const sampling::BatchOptions batch = MakeBatchOptions(options);
  summary.threads = sampling::CountBatchThreads(batch);
  summary.sampling = sampling::SampleBatch(program, batch, callbacks);
  return summary;
}

}  // namespace prs::harness
