// The batch sampler's hand-over of runs of scenes, in index order.
#include "sampling/run_queue.h"

#include <algorithm>
#include <chrono>

namespace prs::sampling::internal {
namespace {

constexpr auto kPollInterval = std::chrono::milliseconds(50);

}  // namespace

RunQueue::RunQueue(int workers, int64_t count, int64_t window, int64_t chunk, bool aligned,
                   int64_t phase)
    : slots_(window),
      spent_(workers),
      count_(count),
      chunk_(chunk),
      aligned_(aligned),
      phase_(phase),
      wake_scenes_(std::max<int64_t>(1, window / 2)) {}

bool RunQueue::IsClaimOver() const {
  return stopping_ || next_claim_ >= std::min(count_, failed_offset_);
}

bool RunQueue::IsRunReady() const {
  return ready_end_ - next_take_ >= wake_scenes_ ||
         (ready_end_ > next_take_ && ready_end_ >= std::min(count_, failed_offset_));
}

std::optional<OffsetRange> RunQueue::Claim(int worker, std::vector<SceneRun>& spent) {
  std::unique_lock lock(mutex_);
  for (SceneRun& run : spent_[worker]) spent.push_back(std::move(run));
  spent_[worker].clear();
  slot_free_.wait(lock, [&] { return IsClaimOver() || HasFreeSlot(); });
  if (IsClaimOver()) return std::nullopt;
  const int64_t chunk = aligned_ ? chunk_ - (next_claim_ + phase_) % chunk_ : chunk_;
  const int64_t end =
      std::min({next_claim_ + chunk, next_take_ + Window(), std::min(count_, failed_offset_)});
  const OffsetRange range{next_claim_, end};
  next_claim_ = end;
  return range;
}

void RunQueue::Finish(SceneRun&& run) {
  if (run.scenes.empty()) return;
  bool wake_consumer;
  {
    std::lock_guard lock(mutex_);
    const int64_t begin = run.begin;
    SlotOf(begin) = std::move(run);
    if (begin == ready_end_) {
      // Runs finish out of order: the run that continues the finished offsets in a row
      // extends them by itself and by the runs already parked after it.
      while (ready_end_ < next_claim_) {
        const std::optional<SceneRun>& slot = SlotOf(ready_end_);
        if (!slot || slot->begin != ready_end_) break;
        ready_end_ += static_cast<int64_t>(slot->scenes.size());
      }
    }
    wake_consumer = IsRunReady();
  }
  if (wake_consumer) scene_ready_.notify_one();
}

void RunQueue::Fail(int64_t offset, std::exception_ptr error) {
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

void RunQueue::TakeReady(int64_t offset, std::vector<SceneRun>& ready,
                         const std::atomic<bool>* cancel, const std::function<void()>& tick) {
  std::unique_lock lock(mutex_);
  if (offset > next_take_) {
    next_take_ = offset;
    slot_free_.notify_all();
  }
  const auto is_there = [&] { return SlotOf(offset) && SlotOf(offset)->begin == offset; };
  const auto is_decided = [&] { return IsRunReady() || failed_offset_ <= offset; };
  while (true) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw BatchCancelled();
    if (is_decided()) break;
    if (!scene_ready_.wait_for(lock, kPollInterval, is_decided)) {
      if (tick) {
        lock.unlock();  // the tick may take a while (a terminal write): workers go on
        tick();
        lock.lock();
      }
      if (is_there()) break;  // a poll takes what is there
    }
  }
  if (!is_there()) std::rethrow_exception(failure_);
  for (int64_t next = offset; next < ready_end_;) {
    std::optional<SceneRun>& slot = SlotOf(next);
    next += static_cast<int64_t>(slot->scenes.size());
    ready.push_back(std::move(*slot));
    slot.reset();
  }
}

void RunQueue::GiveBack(std::vector<SceneRun>& spent) {
  {
    std::lock_guard lock(mutex_);
    for (SceneRun& run : spent) spent_[run.worker].push_back(std::move(run));
  }
  spent.clear();
}

void RunQueue::Stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  slot_free_.notify_all();
}

}  // namespace prs::sampling::internal
