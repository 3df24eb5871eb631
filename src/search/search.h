// Failure-directed search (docs/search.md): episodes run in generations at points of scene
// coordinates proposed by a strategy that learns from the outcomes and scores of the earlier
// generations where the controller fails. Every scene still goes through the exact sampler,
// so every evaluated scene satisfies every hard constraint of the program.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/harness.h"

namespace prs::search {

enum class Strategy {
  kRandom,        // i.i.d. uniform points: the baseline, distributed as `prs test`
  kCrossEntropy,  // the cross-entropy method over independent truncated normals per coordinate
  kAnneal,        // simulated annealing: one Metropolis chain per episode slot of a generation
};

const char* StrategyName(Strategy strategy);  // "random", "ce", "anneal"
std::vector<std::string> StrategyNames();
bool ParseStrategy(const std::string& name, Strategy* strategy);

/// Thrown when the program draws nothing at random: there is nothing to search.
class NothingToSearch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SearchOptions {
  Strategy strategy = Strategy::kCrossEntropy;
  int64_t budget = 0;  // episodes in all (> 0)
  /// Episodes per generation (each generation runs as one batch on all threads); 0 picks
  /// budget / 50 within [20, 200] (at most the budget).
  int64_t batch = 0;
  /// Seed, threads, sampling options, save_failures_dir, on_failure, cancel (scenario_args
  /// should stay empty: no `prs sample` command rewrites a searched scene).
  /// `start`, `count`, `on_record` and `sample.points` are set by the search.
  harness::RunOptions run;
  /// Called on the calling thread with each record, in evaluation order, as its generation
  /// finishes (so a stopped search has complete records up to its last finished generation).
  std::function<void(const harness::EpisodeRecord&)> on_record;
};

struct SearchSummary {
  std::vector<harness::EpisodeRecord> records;    // in evaluation order; index = evaluation
  std::vector<lang::CoordinateInfo> coordinates;  // what each coordinate is
  int64_t batch = 0;
  int generations = 0;
  int64_t failures = 0;
  int64_t first_failure = -1;  // 1-based number of the first failing episode, -1 for none
  int threads = 1;
  /// The cross-entropy method's last proposal (mean and standard deviation per coordinate);
  /// empty for the other strategies.
  std::vector<double> proposal_mean, proposal_std;
};

/// The generation size SearchOptions::batch = 0 stands for.
int64_t DefaultBatch(int64_t budget);

/// Runs the search. The records are a pure function of (program, controller, strategy,
/// budget, batch, seed): the same for any thread count. Throws std::invalid_argument for a
/// budget or batch < 1, NothingToSearch, and what harness::RunEpisodes throws (a scenario
/// error, sampling::BatchCancelled).
SearchSummary RunSearch(const lang::CompiledProgram& program,
                        const harness::ControllerFactory& factory, const SearchOptions& options);

}  // namespace prs::search
