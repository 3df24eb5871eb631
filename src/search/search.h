// Failure-directed search (docs/search.md): episodes run in generations at points of scene
// coordinates proposed by a strategy that learns from the outcomes and scores of the earlier
// generations where the controller fails. Every scene still goes through the exact sampler,
// so every evaluated scene satisfies every hard constraint of the program.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/harness.h"

namespace prs::search {

enum class Strategy {
  kRandom,        // i.i.d. uniform points: the baseline, distributed as `prs test`
  kCrossEntropy,  // the cross-entropy method over independent truncated normals per coordinate
  kAnneal,        // simulated annealing: one Metropolis chain per episode slot of a generation
  kExternal,      // points from SearchOptions::propose (Python's Bayesian optimisation)
};

const char* StrategyName(Strategy strategy);  // "random", "ce", "anneal", "external"
/// The strategies `prs search` runs itself (not "external").
std::vector<std::string> StrategyNames();
bool ParseStrategy(const std::string& name, Strategy* strategy);

/// What a strategy learns from one evaluated episode: its scene coordinates and its badness
/// (lower is worse: failures below every success, then by score; without a score -1 for a
/// failure, +1 for a success).
double CalcBadness(const harness::EpisodeRecord& record);

/// The points of the next generation for Strategy::kExternal: given every record so far (in
/// evaluation order), the number of points wanted and the generation, returns that many points
/// of dimension `dimension`, each coordinate in [0, 1). An attempt at a point that the
/// program rejects is retried at i.i.d. uniform points (the scene still follows the program).
using Proposer = std::function<std::vector<std::vector<double>>(
    const std::vector<harness::EpisodeRecord>& so_far, int64_t count, int dimension,
    int generation)>;

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
  /// Strategy::kExternal only. Its exceptions propagate from RunSearch; a wrong number of
  /// points, or a point of the wrong size or outside [0, 1), is std::invalid_argument.
  Proposer propose;
  /// The name records carry as "strategy" for kExternal (e.g. "bo").
  std::string external_name = "external";
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

/// One generation of a search: its episodes and where their points come from. A pure function
/// of the program, the options and the earlier generations' records, and plain data, so that
/// its episodes can run anywhere in any pieces (a campaign's shards, docs/cluster.md) and give
/// the records one machine's search gives.
struct GenerationPlan {
  int generation = 0;
  uint64_t start = 0;  // the first episode's index (= episodes in the earlier generations)
  int64_t count = 0;
  int dimension = 0;
  std::string mode;  // "uniform", "sobol", "gaussian" (mean, std), "chain" (centres, step),
                     // "given" (centres), "mixture" (prs estimate's MixtureProposal: mean, std,
                     // centres, uniform_share)
  std::vector<double> mean, std;
  std::vector<std::vector<double>> centres;
  double step = 0;
  double uniform_share = 1;
  // "mixture" too: MixtureProposal's per-centre spreads and wide layer.
  std::vector<std::vector<double>> centre_std;
  double wide_share = 0, wide_factor = 1;
  std::string strategy;  // the name records carry ("ce", "anneal", "random", "bo", ...)
};
nlohmann::json PlanToJson(const GenerationPlan& plan);
/// Throws std::runtime_error for JSON that is not a plan.
GenerationPlan PlanFromJson(const nlohmann::json& json);

/// A run in generations, each planned from the records of the ones before: Next() plans a
/// generation, Add() learns from its records. The search and the estimate are loops over one;
/// src/campaign replays one from the records on disk to plan a campaign's next generation.
class GenerationPlanner {
 public:
  virtual ~GenerationPlanner() = default;
  virtual bool done() const = 0;
  virtual GenerationPlan Next() = 0;
  /// The records of the generation Next() planned last, in index order.
  virtual void Add(std::vector<harness::EpisodeRecord> records) = 0;
};

/// The search's state between generations.
class SearchPlanner : public GenerationPlanner {
 public:
  /// Throws as RunSearch does for bad options and NothingToSearch.
  SearchPlanner(const lang::CompiledProgram& program, const SearchOptions& options);
  ~SearchPlanner() override;
  bool done() const override;
  /// The next generation (for kExternal, from options.propose).
  GenerationPlan Next() override;
  void Add(std::vector<harness::EpisodeRecord> records) override;
  /// What the search has found so far (records in evaluation order).
  const SearchSummary& summary() const;
  SearchSummary TakeSummary();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Runs episodes [first, first + count) of `plan` (all of it: plan.start, plan.count) with
/// `run`'s seed, threads, sampling options and callbacks; records carry "search" {strategy,
/// generation} and the spec hash. Throws what harness::RunEpisodes throws.
harness::RunSummary RunGeneration(const lang::CompiledProgram& program,
                                  const harness::ControllerFactory& factory,
                                  const GenerationPlan& plan, harness::RunOptions run,
                                  uint64_t first, int64_t count);

/// What the planner needs of a record read back from JSON (index, outcome, score,
/// coordinates); false for a line that is not a record.
bool ParseRecordForSearch(const std::string& line, harness::EpisodeRecord* record);

/// Runs the search. The records are a pure function of (program, controller, strategy,
/// budget, batch, seed): the same for any thread count. Throws std::invalid_argument for a
/// budget or batch < 1 (or kExternal without a proposer), NothingToSearch, and what
/// harness::RunEpisodes throws (a scenario error, sampling::BatchCancelled).
SearchSummary RunSearch(const lang::CompiledProgram& program,
                        const harness::ControllerFactory& factory, const SearchOptions& options);

}  // namespace prs::search
