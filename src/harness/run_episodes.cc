// RunEpisodes: episodes run on the batch sampler's worker threads right after their scene is
// sampled (its `prepare` step), each thread with a controller of its own, and the records
// come back through the batch's reordering in index order.
#include <map>
#include <mutex>
#include <set>

#include "harness/episode_runner.h"
#include "harness/harness.h"

namespace prs::harness {
namespace {

using internal::EpisodeRunner;

sampling::BatchOptions MakeBatchOptions(const RunOptions& options) {
  sampling::BatchOptions batch;
  batch.sample = options.sample;
  batch.seed = options.seed;
  batch.start = options.start;
  batch.count = options.count;
  batch.threads = options.threads;
  batch.cancel = options.cancel;
  // Episodes are slow next to sampling: claims of one episode, so that every thread ends with
  // the run; a window of 16 a thread, so that one long episode (a timeout) does not stop the
  // others (only records wait in it: each scene is freed on its worker).
  batch.window_per_thread = 16;
  batch.max_claim = 1;
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
