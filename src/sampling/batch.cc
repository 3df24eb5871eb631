// The parallel batch sampler: workers claim scene indices in increasing order, park finished
// scenes in a ring of slots, and the calling thread takes them out in index order. A worker
// may run at most `window` scenes ahead of the consumer, which bounds memory.
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
      std::numeric_limits<uint64_t>::max() - static_cast<uint64_t>(std::max<int64_t>(options.count - 1, 0));
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
    callbacks.consume(std::move(item));
  }
  return summary;
}

// The hand-over between workers and the consumer. Offsets count from the batch's first scene.
// Claims go out in increasing order, so when offset f fails every offset below f has been
// claimed and will finish or fail: the lowest failure is found without waiting for the rest.
class ReorderQueue {
 public:
  ReorderQueue(int64_t count, int64_t window) : slots_(window), count_(count) {}

  /// Worker: the next offset to sample, waiting while the window is full; nullopt when
  /// nothing is left to claim (done, stopping, or past a failed offset).
  std::optional<int64_t> Claim() {
    std::unique_lock lock(mutex_);
    slot_free_.wait(lock, [&] { return IsClaimOver() || HasFreeSlot(); });
    if (IsClaimOver()) return std::nullopt;
    return next_claim_++;
  }

  /// Worker: parks the finished scene for `offset`.
  void Finish(int64_t offset, BatchScene&& scene) {
    bool is_awaited;
    {
      std::lock_guard lock(mutex_);
      slots_[offset % Window()] = std::move(scene);
      is_awaited = offset == next_take_;
    }
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

  /// Consumer: waits for scene `offset` and returns it. Rethrows its failure, or throws
  /// BatchCancelled once `cancel` is set.
  BatchScene Take(int64_t offset, const std::atomic<bool>* cancel) {
    std::unique_lock lock(mutex_);
    std::optional<BatchScene>& slot = slots_[offset % Window()];
    auto is_decided = [&] { return slot.has_value() || failed_offset_ <= offset; };
    while (true) {
      if (cancel && cancel->load(std::memory_order_relaxed)) throw BatchCancelled();
      if (is_decided()) break;
      scene_ready_.wait_for(lock, kCancelPollInterval, is_decided);
    }
    if (!slot) std::rethrow_exception(failure_);
    BatchScene scene = std::move(*slot);
    slot.reset();
    next_take_ = offset + 1;
    lock.unlock();
    slot_free_.notify_one();
    return scene;
  }

  /// Tells every worker to stop claiming; their current scene still finishes.
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
  bool IsClaimOver() const {
    return stopping_ || next_claim_ >= std::min(count_, failed_offset_);
  }

  std::mutex mutex_;
  std::condition_variable scene_ready_;  // the consumer waits here
  std::condition_variable slot_free_;    // workers wait here
  std::vector<std::optional<BatchScene>> slots_;
  const int64_t count_;
  int64_t next_claim_ = 0;
  int64_t next_take_ = 0;
  int64_t failed_offset_ = std::numeric_limits<int64_t>::max();
  std::exception_ptr failure_;
  bool stopping_ = false;
};

// A worker: samples claimed offsets until none is left. Every error, even from building the
// sampler, is charged to the offset being sampled, so the consumer reports it in order.
void RunWorker(const lang::CompiledProgram& program, const BatchOptions& options,
               const BatchCallbacks& callbacks, ReorderQueue& queue) {
  std::optional<SceneSampler> sampler;
  while (const std::optional<int64_t> offset = queue.Claim()) {
    try {
      if (!sampler) sampler.emplace(program, options.sample);
      BatchScene item;
      item.sampled = sampler->Sample(options.seed, options.start + static_cast<uint64_t>(*offset));
      if (callbacks.prepare) callbacks.prepare(item);
      queue.Finish(*offset, std::move(item));
    } catch (...) {
      queue.Fail(*offset, std::current_exception());
    }
  }
}

// Stops the queue when the consumer leaves, normally or by an exception; declared after the
// worker threads so that it runs before they are joined.
struct StopQueueOnExit {
  ReorderQueue& queue;
  ~StopQueueOnExit() { queue.Stop(); }
};

BatchSummary SampleOnWorkers(const lang::CompiledProgram& program, const BatchOptions& options,
                             const BatchCallbacks& callbacks, int threads) {
  const int64_t window = int64_t{threads} * std::max(options.window_per_thread, 1);
  ReorderQueue queue(options.count, window);
  BatchSummary summary;
  std::vector<std::jthread> workers;
  StopQueueOnExit stop_queue{queue};
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&] { RunWorker(program, options, callbacks, queue); });
  }
  for (int64_t offset = 0; offset < options.count; ++offset) {
    BatchScene item = queue.Take(offset, options.cancel);
    summary.Add(item.sampled);
    callbacks.consume(std::move(item));
  }
  return summary;
}

}  // namespace

BatchSummary SampleBatch(const lang::CompiledProgram& program, const BatchOptions& options,
                         const BatchCallbacks& callbacks) {
  CheckArguments(options);
  const int threads = static_cast<int>(std::min<int64_t>(options.threads, options.count));
  if (threads <= 1) return SampleOnCallingThread(program, options, callbacks);
  return SampleOnWorkers(program, options, callbacks, threads);
}

}  // namespace prs::sampling
