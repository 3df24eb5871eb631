// How often a controller fails under the program's own law (docs/search.md, "How often does it
// fail: prs estimate"): a cross-entropy adaptation of a proposal over the scene coordinates
// toward failures, then importance sampling from it kept as a defensive mixture with the
// uniform law, and self-normalised estimates with confidence intervals.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/harness.h"
#include "sampling/sampler.h"
#include "search/mixture.h"
#include "search/report.h"
#include "search/search.h"

namespace prs::search {

/// One failure outcome's probability under the program's law.
struct OutcomeEstimate {
  std::string outcome;
  int64_t episodes = 0;  // episodes that ended in it (weighted or i.i.d.)
  double p = 0;          // the (self-normalised) estimate
  /// 95 %: the exact binomial interval at the estimate's effective counts (intervals.h), so
  /// right for few failures and for p near 1; [0, bound] for a kind no episode here ended in.
  double ci_low = 0, ci_high = 0;
  /// The i.i.d. episodes whose binomial estimate would be as precise: p (1 - p) / variance
  /// (the effective sample size when the variance is 0).
  double iid_episodes = 0;
};

/// What a set of records says.
struct Estimate {
  int64_t episodes = 0;  // episodes (exploration and sampling when weighted)
  double ess = 0;        // effective sample size, (sum w)^2 / sum w^2
  /// True when every record weighs 1 (i.i.d. episodes, not weighted ones).
  bool iid = true;
  /// False when the weights degenerate (ESS under kMinEss or under 5 % of the episodes), or
  /// when the proposal's normals miss much of where the controller nearly fails (below): the
  /// numbers are then not to be trusted, and `prs estimate` says so instead of printing them.
  bool reliable = true;
  /// Of the episodes nearest to failing (the lowest scores, kNearFailureMass of the program's
  /// law), the weighted share drawn where the proposal's normals give under half the density:
  /// a failure set the normals miss in part shows up there first, where only the uniform share
  /// draws. Above kMaxUncoveredShare the estimate is unreliable. NaN without scores.
  double uncovered_share = NAN;
  /// Failures seen, largest p first; then the failure kinds seen only elsewhere (an
  /// adaptation's episodes) with no episode here, with p = 0 and [0, bound].
  std::vector<OutcomeEstimate> outcomes;
  /// With no failure seen: an upper bound on the probability of any failure at 95 %
  /// (docs/search.md derives it from the mixture's uniform share); else 0.
  double upper_bound = 0;
};

/// The fewest effective episodes an estimate is reported for.
inline constexpr double kMinEss = 30;
/// A failure's variance is the larger of what its failing draws say and what the draws nearest
/// to failing say: the lowest scores, this many times the failures' weight (docs/search.md,
/// "Intervals").
inline constexpr double kEdgeMass = 3;
/// The near-failures the coverage check looks at: the lowest scores, this much of the law.
inline constexpr double kNearFailureMass = 0.01;
/// The most of the near-failures the proposal's normals may leave to the uniform share.
inline constexpr double kMaxUncoveredShare = 0.3;

/// A record as the estimate reads it.
struct WeightedOutcome {
  std::string outcome;
  double weight = 1;         // 1 / proposal density (1 for i.i.d. records)
  double uniform_share = 1;  // of the proposal it was drawn from (1: i.i.d.)
  /// True when the accepted set may be smaller than the cube (the run saw rejections): then
  /// the estimate is self-normalised, sum w 1F / sum w; else the plain mean of w 1F.
  bool normalised = true;
  /// The controller's score (NaN when it reports none) and the share of the proposal's
  /// density its normals gave at the draw (MixtureProposal::CalcKernelShare; NaN unknown).
  double score = NAN, kernel_share = NAN;
};

/// Why `estimate` is unreliable, in one sentence that ends in what to do ("" when reliable):
/// the weights degenerate, or the proposal misses much of where the controller nearly fails.
std::string DescribeUnreliable(const Estimate& estimate);

/// The estimate of weighted outcomes (throws std::invalid_argument when there are none or a
/// weight is not positive and finite). Each name of `also_seen` that is neither "success" nor
/// among the records' outcomes gets a row with no episode and the bound.
Estimate CalcEstimate(const std::vector<WeightedOutcome>& records,
                      const std::vector<std::string>& also_seen = {});

/// The records an estimate is made of, and every outcome seen in the file.
struct WeightedRecords {
  std::vector<WeightedOutcome> records;
  std::vector<std::string> outcomes_seen;  // in any record, of any phase
};

/// The records an estimate is made of: those of the importance-sampling phase when there are
/// any, else the i.i.d. ones (`prs test -o`, weight 1). Throws std::runtime_error
/// "PATH:LINE: ..." for a record of another program when `spec_hash` is not empty, and for
/// records whose law gives no estimate (DescribeLaw): a search's, a Markov chain's, a design's
/// and a replay of failures alone.
WeightedRecords SelectWeightedRecords(const std::vector<ReportRecord>& records,
                                      const std::string& path, const std::string& spec_hash);

/// SelectWeightedRecords of the JSON Lines records in `lines` (`prs estimate -o`, `prs test
/// -o`); a line that is not a record is a located error too (ParseReportRecords).
WeightedRecords ReadWeightedRecords(const std::vector<std::string>& lines, const std::string& path,
                                    const std::string& spec_hash);

struct EstimateOptions {
  int64_t budget = 0;          // episodes in all
  double adapt_share = 0.3;    // of the budget spent adapting the proposal
  double uniform_share = 0.2;  // the mixture's uniform share in the sampling phase
  /// Seed, threads, sampling options, cancel, save_failures_dir (start, count, on_record and
  /// sample.points are set here).
  harness::RunOptions run;
  /// Each record in evaluation order (adaptation first), as its generation finishes.
  std::function<void(const harness::EpisodeRecord&)> on_record;
};

struct EstimateSummary {
  std::vector<harness::EpisodeRecord> records;  // adaptation, then sampling
  int64_t adapt_episodes = 0;  // unweighted: the search's, the probe's and the walks'
  bool scored = false;         // the controller reported scores
  MixtureProposal proposal;    // the sampling phase's
  Estimate estimate;
  int threads = 1;
};

/// The smallest budget RunEstimate takes.
inline constexpr int64_t kMinEstimateBudget = 200;

/// The sizes of an estimate's generations, in order: the first cross-entropy search's (two
/// thirds of adapt_share of the budget, itself at least 60), the probe's (none when a tenth of
/// the budget gives fewer than four episodes per coordinate), the second search's (the other
/// third), the exploration's (10 %), each round of the walks (10 %), and the sampling's (the
/// rest). A function of these alone, so that a campaign cuts its
/// shards at init (docs/cluster.md); without failures to probe, explore or walk from, those
/// generations draw the sampling proposal instead.
std::vector<int64_t> CalcEstimateLayout(int64_t budget, int dimension,
                                        double adapt_share = EstimateOptions{}.adapt_share);

/// The estimate's state between generations, laid out as CalcEstimateLayout says: RunEstimate
/// is a loop over it, and src/campaign replays it from the records on disk. Each generation's
/// plan is a pure function of the earlier generations' records (index, outcome, score and
/// coordinates are all it reads), so the same for any thread count, machine or shard layout.
class EstimatePlanner : public GenerationPlanner {
 public:
  /// Throws std::invalid_argument for a budget under kMinEstimateBudget, and NothingToSearch.
  EstimatePlanner(const lang::CompiledProgram& program, const EstimateOptions& options);
  ~EstimatePlanner() override;
  bool done() const override;
  GenerationPlan Next() override;
  void Add(std::vector<harness::EpisodeRecord> records) override;
  /// Whether a generation's records are weighted ones (the exploration's and the sampling's):
  /// their "search" tag says "estimate-explore" or "estimate-sample" until Finish gives them
  /// their weights, so a record file of them alone estimates nothing.
  static bool IsWeighted(const GenerationPlan& plan);
  /// Once done(): every record as `prs estimate -o` writes them (the adaptation's in index
  /// order, then the weighted ones in index order with their "search" tag of weights:
  /// RunEstimate), and the estimate. `threads` is left at 1.
  EstimateSummary Finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Adapts a proposal toward failures — the failure search's cross-entropy method on two thirds
/// of adapt_share of the budget, a probe of which coordinates failing depends on (the others
/// stay uniform), a second search on the last third that sees the first one's failure region
/// as safe and so finds a second cause if there is one, an exploration around the causes
/// (10 %) whose weighted failures place kernels,
/// random walks among the failures from them (10 %) whose states place the kernels of the
/// sampling proposal — then runs the rest of the budget from that proposal mixed with the
/// uniform law (EstimatePlanner). The exploration's and the sampling's records carry "search":
/// {"strategy": "importance", "phase", "weight": W, "uniform_share": S, "normalised",
/// "kernel_share"}, their weights those of both phases' deterministic mixture (docs/search.md
/// derives them). A pure function of (program, controller, options) for any thread count.
/// Throws std::invalid_argument for a budget under kMinEstimateBudget, NothingToSearch, and
/// what harness::RunEpisodes throws.
EstimateSummary RunEstimate(const lang::CompiledProgram& program,
                            const harness::ControllerFactory& factory,
                            const EstimateOptions& options);

}  // namespace prs::search
