// The parallel batch sampler: workers claim runs of scene indices in increasing order, park
// finished scenes in a ring of slots, and the calling thread takes them out in index order.
// No scene is claimed more than `window` scenes ahead of the consumer, which bounds memory.
#include "sampling/batch.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "sampling/gibbs.h"

namespace prs::sampling {

void BatchSummary::Add(const SampledScene& sampled) {
  ++scenes;
  attempts += sampled.attempts;
  rejections.Merge(sampled.rejections);
}

namespace {

constexpr auto kCancelPollInterval = std::chrono::milliseconds(50);

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
  for (int64_t offset = 0; offset < options.count; ++offset) {
    if (IsCancelled(options)) throw BatchCancelled();
    BatchScene item;
    item.sampled = sampler.Sample(options.seed, options.start + static_cast<uint64_t>(offset));
    if (callbacks.prepare) callbacks.prepare(item);
    summary.Add(item.sampled);
    if (callbacks.consume) callbacks.consume(std::move(item));
  }
  return summary;
}

// A run of consecutive offsets [begin, end) claimed by one worker.
struct OffsetRange {
  int64_t begin;
  int64_t end;
};

// The hand-over between workers and the consumer. Offsets count from the batch's first scene.
// Claims go out in increasing order, so when offset f fails every offset below f has been
// claimed and will finish or fail: the lowest failure is found without waiting for the rest.
// Workers claim a few scenes at a time and the consumer takes every ready scene at once, so
// the lock and the wake-ups are paid per run of scenes, not per scene.
class ReorderQueue {
 public:
  /// With `aligned`, claims end where (offset + phase) is a multiple of `chunk` (a Gibbs
  /// chain's scenes are claimed together: sampling/gibbs.h).
  ReorderQueue(int64_t count, int64_t window, int64_t chunk, bool aligned = false,
               int64_t phase = 0)
      : slots_(window), count_(count), chunk_(chunk), aligned_(aligned), phase_(phase) {}

  /// Worker: the next offsets to sample (at most `chunk`, as many as the window has room
  /// for), waiting while it is full; nullopt when nothing is left to claim (done, stopping,
  /// or past a failed offset).
  std::optional<OffsetRange> Claim() {
    std::unique_lock lock(mutex_);
    slot_free_.wait(lock, [&] { return IsClaimOver() || HasFreeSlot(); });
    if (IsClaimOver()) return std::nullopt;
    const int64_t chunk = aligned_ ? chunk_ - (next_claim_ + phase_) % chunk_ : chunk_;
    const int64_t end =
        std::min({next_claim_ + chunk, next_take_ + Window(), std::min(count_, failed_offset_)});
    const OffsetRange range{next_claim_, end};
    next_claim_ = end;
    return range;
  }

  /// Worker: parks finished scenes for offsets begin, begin + 1, ...
  void Finish(int64_t begin, std::vector<BatchScene>& scenes) {
    if (scenes.empty()) return;
    bool is_awaited;
    {
      std::lock_guard lock(mutex_);
      for (size_t i = 0; i < scenes.size(); ++i) {
        slots_[(begin + int64_t(i)) % Window()] = std::move(scenes[i]);
      }
      is_awaited = begin == next_take_;
    }
    scenes.clear();
    if (is_awaited) scene_ready_.notify_one();
  }

  /// Worker: records that `offset` failed; the lowest failed offset wins.
  void Fail(int64_t offset, std::exception_ptr error) {
    {
      std::lock_guard lock(mutex_);
      if (offset < failed_offset_) {
        failed_offset_ = offset;
        failure_ = std::move(error);
      }
    }
    scene_ready_.notify_one();
    slot_free_.notify_all();  // workers waiting for a slot past the failure can quit
  }

  /// Consumer: releases the scenes before `offset` (consumed), waits for scene `offset`, then
  /// moves it and the finished scenes right after it into `ready`. Their slots stay reserved
  /// until the next call, so at most `window` scenes exist at a time. Rethrows the failure of
  /// `offset`, or throws BatchCancelled once `cancel` is set.
  void TakeReady(int64_t offset, std::vector<BatchScene>& ready, const std::atomic<bool>* cancel,
                 const std::function<void()>& tick) {
    std::unique_lock lock(mutex_);
    if (offset > next_take_) {
      next_take_ = offset;
      slot_free_.notify_all();
    }
    auto is_decided = [&] {
      return slots_[offset % Window()].has_value() || failed_offset_ <= offset;
    };
    while (true) {
      if (cancel && cancel->load(std::memory_order_relaxed)) throw BatchCancelled();
      if (is_decided()) break;
      if (!scene_ready_.wait_for(lock, kCancelPollInterval, is_decided) && tick) {
        lock.unlock();  // the tick may take a while (a terminal write): workers go on
        tick();
        lock.lock();
      }
    }
    if (!slots_[offset % Window()]) std::rethrow_exception(failure_);
    for (int64_t next = offset; next < count_ && next < offset + Window(); ++next) {
      std::optional<BatchScene>& slot = slots_[next % Window()];
      if (!slot) break;
      ready.push_back(std::move(*slot));
      slot.reset();
    }
  }

