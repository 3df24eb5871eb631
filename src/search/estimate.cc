// prs estimate: the adaptation loop (weighted cross-entropy toward failures), the importance-
// sampling run from a defensive mixture, and the self-normalised estimator with its delta-method
// interval (derivations in docs/search.md).
#include "search/estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "search/intervals.h"
#include "search/like.h"
#include "search/search.h"

namespace prs::search {
namespace {

constexpr double kSamplingWidening = 2.5;
constexpr double kExploreShare = 0.1;  // of the budget
constexpr double kWalkShare = 0.1;     // of the budget
constexpr size_t kChains = 16;
constexpr int64_t kMinFailuresToFit = 10;
constexpr size_t kProbeFailures = 8;
constexpr size_t kKernels = 64;

// The normal CDF.
double CalcNormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// The density at x of the normal (mean, std) truncated to [0, 1].
double CalcTruncatedNormalDensity(double x, double mean, double std) {
  const double mass = CalcNormalCdf((1 - mean) / std) - CalcNormalCdf(-mean / std);
  if (!(mass > 0)) return 1;  // MixturePoints then draws this coordinate uniformly
  const double z = (x - mean) / std;
  return std::exp(-0.5 * z * z) / (std::sqrt(2 * M_PI) * std * mass);
}

// The failures' mean and spread per coordinate (at least kMinProposalStd), each failure
// weighted by 1 / the density it was drawn from (`drawn_from`, null for equal weights), so that
// they estimate the moments of the law restricted to the failures; coordinates with std 0 stay
// uniform.
void FitToFailures(const std::vector<const harness::EpisodeRecord*>& failures,
                   const MixtureProposal* drawn_from, MixtureProposal& proposal) {
  std::vector<double> w;
  double total = 0;
  for (const harness::EpisodeRecord* r : failures) {
    w.push_back(drawn_from ? 1 / drawn_from->CalcDensity(r->coordinates.data()) : 1.0);
    total += w.back();
  }
  for (int j = 0; j < proposal.dimension(); ++j) {
    if (proposal.std[j] <= 0) continue;
    double mean = 0, variance = 0;
    for (size_t k = 0; k < failures.size(); ++k) mean += w[k] * failures[k]->coordinates[j];
    mean /= total;
    for (size_t k = 0; k < failures.size(); ++k) {
      variance += w[k] * std::pow(failures[k]->coordinates[j] - mean, 2);
    }
    proposal.mean[j] = mean;
    proposal.std[j] = std::max(std::sqrt(variance / total), kMinProposalStd);
  }
}

// A bandwidth for `kernels` kernels: each spread (std > 0) times Scott's factor
// K^(-1 / (d + 4)) over the d coordinates failing depends on, at least kMinProposalStd.
void NarrowByScott(size_t kernels, MixtureProposal& proposal) {
  const auto relevant =
      std::count_if(proposal.std.begin(), proposal.std.end(), [](double s) { return s > 0; });
  const double scott = std::pow(double(kernels), -1.0 / double(relevant + 4));
  for (double& std : proposal.std) {
    if (std > 0) std = std::max(std * scott, kMinProposalStd);
  }
}

// The normals' component as kernels around failures of the exploration, drawn with
// probability in proportion to their weights (systematic resampling, so deterministic), with
// a bandwidth of the failures' spread times Scott's factor K^(-1 / (d + 4)) over the d
// coordinates failing depends on.
void PlaceKernels(const std::vector<const harness::EpisodeRecord*>& failures,
                  const MixtureProposal& drawn_from, MixtureProposal& proposal) {
  std::vector<double> cumulative;
  double total = 0;
  for (const harness::EpisodeRecord* r : failures) {
    total += 1 / drawn_from.CalcDensity(r->coordinates.data());
    cumulative.push_back(total);
  }
  const size_t k = std::min<size_t>(kKernels, failures.size());
  proposal.centres.clear();
  for (size_t i = 0; i < k; ++i) {
    const double at = (double(i) + 0.5) / double(k) * total;
    const size_t pick =
        size_t(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin());
    proposal.centres.push_back(failures[std::min(pick, failures.size() - 1)]->coordinates);
  }
  NarrowByScott(k, proposal);
}

// Kernels around `points` (equal weights; at most kKernels of them, evenly spaced), with a
// bandwidth of their spread times Scott's factor, on the coordinates with std > 0.
void PlaceKernelsAt(const std::vector<std::vector<double>>& points, MixtureProposal& proposal) {
  const double n = double(points.size());
  for (int j = 0; j < proposal.dimension(); ++j) {
    if (proposal.std[j] <= 0) continue;
    double mean = 0, variance = 0;
    for (const auto& u : points) mean += u[j] / n;
    for (const auto& u : points) variance += std::pow(u[j] - mean, 2) / n;
    proposal.std[j] = std::sqrt(variance);
  }
  const size_t k = std::min<size_t>(kKernels, points.size());
  proposal.centres.clear();
  for (size_t i = 0; i < k; ++i) proposal.centres.push_back(points[i * points.size() / k]);
  NarrowByScott(k, proposal);
}

// Scene start + k's first attempt at points[k]; its later attempts read the stream (the probe
// only shapes the proposal, so it need not follow any law).
class ProbePoints : public sampling::AttemptPoints {
 public:
  ProbePoints(uint64_t start, std::vector<std::vector<double>> points)
      : start_(start), points_(std::move(points)) {}
  int dimension() const override { return int(points_.front().size()); }
  bool Point(uint64_t, uint64_t index, int64_t attempt, double* u) const override {
    if (attempt != 0 || index < start_ || index - start_ >= points_.size()) return false;
    std::copy(points_[index - start_].begin(), points_[index - start_].end(), u);
    return true;
  }

