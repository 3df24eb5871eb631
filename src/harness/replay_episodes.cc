// ReplayEpisodes: given scenes (read from files, or regenerated from their program) run on
// worker threads that take the next item as they finish one; the calling thread hands the
// records on in item order as they become ready.
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "harness/episode_runner.h"
#include "harness/harness.h"

namespace prs::harness {
namespace {

// What the workers share: the next item to take, the records made, the first failure.
class ReplayState {
 public:
  explicit ReplayState(int64_t count) : count_(count) {}

  // The next item for a worker, or -1 when there is none (all taken, cancelled or failed).
  int64_t Take(const std::atomic<bool>* cancel) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return -1;
    const int64_t item = next_.fetch_add(1);
    std::lock_guard lock(mutex_);
    return item < count_ && item < failed_item_ ? item : -1;
  }

  void Finish(int64_t item, EpisodeRecord record) {
    std::lock_guard lock(mutex_);
    done_.emplace(item, std::move(record));
    ready_.notify_all();
  }

  void Fail(int64_t item, std::exception_ptr error) {
    std::lock_guard lock(mutex_);
    if (item < failed_item_) {
      failed_item_ = item;
      error_ = error;
    }
    ready_.notify_all();
  }

  void WorkerStopped() {
    std::lock_guard lock(mutex_);
    ++stopped_workers_;
    ready_.notify_all();
  }

  // Waits for item `item`'s record; nullopt when it will never come (failed, cancelled).
  std::optional<EpisodeRecord> Await(int64_t item, int workers) {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] {
      return done_.contains(item) || item >= failed_item_ || stopped_workers_ == workers;
    });
    auto node = done_.extract(item);
    if (node.empty()) return std::nullopt;
    return std::move(node.mapped());
  }

  // The failure of the lowest item, if any.
  std::exception_ptr error() {
    std::lock_guard lock(mutex_);
    return error_;
  }

 private:
  const int64_t count_;
  std::atomic<int64_t> next_{0};
  std::mutex mutex_;
  std::condition_variable ready_;
  std::map<int64_t, EpisodeRecord> done_;
  int64_t failed_item_ = INT64_MAX;
  std::exception_ptr error_;
  int stopped_workers_ = 0;
};

void RunWorker(ReplayState& state, const ReplaySourceFactory& sources,
               internal::EpisodeRunner& runner, const RunOptions& options) {
  ReplaySource source;
  for (int64_t item; (item = state.Take(options.cancel)) >= 0;) {
    try {
      if (!source) source = sources();
      ReplayScene scene = source(item);
      EpisodeRecord record = runner.Run(scene.sampled, std::move(scene.scene_json));
      record.search = std::move(scene.search);
      record.replay = std::move(scene.replay);
      if (scene.scene_options && !record.spec.empty()) record.scene_options = *scene.scene_options;
      state.Finish(item, std::move(record));
    } catch (...) {
      state.Fail(item, std::current_exception());
    }
  }
  state.WorkerStopped();
}

}  // namespace

RunSummary ReplayEpisodes(int64_t count, const ReplaySourceFactory& sources,
                          const ControllerFactory& factory, const RunOptions& options) {
  if (count < 0) throw std::invalid_argument("ReplayEpisodes: count must be >= 0");
  if (options.threads < 1) throw std::invalid_argument("ReplayEpisodes: threads must be >= 1");
  internal::EpisodeRunner runner(factory, options);
  ReplayState state(count);
  RunSummary summary;
  summary.threads = int(std::clamp<int64_t>(count, 1, options.threads));
  std::vector<std::jthread> workers;
  for (int t = 0; t < summary.threads; ++t) {
    workers.emplace_back([&] { RunWorker(state, sources, runner, options); });
  }
  std::set<std::string> warned;
  std::exception_ptr consume_error;
  for (int64_t item = 0; item < count && !consume_error; ++item) {
    std::optional<EpisodeRecord> record = state.Await(item, summary.threads);
    if (!record) break;
    try {
      for (const std::string& warning : record->result.warnings) {
        if (warned.insert(warning).second && options.on_warning) options.on_warning(warning);
      }
      if (options.on_record) options.on_record(*record);
    } catch (...) {
      consume_error = std::current_exception();
      state.Fail(item + 1, consume_error);  // the workers take nothing more
    }
    summary.records.push_back(*std::move(record));
  }
  workers.clear();  // joins
  if (consume_error) std::rethrow_exception(consume_error);
  if (std::exception_ptr error = state.error()) std::rethrow_exception(error);
  if (int64_t(summary.records.size()) < count) throw sampling::BatchCancelled();
  return summary;
}

}  // namespace prs::harness
