// Many scenes at once: scenes start..start+count-1 of one seed sampled by worker threads, each
// with its own SceneSampler, and handed back in index order through a bounded reorder window,
// so the output is the same for any thread count and memory does not grow with `count`.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "sampling/sampler.h"

namespace prs::sampling {

struct BatchOptions {
  SampleOptions sample;
  uint64_t seed = 0;
  uint64_t start = 0;  // index of the first scene
  int64_t count = 0;   // number of scenes; start + count - 1 must not overflow uint64_t
  int threads = 1;     // worker threads; 1 samples on the calling thread
  /// Scenes that may be finished ahead of the next one to hand back, per thread. Bounds memory.
  int window_per_thread = 256;
  /// The most scenes a worker claims at once (runs are handed over whole). Fewer for slow
  /// scenes (episodes), so that the threads' last claims end together.
  int max_claim = 64;
  /// Polled about every 50 ms and between scenes; once true, the batch stops (BatchCancelled).
  const std::atomic<bool>* cancel = nullptr;
};

/// One scene of a batch, with room for a caller's per-scene result computed on the worker.
struct BatchScene {
  SampledScene sampled;
  std::string rendered;  // filled by BatchCallbacks::prepare, if the caller gives one
};

struct BatchCallbacks {
  /// Optional. Runs on a worker thread right after a scene is sampled, in no particular
  /// order: per-scene work that should run in parallel (e.g. formatting it as JSON).
  std::function<void(BatchScene&)> prepare = {};
  /// Runs on the calling thread, once per scene, in index order. Optional (a batch run only
  /// for its summary).
  std::function<void(BatchScene&&)> consume = {};
  /// Optional. Runs on the calling thread about every 50 ms while it waits for the next scene
  /// (e.g. to redraw progress while one scene takes many attempts). When given, scenes are
  /// sampled on worker threads even for threads == 1, so the calling thread stays free.
  std::function<void()> tick = {};
  /// Optional, for text written in index order (`prs sample`'s JSON Lines): runs on a worker
  /// after `prepare` and appends the scene's text to `text`, the one buffer of the scenes the
  /// worker claimed together; it may also drop what `consume` does not need. The calling
  /// thread hands each such run's text to `write` at once, before `consume` gets its scenes
  /// (so a cancel stops between runs), and no string is made, copied or freed per scene on
  /// the calling thread.
  std::function<void(BatchScene&, std::string& text)> format = {};
  /// Required with `format`: runs on the calling thread, in index order, with the text of
  /// `count` consecutive scenes.
  std::function<void(std::string_view text, int64_t count)> write = {};
};

/// Totals over the scenes handed to `consume`.
struct BatchSummary {
  int64_t scenes = 0;
  int64_t attempts = 0;
  RejectionCounts rejections;

  void Add(const SampledScene& sampled);
  /// Adds the totals of later scenes (kept rejection examples stay the earliest).
  void Merge(const BatchSummary& later);
};

/// Thrown by SampleBatch when BatchOptions::cancel became true.
class BatchCancelled : public std::runtime_error {
 public:
  BatchCancelled() : std::runtime_error("the batch was cancelled") {}
};

/// The threads SampleBatch samples on: min(threads, count), at least 1 (1 means the calling
/// thread alone).
int CountBatchThreads(const BatchOptions& options);

/// Samples scenes start..start+count-1 of `seed` and hands each to `callbacks.consume` in index
/// order. Scene i is SceneSampler::Sample(seed, i), so the scenes do not depend on `threads`.
/// If scenes fail, every scene before the lowest failing index is consumed, the workers stop,
/// and the exception of that lowest index is rethrown (lang::ScenarioError, or whatever
/// `prepare` threw). An exception from `consume` stops the workers and propagates.
/// Throws std::invalid_argument for count < 0, threads < 1 or an index range past 2^64 - 1.
BatchSummary SampleBatch(const lang::CompiledProgram& program, const BatchOptions& options,
                         const BatchCallbacks& callbacks);

}  // namespace prs::sampling
