// The parallel batch sampler: workers claim runs of scene indices in increasing order and hand
// each finished run over whole (sampling/run_queue.h); the calling thread takes the runs out
// in index order. No scene is claimed more than `window` scenes ahead of the consumer, which
// bounds memory.
#include "sampling/batch.h"

#include <algorithm>
#include <exception>
#include <limits>
#include <optional>
#include <thread>
#include <vector>

#include "sampling/gibbs.h"
#include "sampling/run_queue.h"

namespace prs::sampling {

void BatchSummary::Add(const SampledScene& sampled) {
  ++scenes;
  attempts += sampled.attempts;
  rejections.Merge(sampled.rejections);
}

void BatchSummary::Merge(const BatchSummary& later) {
  scenes += later.scenes;
  attempts += later.attempts;
  rejections.Merge(later.rejections);
}

namespace {

bool IsCancelled(const BatchOptions& options) {
  return options.cancel && options.cancel->load(std::memory_order_relaxed);
}

void CheckArguments(const BatchOptions& options) {
  if (options.count < 0) {
    throw std::invalid_argument("SampleBatch: count must be >= 0, got " +
                                std::to_string(options.count));
  }
  if (options.threads < 1) {
    throw std::invalid_argument("SampleBatch: threads must be >= 1, got " +
                                std::to_string(options.threads));
  }
  const uint64_t last_allowed_start =
      std::numeric_limits<uint64_t>::max() -
      static_cast<uint64_t>(std::max<int64_t>(options.count - 1, 0));
  if (options.start > last_allowed_start) {
    throw std::invalid_argument("SampleBatch: scenes " + std::to_string(options.start) + " + " +
                                std::to_string(options.count) + " run past index 2^64 - 1");
  }
}

// One thread: no queue, no locks; the first failure is the lowest failing index by definition.
BatchSummary SampleOnCallingThread(const lang::CompiledProgram& program,
                                   const BatchOptions& options, const BatchCallbacks& callbacks) {
  SceneSampler sampler(program, options.sample);
  BatchSummary summary;
  std::string text;
  for (int64_t offset = 0; offset < options.count; ++offset) {
    if (IsCancelled(options)) throw BatchCancelled();
    BatchScene item;
    item.sampled = sampler.Sample(options.seed, options.start + static_cast<uint64_t>(offset));
    if (callbacks.prepare) callbacks.prepare(item);
    if (callbacks.format) {
      text.clear();
      callbacks.format(item, text);
      callbacks.write(text, 1);
    }
    summary.Add(item.sampled);
    if (callbacks.consume) callbacks.consume(std::move(item));
  }
  return summary;
}

// A worker: samples claimed runs until none is left, formatting each run's text into one
// buffer. A failure ends its run (the scenes after it are not needed); every error, even from
// building the sampler, is charged to the offset being sampled, so the consumer reports it in
// order. The runs the consumer gave back are reused for later claims (their buffers keep
// their size), and what is left of their scenes is freed here, on the thread that allocated it.
void RunWorker(int worker, const lang::CompiledProgram& program, const BatchOptions& options,
               const BatchCallbacks& callbacks, internal::RunQueue& queue) {
  std::optional<SceneSampler> sampler;
  std::vector<internal::SceneRun> spent;
  while (const std::optional<internal::OffsetRange> range = queue.Claim(worker, spent)) {
    internal::SceneRun run;
    if (!spent.empty()) {
      run = std::move(spent.back());
      spent.pop_back();
    }
    run.scenes.clear();
    run.text.clear();
    run.summary = {};
    run.begin = range->begin;
    run.worker = worker;
    bool failed = false;
    for (int64_t offset = range->begin; offset < range->end && !failed; ++offset) {
      BatchScene& item = run.scenes.emplace_back();
      const size_t text_size = run.text.size();
      try {
        if (!sampler) sampler.emplace(program, options.sample);
        item.sampled = sampler->Sample(options.seed, options.start + static_cast<uint64_t>(offset));
        if (callbacks.prepare) callbacks.prepare(item);
        if (callbacks.format) callbacks.format(item, run.text);
        run.summary.Add(item.sampled);
      } catch (...) {
        run.scenes.pop_back();
        run.text.resize(text_size);
        queue.Fail(offset, std::current_exception());
        failed = true;
      }
    }
    queue.Finish(std::move(run));
  }
}

// Stops the queue when the consumer leaves, normally or by an exception; declared after the
// worker threads so that it runs before they are joined.
struct StopQueueOnExit {
  internal::RunQueue& queue;
  ~StopQueueOnExit() { queue.Stop(); }
};

// Scenes a worker claims at once. Small batches are claimed one scene at a time so that every
// thread gets a share; large ones in runs of up to `max_claim` (64 for sampling, which is
// plenty to amortise the lock and the hand-over; 1 for episodes). A worker publishes its claim
// only when it has sampled all of it, so a claim must leave room in the window for the other
// workers' claims: at most half a thread's share of the window (a chunk as large as the window
// made one worker hold it all while the others waited).
int64_t ChooseChunk(int64_t count, int threads, int window_per_thread, int max_claim) {
  const int64_t max_chunk = std::clamp<int64_t>(window_per_thread / 2, 1, max_claim);
  return std::clamp<int64_t>(count / (int64_t{threads} * 16), 1, max_chunk);
}

BatchSummary SampleOnWorkers(const lang::CompiledProgram& program, const BatchOptions& options,
                             const BatchCallbacks& callbacks, int threads) {
  int64_t window_per_thread = std::max(options.window_per_thread, 1);
  int64_t chunk =
      ChooseChunk(options.count, threads, window_per_thread, std::max(options.max_claim, 1));
  int64_t phase = 0;
  if (options.sample.gibbs) {
    // A chain's scenes cost one thinning interval each only on the thread that ran the ones
    // before: claim whole chains, with room in the window for two per thread.
    chunk = std::max<int64_t>(1, options.sample.gibbs->settings().scenes_per_chain);
    window_per_thread = std::max(window_per_thread, 2 * chunk);
    phase = static_cast<int64_t>(options.start % static_cast<uint64_t>(chunk));
  }
  internal::RunQueue queue(threads, options.count, int64_t{threads} * window_per_thread, chunk,
                           options.sample.gibbs != nullptr, phase);
  BatchSummary summary;
  std::vector<std::jthread> workers;
  StopQueueOnExit stop_queue{queue};
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&, t] { RunWorker(t, program, options, callbacks, queue); });
  }
  std::vector<internal::SceneRun> ready;
  for (int64_t offset = 0; offset < options.count;) {
    queue.TakeReady(offset, ready, options.cancel, callbacks.tick);
    for (internal::SceneRun& run : ready) {
      // A run's text is written whole, so with `format` the cancel check is per run.
      if (callbacks.format) {
        if (IsCancelled(options)) throw BatchCancelled();
        callbacks.write(run.text, static_cast<int64_t>(run.scenes.size()));
      }
      summary.Merge(run.summary);  // counted on the worker: no scene's counts cross threads
      for (BatchScene& item : run.scenes) {
        if (!callbacks.format && IsCancelled(options)) throw BatchCancelled();
        if (callbacks.consume) callbacks.consume(std::move(item));
        ++offset;
      }
    }
    queue.GiveBack(ready);
  }
  return summary;
}

}  // namespace

int CountBatchThreads(const BatchOptions& options) {
  return static_cast<int>(std::clamp<int64_t>(options.count, 1, std::max(options.threads, 1)));
}

BatchSummary SampleBatch(const lang::CompiledProgram& program, const BatchOptions& options,
                         const BatchCallbacks& callbacks) {
  CheckArguments(options);
  const int threads = CountBatchThreads(options);
  if (threads == 1 && !callbacks.tick) return SampleOnCallingThread(program, options, callbacks);
  return SampleOnWorkers(program, options, callbacks, threads);
}

}  // namespace prs::sampling
