// One episode as RunEpisodes and ReplayEpisodes run it on a worker thread: a controller taken
// from a pool, the outcome guarded, the record filled in, a failing scene saved. Internal to
// src/harness.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "harness/harness.h"

namespace prs::harness::internal {

/// Controllers for the worker threads: a thread takes an idle one or makes a new one, so no
/// more are made than episodes run at once, and none is used by two threads at a time.
class ControllerPool {
 public:
  explicit ControllerPool(const ControllerFactory& factory) : factory_(factory) {}
  std::unique_ptr<Controller> Take();
  void Give(std::unique_ptr<Controller> controller);

 private:
  const ControllerFactory& factory_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Controller>> idle_;
};

/// Runs one episode and fills in its record. Thread-safe.
class EpisodeRunner {
 public:
  EpisodeRunner(const ControllerFactory& factory, const RunOptions& options)
      : pool_(factory), options_(options) {}

  /// The episode of `scene`, whose controller input is `scene_json` (FormatSceneJson(scene)
  /// when empty). Throws ControllerStartError (the controller cannot start) and
  /// std::runtime_error (a failing scene cannot be saved).
  EpisodeRecord Run(const sampling::SampledScene& scene, std::string scene_json = {});

 private:
  void RecordFailure(const sampling::SampledScene& scene, const std::string& scene_json,
                     EpisodeRecord& record);

  ControllerPool pool_;
  const RunOptions& options_;
};

}  // namespace prs::harness::internal