  /// Tells every worker to stop claiming; their current scenes still finish.
  void Stop() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    slot_free_.notify_all();
  }

 private:
  int64_t Window() const { return static_cast<int64_t>(slots_.size()); }
  bool HasFreeSlot() const { return next_claim_ < next_take_ + Window(); }
  bool IsClaimOver() const { return stopping_ || next_claim_ >= std::min(count_, failed_offset_); }

  std::mutex mutex_;
  std::condition_variable scene_ready_;  // the consumer waits here
  std::condition_variable slot_free_;    // workers wait here
  std::vector<std::optional<BatchScene>> slots_;
  const int64_t count_;
  const int64_t chunk_;
  const bool aligned_;
  const int64_t phase_;
  int64_t next_claim_ = 0;
  int64_t next_take_ = 0;  // offsets below it are consumed; their slots are free
  int64_t failed_offset_ = std::numeric_limits<int64_t>::max();
  std::exception_ptr failure_;
  bool stopping_ = false;
};

// A worker: samples claimed runs until none is left. A failure ends its run (the scenes after
// it are not needed); every error, even from building the sampler, is charged to the offset
// being sampled, so the consumer reports it in order.
void RunWorker(const lang::CompiledProgram& program, const BatchOptions& options,
               const BatchCallbacks& callbacks, ReorderQueue& queue) {
  std::optional<SceneSampler> sampler;
  std::vector<BatchScene> finished;
  while (const std::optional<OffsetRange> range = queue.Claim()) {
    for (int64_t offset = range->begin; offset < range->end; ++offset) {
      try {
        if (!sampler) sampler.emplace(program, options.sample);
        BatchScene item;
        item.sampled = sampler->Sample(options.seed, options.start + static_cast<uint64_t>(offset));
        if (callbacks.prepare) callbacks.prepare(item);
        finished.push_back(std::move(item));
      } catch (...) {
        queue.Finish(range->begin, finished);
        queue.Fail(offset, std::current_exception());
        break;
      }
    }
    queue.Finish(range->begin, finished);
  }
}

// Stops the queue when the consumer leaves, normally or by an exception; declared after the
// worker threads so that it runs before they are joined.
struct StopQueueOnExit {
  ReorderQueue& queue;
  ~StopQueueOnExit() { queue.Stop(); }
};

// Small batches are claimed one scene at a time so that every thread gets a share; large ones
// in runs of up to 16, which is plenty to amortise the lock.
// Scenes a worker claims at once. A worker publishes its claim only when it has sampled all of
// it, so a claim must leave room in the window for the other workers' claims: at most half a
// thread's share of the window (with the harness's window of 4 per thread, 2 episodes; a chunk
// as large as the window made one worker hold it all while the others waited).
int64_t ChooseChunk(int64_t count, int threads, int window_per_thread) {
  const int64_t max_chunk = std::clamp<int64_t>(window_per_thread / 2, 1, 16);
  return std::clamp<int64_t>(count / (int64_t{threads} * 16), 1, max_chunk);
}

BatchSummary SampleOnWorkers(const lang::CompiledProgram& program, const BatchOptions& options,
                             const BatchCallbacks& callbacks, int threads) {
  int64_t window_per_thread = std::max(options.window_per_thread, 1);
  int64_t chunk = ChooseChunk(options.count, threads, window_per_thread);
  int64_t phase = 0;
  if (options.sample.gibbs) {
    // A chain's scenes cost one thinning interval each only on the thread that ran the ones
    // before: claim whole chains, with room in the window for two per thread.
    chunk = std::max<int64_t>(1, options.sample.gibbs->settings().scenes_per_chain);
    window_per_thread = std::max(window_per_thread, 2 * chunk);
    phase = static_cast<int64_t>(options.start % static_cast<uint64_t>(chunk));
  }
  ReorderQueue queue(options.count, int64_t{threads} * window_per_thread, chunk,
                     options.sample.gibbs != nullptr, phase);
  BatchSummary summary;
  std::vector<std::jthread> workers;
  StopQueueOnExit stop_queue{queue};
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&] { RunWorker(program, options, callbacks, queue); });
  }
  std::vector<BatchScene> ready;
  for (int64_t offset = 0; offset < options.count;) {
    queue.TakeReady(offset, ready, options.cancel, callbacks.tick);
    for (BatchScene& item : ready) {
      if (IsCancelled(options)) throw BatchCancelled();
      summary.Add(item.sampled);
      if (callbacks.consume) callbacks.consume(std::move(item));
      ++offset;
    }
    ready.clear();
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