 private:
  uint64_t start_;
  std::vector<std::vector<double>> points_;
};

// Episodes start, start + 1, ... with their first attempts at `points` (ProbePoints).
std::vector<harness::EpisodeRecord> RunAtPoints(const lang::CompiledProgram& program,
                                                const harness::ControllerFactory& factory,
                                                const EstimateOptions& options, uint64_t start,
                                                std::vector<std::vector<double>> points) {
  const int64_t count = int64_t(points.size());
  const ProbePoints probe(start, std::move(points));
  harness::RunOptions run = options.run;
  run.sample.points = &probe;
  run.start = start;
  run.count = count;
  run.on_record = nullptr;
  return harness::RunEpisodes(program, factory, run).records;
}

// Which coordinates failing depends on: a few failures, each run again with one coordinate
// redrawn uniformly; a coordinate whose redraw keeps half of them failing or more gets std 0
// (uniform) in `proposal`. Returns the probe's records.
std::vector<harness::EpisodeRecord> ProbeCoordinates(
    const lang::CompiledProgram& program, const harness::ControllerFactory& factory,
    const EstimateOptions& options, const std::vector<const harness::EpisodeRecord*>& failures,
    uint64_t start, MixtureProposal& proposal) {
  const int d = proposal.dimension();
  // At most a tenth of the budget; too few failures per coordinate tell nothing.
  const size_t m =
      std::min<size_t>({failures.size(), kProbeFailures, size_t(options.budget / 10 / d)});
  if (m < kProbeFailures / 2) return {};
  std::vector<std::vector<double>> points;
  geometry::Rng rng(options.run.seed ^ 0x5EEDFACEULL, start);
  for (int j = 0; j < d; ++j) {
    for (size_t k = 0; k < m; ++k) {
      // Spread over the failures found (the search's last ones are its deepest).
      std::vector<double> u = failures[k * failures.size() / m]->coordinates;
      u[j] = rng.Uniform01();
      points.push_back(std::move(u));
    }
  }
  std::vector<harness::EpisodeRecord> records =
      RunAtPoints(program, factory, options, start, std::move(points));
  for (int j = 0; j < d; ++j) {
    size_t still = 0;
    for (size_t k = 0; k < m; ++k) still += records[size_t(j) * m + k].result.outcome != "success";
    if (2 * still >= m) proposal.std[j] = 0;
  }
  for (harness::EpisodeRecord& r : records) r.search = {{"strategy", "estimate-probe"}};
  return records;
}

// Random walks that stay among the failures (Metropolis for the law restricted to them): from
// `starts`, each step moves the coordinates failing depends on (std > 0 in `proposal`) by a
// normal step, reflected into [0, 1), and keeps the move when the episode there fails at that
// very point. The step adapts toward a third of the moves kept. Returns every chain's state
// after each of its later steps (the law restricted to the failures, roughly); the walk's
// records go to `records`.
std::vector<std::vector<double>> WalkFailures(const lang::CompiledProgram& program,
                                              const harness::ControllerFactory& factory,
                                              const EstimateOptions& options,
                                              std::vector<std::vector<double>> chains,
                                              const MixtureProposal& proposal, int64_t budget,
                                              uint64_t& next,
                                              std::vector<harness::EpisodeRecord>& records) {
  std::vector<double> step = proposal.std;
  geometry::Rng rng(options.run.seed ^ 0x3A1C5EEDULL, next);
  std::vector<std::vector<double>> states;
  const int64_t rounds = budget / int64_t(chains.size());
  for (int64_t round = 0; round < rounds; ++round) {
    std::vector<std::vector<double>> moves = chains;
    for (std::vector<double>& u : moves) {
      for (size_t j = 0; j < u.size(); ++j) {
        if (step[j] <= 0) continue;
        double x = std::fmod(std::abs(u[j] + step[j] * geometry::MapNormal(rng.Uniform01())), 2.0);
        if (x >= 1) x = 2 - x;
        u[j] = std::min(x, 1.0 - 0x1.0p-53);
      }
    }
    std::vector<harness::EpisodeRecord> ran = RunAtPoints(program, factory, options, next, moves);
    next += moves.size();
    int kept = 0;
    for (size_t k = 0; k < chains.size(); ++k) {
      if (ran[k].result.outcome != "success" && ran[k].coordinates == moves[k]) {
        chains[k] = moves[k];
        ++kept;
      }
      if (round >= rounds / 3) states.push_back(chains[k]);  // after a burn-in
      ran[k].search = {{"strategy", "estimate-walk"}};
      records.push_back(std::move(ran[k]));
    }
    const double rate = double(kept) / double(chains.size());
    for (double& s : step) s *= rate < 0.2 ? 0.7 : rate > 0.45 ? 1.4 : 1.0;
  }
  return states;
}

// Runs `count` episodes from index `start` at points of `proposal`.
std::vector<harness::EpisodeRecord> RunAt(const lang::CompiledProgram& program,
                                          const harness::ControllerFactory& factory,
                                          const EstimateOptions& options,
                                          const MixtureProposal& proposal, uint64_t start,
                                          int64_t count, int* threads, int64_t* rejections) {
  const MixturePoints points(proposal);
  harness::RunOptions run = options.run;
  run.sample.points = &points;
  run.start = start;
  run.count = count;
  run.on_record = nullptr;
  harness::RunSummary summary = harness::RunEpisodes(program, factory, run);
  *threads = summary.threads;
  *rejections += summary.sampling.rejections.total;
  return std::move(summary.records);
}

// Estimate::uncovered_share: the draws with the lowest scores, as many as make
// kNearFailureMass of the weight (of the program's law), and the weighted share of them drawn
// where the normals give under half the proposal's density. NaN when a record has no score or
// no kernel share.
double CalcUncoveredShare(const std::vector<WeightedOutcome>& records, double total_weight) {
  std::vector<const WeightedOutcome*> by_score;
  for (const WeightedOutcome& r : records) {
    if (std::isnan(r.score) || std::isnan(r.kernel_share)) return NAN;
    by_score.push_back(&r);
  }
  std::stable_sort(by_score.begin(), by_score.end(),
                   [](const auto* a, const auto* b) { return a->score < b->score; });
  double near = 0, uncovered = 0;
  for (const WeightedOutcome* r : by_score) {
    if (near >= kNearFailureMass * total_weight && r->score > 0) break;
    near += r->weight;
    if (r->kernel_share < 0.5) uncovered += r->weight;
  }
  return near > 0 ? uncovered / near : NAN;
}

}  // namespace

double MixtureProposal::CalcDensity(const double* u) const {
  if (uniform_share >= 1) return 1;
  auto normals = [&](const std::vector<double>& centre) {
    double density = 1;
    for (int j = 0; j < dimension(); ++j) {
      if (std[j] > 0) density *= CalcTruncatedNormalDensity(u[j], centre[j], std[j]);
    }
    return density;
  };
  double gaussian = 0;
  if (centres.empty()) {
    gaussian = normals(mean);
  } else {
    for (const std::vector<double>& centre : centres) gaussian += normals(centre);
    gaussian /= double(centres.size());
  }
  return uniform_share + (1 - uniform_share) * gaussian;
}

double MixtureProposal::CalcKernelShare(const double* u) const {
  if (uniform_share >= 1) return 0;
  const double density = CalcDensity(u);
  return (density - uniform_share) / density;
}

bool MixturePoints::Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const {
  geometry::Rng rng = MakeProposalRng(seed, index, attempt);
  const int d = dimension();
  if (proposal_.uniform_share >= 1 || rng.Uniform01() < proposal_.uniform_share) {
    for (int j = 0; j < d; ++j) u[j] = rng.Uniform01();
    return true;
  }
  const std::vector<double>& centre =
      proposal_.centres.empty()
          ? proposal_.mean
          : proposal_.centres[size_t(rng.UniformInt(0, int64_t(proposal_.centres.size()) - 1))];
  for (int j = 0; j < d; ++j) {
    const double v = rng.Uniform01();
    if (proposal_.std[j] <= 0) {
      u[j] = v;
      continue;
    }
    const double x = geometry::MapTruncatedNormal(v, centre[j], proposal_.std[j], 0, 1);
    u[j] = std::isnan(x) ? rng.Uniform01() : std::min(x, 1.0 - 0x1.0p-53);
  }
  return true;
}

std::string DescribeUnreliable(const Estimate& e) {
  if (e.reliable) return "";
  if (e.uncovered_share > kMaxUncoveredShare) {
    return fmt::format(
        "the proposal misses where the controller nearly fails: {:.0f} % of the episodes "
        "nearest to failing ({:.0f} % of the scenes, by score) were drawn where only its uniform "
        "share reaches, so the failure set may extend where it drew too little to tell; no "
        "estimate is given, as its interval could not be trusted (docs/search.md, \"How "
        "good\"); raise --budget",
        100 * e.uncovered_share, 100 * kNearFailureMass);
  }
  return fmt::format(
      "the weights degenerate (effective sample size {:.0f} of {} weighted episodes): no "
      "estimate is given, as its interval could not be trusted; raise --budget",
      e.ess, e.episodes);
}

Estimate CalcEstimate(const std::vector<WeightedOutcome>& records,
                      const std::vector<std::string>& also_seen) {
  if (records.empty()) throw std::invalid_argument("no records to estimate from");
  Estimate estimate;
  estimate.episodes = int64_t(records.size());
  double total = 0, squares = 0, share = 1;
  std::map<std::string, std::pair<double, int64_t>> failed;  // outcome -> (weight, episodes)
  for (const WeightedOutcome& r : records) {
    if (!(r.weight > 0) || !std::isfinite(r.weight)) {
      throw std::invalid_argument(
          fmt::format("a record's weight is {}, not a positive number", r.weight));
    }
    total += r.weight;
    squares += r.weight * r.weight;
    share = std::min(share, r.uniform_share);
    estimate.iid = estimate.iid && r.weight == 1 && r.uniform_share == 1;
    if (r.outcome == "success") continue;
    failed[r.outcome].first += r.weight;
    ++failed[r.outcome].second;
  }
  estimate.ess = total * total / squares;
  estimate.reliable = estimate.ess >= kMinEss && estimate.ess >= 0.05 * double(estimate.episodes);
  estimate.uncovered_share = CalcUncoveredShare(records, total);
  if (estimate.uncovered_share > kMaxUncoveredShare) estimate.reliable = false;
  const bool normalised =
      std::any_of(records.begin(), records.end(), [](const auto& r) { return r.normalised; });
  const double n = double(records.size());
  // No failure of a kind in n draws from the proposal: P(that kind | proposal) <= 1 - 0.05^(1/n)
  // at 95 %, and p = E[w 1F] / E[w] <= P(fail | proposal) / (share * mean weight), as
  // w <= 1 / share.
  const double bound_proposal = 1 - std::pow(0.05, 1 / n);
  const double mean_weight = normalised ? total / n : 1.0;
  const double upper_bound = std::min(1.0, bound_proposal / (share * mean_weight));
  for (const auto& [outcome, weight_and_count] : failed) {
    // Self-normalised, sum w 1F / sum w, with the delta method's variance; or, when the weights'
    // mean is known to be 1, the plain mean of w 1F with its sample variance.
    const double p = weight_and_count.first / (normalised ? total : n);
    OutcomeEstimate o{outcome, weight_and_count.second, p};
    double variance = 0;
    for (const WeightedOutcome& r : records) {
      const double f = r.outcome == outcome ? 1.0 : 0.0;
      variance += normalised ? r.weight * r.weight * (f - p) * (f - p)
                             : (r.weight * f - p) * (r.weight * f - p);
    }
    variance /= normalised ? total * total : n * (n - 1);
    // The exact binomial interval at the effective counts (intervals.h): right for few
    // failures and for p near 1, where the delta method's p +- 1.96 sd is not.
    const RateInterval ci = CalcEffectiveCountInterval(std::min(p, 1.0), variance, estimate.ess);
    o.ci_low = ci.low;
    o.ci_high = ci.high;
    o.iid_episodes = variance > 0 ? o.p * (1 - o.p) / variance : estimate.ess;
    estimate.outcomes.push_back(o);
  }
  std::stable_sort(estimate.outcomes.begin(), estimate.outcomes.end(),
                   [](const auto& a, const auto& b) { return a.p > b.p; });
  // Failure kinds seen elsewhere (an adaptation's episodes) but not here: a row with the bound.
  std::set<std::string> unseen(also_seen.begin(), also_seen.end());
  unseen.erase("success");
  for (const auto& [outcome, ignored] : failed) unseen.erase(outcome);
  for (const std::string& outcome : unseen) {
    estimate.outcomes.push_back({outcome, 0, 0, 0, upper_bound, 0});
  }
  if (failed.empty()) estimate.upper_bound = upper_bound;
  return estimate;
}

WeightedRecords SelectWeightedRecords(const std::vector<ReportRecord>& records,
                                      const std::string& path, const std::string& spec_hash) {
  WeightedRecords weighted, plain;
  std::set<std::string> seen;
  const ReportRecord* refused = nullptr;  // the first record whose law gives no estimate
  for (const ReportRecord& record : records) {
    if (!spec_hash.empty() && !record.spec.empty() && record.spec != spec_hash) {
      throw std::runtime_error(fmt::format(
          "{}:{}: the record was drawn from another program (fingerprint \"{}\", this one's "
          "\"{}\")",
          path, record.line, record.spec, spec_hash));
    }
    seen.insert(record.outcome);
    const RecordLaw law = DescribeLaw(record);
    if (law == RecordLaw::kImportance) {
      weighted.records.push_back({record.outcome, record.weight, record.uniform_share,
                                  record.normalised, record.score.value_or(NAN),
                                  record.kernel_share});
    } else if (law == RecordLaw::kIid) {
      plain.records.push_back({record.outcome});
    } else if (law != RecordLaw::kSearch) {
      // A chain's, a design's or a replay of failures: never an estimate, whatever else the
      // file holds. A search's records beside weighted ones are an estimate's adaptation.
      throw std::runtime_error(fmt::format(
          "{}:{}: {} give no estimate of how often the controller fails under the program's "
          "law: {}",
          path, record.line, DescribeLawInWords(law),
          law == RecordLaw::kSelected
              ? "estimate from the records it replays, or replay them all (without --failed)"
          : law == RecordLaw::kChain
              ? "run prs test without --sampler gibbs, or prs estimate"
              : "run prs test without --design, or prs estimate"));
    } else if (!refused) {
      refused = &record;
    }
  }
  WeightedRecords& chosen = !weighted.records.empty() ? weighted : plain;
  if (chosen.records.empty()) {
    throw std::runtime_error(
        refused ? fmt::format("{}:{}: {} holds only {}: estimate with `prs estimate`, whose "
                              "records carry weights",
                              path, refused->line, path, DescribeLawInWords(RecordLaw::kSearch))
                : path + " holds no record");
  }
  chosen.outcomes_seen.assign(seen.begin(), seen.end());
  return chosen;
}

WeightedRecords ReadWeightedRecords(const std::vector<std::string>& lines, const std::string& path,
                                    const std::string& spec_hash) {
  return SelectWeightedRecords(ParseReportRecords(lines, path), path, spec_hash);
}

EstimateSummary RunEstimate(const lang::CompiledProgram& program,
                            const harness::ControllerFactory& factory,
                            const EstimateOptions& options) {
  if (options.budget < kMinEstimateBudget) {
    throw std::invalid_argument(
        fmt::format("a budget of {} episodes is too small to adapt a "
                    "proposal and then sample: give at least {}",
                    options.budget, kMinEstimateBudget));
  }
  const int dimension = int(sampling::DescribeCoordinates(program, options.run.sample).size());
  if (dimension == 0) throw NothingToSearch("the program draws nothing at random");
  EstimateSummary summary;
  const int64_t adapt = std::max<int64_t>(60, std::llround(options.adapt_share * options.budget));
  const int64_t piece = 200;  // sampling episodes per batch (records arrive between them)
  MixtureProposal proposal{std::vector<double>(dimension, 0.5),
                           std::vector<double>(dimension, 1 / std::sqrt(12.0)),
                           1.0,
                           {}};
  uint64_t next = 0;
  // Adaptation: the failure search's cross-entropy method (search.cc), whose records lead the
  // record file.
  SearchOptions search;
  search.strategy = Strategy::kCrossEntropy;
  search.budget = adapt;
  search.run = options.run;
  search.on_record = options.on_record;
  SearchSummary found = RunSearch(program, factory, search);
  summary.threads = found.threads;
  summary.generations = found.generations;
  summary.adapt_episodes = adapt;
  next = uint64_t(adapt);
  if (!found.proposal_mean.empty()) {
    proposal.mean = found.proposal_mean;
    proposal.std = found.proposal_std;
  }
  // The sampling proposal: fitted to every failure the search found when there are enough (the
  // optimal proposal is the law restricted to the failures), widened to cover their region.
  std::vector<const harness::EpisodeRecord*> failures;
  for (const harness::EpisodeRecord& r : found.records) {
    summary.scored = summary.scored || r.result.score.has_value();
    if (r.result.outcome != "success" && !r.coordinates.empty()) failures.push_back(&r);
  }
  if (int64_t(failures.size()) >= kMinFailuresToFit) FitToFailures(failures, nullptr, proposal);
  proposal.uniform_share = options.uniform_share;
  summary.records = std::move(found.records);
  auto keep = [&](std::vector<harness::EpisodeRecord>&& records) {
    next += records.size();
    for (harness::EpisodeRecord& r : records) {
      if (options.on_record) options.on_record(r);
      summary.records.push_back(std::move(r));
    }
  };
  if (!failures.empty()) {
    keep(ProbeCoordinates(program, factory, options, failures, next, proposal));
  }
  // The search's failures crowd around its best point: explore around them widely and fit
  // the failures found there with their weights, which reach the whole failure region. The
  // exploration's episodes are weighted too (below), as draws of its wider proposal.
  std::vector<harness::EpisodeRecord> explored, walks;
  MixtureProposal explore = proposal;
  int64_t rejections = 0;
  if (int64_t(failures.size()) >= kMinFailuresToFit) {
    for (double& std : explore.std) std = std > 0 ? std::max(4 * std, 0.1) : 0;
    const int64_t count = std::llround(kExploreShare * double(options.budget));
    explored =
        RunAt(program, factory, options, explore, next, count, &summary.threads, &rejections);
    next += uint64_t(count);
    std::vector<const harness::EpisodeRecord*> found_there;
    for (const harness::EpisodeRecord& r : explored) {
      if (r.result.outcome != "success") found_there.push_back(&r);
    }
    if (int64_t(found_there.size()) >= kMinFailuresToFit) {
      FitToFailures(found_there, &explore, proposal);
      PlaceKernels(found_there, explore, proposal);
      // Walks from the kernels' centres spread over the whole (connected) failure region.
      std::vector<std::vector<double>> starts(
          proposal.centres.begin(),
          proposal.centres.begin() + std::min<size_t>(kChains, proposal.centres.size()));
      MixtureProposal walk_step = proposal;
      for (double& std : walk_step.std) std = std > 0 ? 2 * std : 0;
      std::vector<harness::EpisodeRecord> walked;
      const std::vector<std::vector<double>> states =
          WalkFailures(program, factory, options, std::move(starts), walk_step,
                       std::llround(kWalkShare * double(options.budget)), next, walked);
      if (states.size() >= size_t(kMinFailuresToFit)) PlaceKernelsAt(states, proposal);
      for (harness::EpisodeRecord& r : walked) {
        if (options.on_record) options.on_record(r);
        walks.push_back(std::move(r));
      }
    } else {
      proposal = explore;
    }
  }
  for (double& std : proposal.std) std *= kSamplingWidening;
  // Nothing to aim at: the program's own law, whose episodes bound the failure rate best.
  if (failures.empty()) proposal.uniform_share = 1;
  summary.adapt_episodes = int64_t(next) - int64_t(explored.size());
  summary.records.insert(summary.records.end(), std::make_move_iterator(walks.begin()),
                         std::make_move_iterator(walks.end()));
  summary.proposal = proposal;
  std::vector<harness::EpisodeRecord> sampled;
  while (int64_t(next) < options.budget) {  // in pieces, so that records arrive as they finish
    const int64_t count = std::min<int64_t>(piece, options.budget - int64_t(next));
    std::vector<harness::EpisodeRecord> records =
        RunAt(program, factory, options, proposal, next, count, &summary.threads, &rejections);
    next += uint64_t(count);
    for (harness::EpisodeRecord& r : records) sampled.push_back(std::move(r));
  }
  // Both weighted phases as draws of their deterministic mixture (the balance heuristic): an
  // episode's weight is 1 / ((n1 q1 + n2 q2) / (n1 + n2)) at its point. Without a rejection the
  // accepted set is (as far as thousands of attempts tell) the whole cube, the weights' mean is
  // 1, and the plain mean of w 1F needs no normalising.
  const double n1 = double(explored.size()), n2 = double(sampled.size());
  std::vector<WeightedOutcome> weighted;
  for (std::vector<harness::EpisodeRecord>* phase : {&explored, &sampled}) {
    for (harness::EpisodeRecord& r : *phase) {
      const double* u = r.coordinates.data();
      const double density =
          (n1 * (n1 > 0 ? explore.CalcDensity(u) : 0) + n2 * proposal.CalcDensity(u)) / (n1 + n2);
      const WeightedOutcome w{r.result.outcome,
                              1 / density,
                              proposal.uniform_share,
                              rejections > 0,
                              r.result.score.value_or(NAN),
                              proposal.CalcKernelShare(u)};
      weighted.push_back(w);
      r.search = {{"strategy", "importance"},
                  {"phase", phase == &explored ? "explore" : "sample"},
                  {"weight", w.weight},
                  {"uniform_share", w.uniform_share},
                  {"normalised", w.normalised},
                  {"kernel_share", w.kernel_share}};
      if (options.on_record) options.on_record(r);
      summary.records.push_back(std::move(r));
    }
  }
  // Every failure kind of every phase gets a row, a bound at least (the adaptation's too).
  std::set<std::string> seen;
  for (const harness::EpisodeRecord& r : summary.records) seen.insert(r.result.outcome);
  summary.estimate = CalcEstimate(weighted, std::vector<std::string>(seen.begin(), seen.end()));
  return summary;
}

}  // namespace prs::search
