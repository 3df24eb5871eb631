// The hand-over between the batch sampler's workers and its consumer (internal to batch.cc):
// workers claim runs of consecutive scenes, park each finished run whole, and the consumer
// takes the finished runs in index order. Everything crosses threads once per run, not once
// per scene, and memory goes back to the thread that allocated it.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sampling/batch.h"

namespace prs::sampling::internal {

/// Consecutive offsets [begin, end) claimed by one worker. Offsets count from the batch's
/// first scene.
struct OffsetRange {
  int64_t begin;
  int64_t end;
};

/// The scenes a worker sampled from one claim: offsets begin, begin + 1, ... (fewer than it
/// claimed when one failed), with their text when the batch formats scenes.
struct SceneRun {
  int64_t begin = 0;
  int worker = 0;
  std::vector<BatchScene> scenes;
  std::string text;      // BatchCallbacks::format's text of `scenes`, in order
  BatchSummary summary;  // the totals of `scenes`
};

/// Claims go out in increasing order, so when offset f fails every offset below f has been
/// claimed and will finish or fail: the lowest failure is found without waiting for the rest.
/// At most `window` offsets are claimed past the consumer's, which bounds memory.
class RunQueue {
 public:
  /// `workers` threads claim at most `chunk` offsets at a time. With `aligned`, claims end
  /// where (offset + phase) is a multiple of `chunk` (a Gibbs chain's scenes are claimed
  /// together: sampling/gibbs.h).
  RunQueue(int workers, int64_t count, int64_t window, int64_t chunk, bool aligned, int64_t phase);

  /// Worker `worker` (0 .. workers - 1): the next offsets to sample, waiting while the window
  /// is full; nullopt when nothing is left to claim (done, stopping, or past a failed offset).
  /// Adds the runs the consumer gave back to this worker to `spent`, for the worker to reuse.
  std::optional<OffsetRange> Claim(int worker, std::vector<SceneRun>& spent);
  /// Worker: parks a finished run (one with no scene is dropped).
  void Finish(SceneRun&& run);
  /// Worker: records that `offset` failed; the lowest failed offset wins.
  void Fail(int64_t offset, std::exception_ptr error);

  /// Consumer: releases the offsets before `offset` (consumed; `offset` starts a run), waits
  /// for finished runs from `offset` (half the window's scenes, the last ones, or
  /// whatever is there at a 50 ms poll: the consumer wakes once for many runs), and moves them
  /// into `ready`. Their offsets stay reserved until the next call, so at most `window` scenes
  /// exist at a time. Calls `tick` at each poll. Rethrows the failure of `offset`, or throws
  /// BatchCancelled once `cancel` is set.
  void TakeReady(int64_t offset, std::vector<SceneRun>& ready, const std::atomic<bool>* cancel,
                 const std::function<void()>& tick);
  /// Consumer: hands consumed runs (what `consume` left of their scenes) back to the workers
  /// that made them, and clears `spent`. A free from another thread takes the allocating
  /// thread's malloc arena lock; that contention cost more system time than two threads saved.
  void GiveBack(std::vector<SceneRun>& spent);

  /// Tells every worker to stop claiming; their current runs still finish.
  void Stop();

 private:
  int64_t Window() const { return static_cast<int64_t>(slots_.size()); }
  bool HasFreeSlot() const { return next_claim_ < next_take_ + Window(); }
  bool IsClaimOver() const;
  bool IsRunReady() const;
  std::optional<SceneRun>& SlotOf(int64_t begin) { return slots_[begin % Window()]; }

  std::mutex mutex_;
  std::condition_variable scene_ready_;         // the consumer waits here
  std::condition_variable slot_free_;           // workers wait here
  std::vector<std::optional<SceneRun>> slots_;  // a run at the slot of its first offset
  std::vector<std::vector<SceneRun>> spent_;    // per worker: consumed runs to give back
  const int64_t count_;
  const int64_t chunk_;
  const bool aligned_;
  const int64_t phase_;
  const int64_t wake_scenes_;  // finished scenes in a row that wake the consumer
  int64_t next_claim_ = 0;
  int64_t next_take_ = 0;  // offsets below it are consumed; their slots are free
  int64_t ready_end_ = 0;  // the offsets from next_take_ below it are finished
  int64_t failed_offset_ = std::numeric_limits<int64_t>::max();
  std::exception_ptr failure_;
  bool stopping_ = false;
};

}  // namespace prs::sampling::internal
