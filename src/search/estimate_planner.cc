// prs estimate's adaptation as generations (estimate.h, EstimatePlanner): the failure search's
// cross-entropy method, a probe of which coordinates failing depends on, a second search that
// sees the first one's failure region as safe (a second cause), a weighted exploration around
// the causes, random walks among the failures that place the sampling proposal's kernels, and
// the sampling; then the weights of the deterministic mixture of the weighted generations
// (derivations in docs/search.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "geometry/random.h"
#include "search/estimate.h"
#include "search/like.h"
#include "search/search.h"

namespace prs::search {
namespace {

// The sampling proposal: the kernels' spread times kSamplingWidening, and of the normals'
// component a kWideShare drawn kWideFactor times wider still (MixtureProposal's wide layer).
constexpr double kSamplingWidening = 2.5;
constexpr double kWideShare = 0.5;
constexpr double kWideFactor = 6 / kSamplingWidening;
// Each walk kernel's own spread: kLocalBandwidth times the distance to its kNeighbours-th
// nearest distinct walk state (in units of the Scott bandwidth), at least kMinLocalStd and at
// most the Scott bandwidth: narrow inside each of several failure regions, as wide as before
// where the states are sparse.
constexpr double kLocalBandwidth = 0.5;
constexpr size_t kNeighbours = 5;
constexpr double kMinLocalStd = 0.005;
constexpr double kExploreShare = 0.1;  // of the budget
constexpr double kWalkShare = 0.1;     // of the budget
constexpr int64_t kChains = 16;        // walks: at least, and the starts among the kernels
constexpr int64_t kWalkRounds = 12;    // walks: steps of each chain
constexpr int64_t kMinFailuresToFit = 10;
constexpr int64_t kProbeFailures = 8;
constexpr size_t kKernels = 64;
// The second search's share of the searches' budget: a failure with two causes is found one
// cause at a time, so a second search runs with the first one's failure region deflated
// (scored as safe) and finds the next cause if there is one.
constexpr double kSecondSearchShare = 1.0 / 3;

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
  proposal.centre_std.clear();
  for (size_t i = 0; i < k; ++i) {
    const double at = (double(i) + 0.5) / double(k) * total;
    const size_t pick =
        size_t(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin());
    proposal.centres.push_back(failures[std::min(pick, failures.size() - 1)]->coordinates);
  }
  NarrowByScott(k, proposal);
}

// Each centre's own spread (MixtureProposal::centre_std): the bandwidth `scott` times
// kLocalBandwidth times the distance, in units of `scott`, to the centre's kNeighbours-th
// nearest distinct point of `points`, between kMinLocalStd and `scott`.
std::vector<std::vector<double>> CalcLocalSpreads(const std::vector<std::vector<double>>& centres,
                                                  std::vector<std::vector<double>> points,
                                                  const std::vector<double>& scott) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::vector<std::vector<double>> spreads;
  for (const std::vector<double>& centre : centres) {
    std::vector<double> squared;
    for (const std::vector<double>& point : points) {
      double distance = 0;
      for (size_t j = 0; j < centre.size(); ++j) {
        if (scott[j] > 0) distance += std::pow((centre[j] - point[j]) / scott[j], 2);
      }
      if (distance > 0) squared.push_back(distance);
    }
    const size_t k = std::min(kNeighbours, squared.size());
    double radius = 1;
    if (k > 0) {
      std::nth_element(squared.begin(), squared.begin() + ptrdiff_t(k - 1), squared.end());
      radius = std::sqrt(squared[k - 1]);
    }
    std::vector<double> spread = scott;
    for (size_t j = 0; j < spread.size(); ++j) {
      if (scott[j] > 0) {
        spread[j] = std::min(scott[j], std::max(kLocalBandwidth * radius * scott[j], kMinLocalStd));
      }
    }
    spreads.push_back(std::move(spread));
  }
  return spreads;
}

// Kernels around `points` (equal weights; at most kKernels of them, evenly spaced), with a
// bandwidth of their spread times Scott's factor, on the coordinates with std > 0, each
// narrowed where the points around it are dense (CalcLocalSpreads).
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
  proposal.centre_std = CalcLocalSpreads(proposal.centres, points, proposal.std);
}

// Per coordinate that failing depends on (std > 0 in `mask`), the failures' spread around the
// mean of the cause each is nearest to (`modes`, by distance over those coordinates), pooled
// over the causes: the width of one cause's region, not the distance between causes. At least
// kMinProposalStd.
std::vector<double> CalcPooledSpread(const std::vector<const harness::EpisodeRecord*>& failures,
                                     const std::vector<std::vector<double>>& modes,
                                     const std::vector<double>& mask) {
  const size_t d = mask.size(), causes = std::max<size_t>(1, modes.size());
  std::vector<size_t> cause(failures.size(), 0);
  for (size_t i = 0; i < failures.size() && modes.size() > 1; ++i) {
    double best = INFINITY;
    for (size_t c = 0; c < modes.size(); ++c) {
      double distance = 0;
      for (size_t j = 0; j < d; ++j) {
        if (mask[j] > 0) distance += std::pow(failures[i]->coordinates[j] - modes[c][j], 2);
      }
      if (distance < best) std::tie(best, cause[i]) = std::tuple(distance, c);
    }
  }
  std::vector<double> spread(d, 0);
  for (size_t j = 0; j < d; ++j) {
    if (mask[j] <= 0) continue;
    std::vector<double> count(causes, 0), mean(causes, 0);
    for (size_t i = 0; i < failures.size(); ++i) {
      count[cause[i]] += 1;
      mean[cause[i]] += failures[i]->coordinates[j];
    }
    for (size_t c = 0; c < causes; ++c) mean[c] /= count[c] > 0 ? count[c] : 1;
    double variance = 0;
    for (size_t i = 0; i < failures.size(); ++i) {
      variance += std::pow(failures[i]->coordinates[j] - mean[cause[i]], 2);
    }
    spread[j] = std::max(std::sqrt(variance / double(failures.size())), kMinProposalStd);
  }
  return spread;
}

// Scene coordinates of failures (the records' points), for the fits above.
std::vector<const harness::EpisodeRecord*> Failures(
    const std::vector<harness::EpisodeRecord>& records) {
  std::vector<const harness::EpisodeRecord*> failures;
  for (const harness::EpisodeRecord& r : records) {
    if (r.result.outcome != "success" && !r.coordinates.empty()) failures.push_back(&r);
  }
  return failures;
}

// Reflects x into [0, 1) (the walks' moves).
double Reflect(double x) {
  x = std::fmod(std::abs(x), 2.0);
  if (x >= 1) x = 2 - x;
  return std::min(x, 1.0 - 0x1.0p-53);
}

// What a generation of the estimate is for.
enum class Phase { kSearch, kProbe, kExplore, kWalk, kSample };

const char* PhaseTag(Phase phase) {  // the "strategy" its records carry until Finish
  switch (phase) {
    case Phase::kSearch:
      return "ce";
    case Phase::kProbe:
      return "estimate-probe";
    case Phase::kExplore:
      return "estimate-explore";
    case Phase::kWalk:
      return "estimate-walk";
    case Phase::kSample:
      return "estimate-sample";
  }
  return "";
}

// The proposal a weighted generation's plan draws from.
MixtureProposal DrawnFrom(const GenerationPlan& plan) {
  return {plan.mean,       plan.std,        plan.uniform_share, plan.centres,
          plan.centre_std, plan.wide_share, plan.wide_factor};
}

struct Layout {
  int64_t search = 0;  // both searches: the first of search - second_search, then the second
  int64_t second_search = 0;
  int64_t probe = 0, explore = 0, chains = 0, rounds = 0, sample = 0;
  int64_t probe_per_coordinate = 0;
};

Layout MakeLayout(int64_t budget, int dimension, double adapt_share) {
  Layout l;
  l.search = std::max<int64_t>(60, std::llround(adapt_share * double(budget)));
  l.second_search = std::llround(kSecondSearchShare * double(l.search));
  // The probe: up to kProbeFailures failures per coordinate, at most a tenth of the budget;
  // too few per coordinate tell nothing.
  l.probe_per_coordinate = std::min<int64_t>(kProbeFailures, budget / 10 / dimension);
  if (l.probe_per_coordinate < kProbeFailures / 2) l.probe_per_coordinate = 0;
  l.probe = l.probe_per_coordinate * dimension;
  l.explore = std::llround(kExploreShare * double(budget));
  const int64_t walks = std::llround(kWalkShare * double(budget));
  l.chains = std::max<int64_t>(kChains, walks / kWalkRounds);
  l.rounds = walks / l.chains;
  l.sample = budget - l.search - l.probe - l.explore - l.chains * l.rounds;
  return l;
}

}  // namespace

std::vector<int64_t> CalcEstimateLayout(int64_t budget, int dimension, double adapt_share) {
  if (budget < kMinEstimateBudget || dimension < 1) {
    throw std::invalid_argument("an estimate's layout needs a budget and coordinates");
  }
  const Layout l = MakeLayout(budget, dimension, adapt_share);
  std::vector<int64_t> sizes;
  const auto add_search = [&](int64_t search) {
    const int64_t batch = DefaultBatch(search);
    for (int64_t done = 0; done < search; done += batch) {
      sizes.push_back(std::min(batch, search - done));
    }
  };
  add_search(l.search - l.second_search);
  if (l.probe > 0) sizes.push_back(l.probe);
  add_search(l.second_search);
  sizes.push_back(l.explore);
  for (int64_t r = 0; r < l.rounds; ++r) sizes.push_back(l.chains);
  sizes.push_back(l.sample);
  return sizes;
}

struct EstimatePlanner::State {
  EstimateOptions options;
  int dimension = 0;
  Layout layout;
  const lang::CompiledProgram* program = nullptr;
  // The first search, then the second, whose records it sees with the first one's failure
  // region (`first_region`: the failures' mean and spread) scored as safe.
  std::unique_ptr<SearchPlanner> search;
  int searches = 0;  // done
  // The first search's last cross-entropy proposal (mean and spread per coordinate).
  std::vector<double> first_mean, first_std;
  std::optional<MixtureProposal> first_region;
  // The causes found: the mean of the first search's failures, and of the second's outside
  // the first one's region.
  std::vector<std::vector<double>> modes;
  std::vector<harness::EpisodeRecord> adaptation;  // every unweighted record, in index order
  // Every weighted generation: its records, the proposal they were drawn from, its phase.
  struct Weighted {
    std::vector<harness::EpisodeRecord> records;
    MixtureProposal drawn_from;
    const char* phase;  // "explore" or "sample"
  };
  std::vector<Weighted> weighted;
  // The searches' failures (the first one's until the second is done).
  std::vector<const harness::EpisodeRecord*> failures;
  MixtureProposal proposal, explore;
  bool final = false;  // `proposal` is the sampling proposal: every later generation draws it
  // The walks: each chain's state, the step per coordinate, the rounds run, the states kept.
  std::vector<std::vector<double>> chains, moves, states;
  std::vector<double> step;
  std::unique_ptr<geometry::Rng> walk_rng;
  int64_t round = 0;
  // The generation Next() planned last.
  Phase phase = Phase::kSearch;
  GenerationPlan plan;
  bool planned = false;
  uint64_t next = 0;  // the first index of the next generation
  int generation = 0;

  void StartSearch(int64_t budget) {
    SearchOptions search;
    search.strategy = Strategy::kCrossEntropy;
    search.budget = budget;
    search.run = options.run;
    this->search = std::make_unique<SearchPlanner>(*program, search);
  }

  // Whether `u` lies in the first search's failure region: within a Mahalanobis distance of
  // the chi-square law's d + 4 sqrt(2 d) of its failures' mean, over the d coordinates failing
  // depends on.
  bool InFirstRegion(const std::vector<double>& u) const {
    if (!first_region) return false;
    double distance = 0;
    int relevant = 0;
    for (size_t j = 0; j < u.size(); ++j) {
      if (proposal.std[j] <= 0) continue;  // one failing does not depend on (the probe)
      distance += std::pow((u[j] - first_region->mean[j]) / first_region->std[j], 2);
      ++relevant;
    }
    return distance < relevant + 4 * std::sqrt(2.0 * relevant);
  }

  // The sampling proposal from `proposal` as it stands (wider, to cover the region, with a
  // wide layer for its edges).
  void Finalise() {
    for (double& std : proposal.std) std *= kSamplingWidening;
    for (std::vector<double>& spread : proposal.centre_std) {
      for (double& std : spread) std *= kSamplingWidening;
    }
    proposal.wide_share = kWideShare;
    proposal.wide_factor = kWideFactor;
    final = true;
  }
};

EstimatePlanner::EstimatePlanner(const lang::CompiledProgram& program,
                                 const EstimateOptions& options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  if (options.budget < kMinEstimateBudget) {
    throw std::invalid_argument(
        fmt::format("a budget of {} episodes is too small to adapt a "
                    "proposal and then sample: give at least {}",
                    options.budget, kMinEstimateBudget));
  }
  s.options = options;
  s.options.on_record = nullptr;
  s.dimension = int(sampling::DescribeCoordinates(program, options.run.sample).size());
  if (s.dimension == 0) throw NothingToSearch("the program draws nothing at random");
  s.layout = MakeLayout(options.budget, s.dimension, options.adapt_share);
  s.program = &program;
  s.adaptation.reserve(size_t(options.budget));  // `failures` points into it
  s.StartSearch(s.layout.search - s.layout.second_search);
  s.proposal.mean.assign(size_t(s.dimension), 0.5);
  s.proposal.std.assign(size_t(s.dimension), 1 / std::sqrt(12.0));
  s.proposal.uniform_share = 1.0;
}

EstimatePlanner::~EstimatePlanner() = default;

bool EstimatePlanner::done() const {
  return int64_t(state_->next) >= state_->options.budget && !state_->planned;
}

bool EstimatePlanner::IsWeighted(const GenerationPlan& plan) { return plan.mode == "mixture"; }

GenerationPlan EstimatePlanner::Next() {
  State& s = *state_;
  if (s.planned || done()) throw std::logic_error("EstimatePlanner::Next out of turn");
  GenerationPlan plan;
  const Layout& l = s.layout;
  const int64_t first = l.search - l.second_search, second_start = first + l.probe;
  const int64_t explore_start = l.search + l.probe, walk_start = explore_start + l.explore;
  const int64_t at = int64_t(s.next);
  if (at < first || (at >= second_start && at < explore_start)) {
    s.phase = Phase::kSearch;
    plan = s.search->Next();
    // The second search's episodes follow the probe's.
    if (at >= second_start) plan.start += uint64_t(second_start);
  } else {
    plan.start = s.next;
    plan.dimension = s.dimension;
    s.phase = at < second_start                       ? Phase::kProbe
              : at < walk_start                       ? Phase::kExplore
              : at < walk_start + l.chains * l.rounds ? Phase::kWalk
                                                      : Phase::kSample;
    plan.count = s.phase == Phase::kProbe     ? l.probe
                 : s.phase == Phase::kExplore ? l.explore
                 : s.phase == Phase::kWalk    ? l.chains
                                              : l.sample;
    // No failure to probe, explore or walk from: those episodes draw the sampling proposal
    // (the probe's, the program's own law: the second search may still find failures).
    if (s.final || (s.phase == Phase::kProbe && s.failures.empty())) s.phase = Phase::kSample;
    MixtureProposal uniform;
    uniform.mean = s.proposal.mean;
    uniform.std = s.proposal.std;
    const MixtureProposal* draw = nullptr;
    if (s.phase == Phase::kProbe) {
      // Each of a few failures run again with one coordinate redrawn uniformly (spread over
      // the failures found: the search's last ones are its deepest).
      plan.mode = "given";
      geometry::Rng rng(s.options.run.seed ^ 0x5EEDFACEULL, s.next);
      const size_t m = size_t(l.probe_per_coordinate), f = s.failures.size();
      for (int j = 0; j < s.dimension; ++j) {
        for (size_t k = 0; k < m; ++k) {
          std::vector<double> u = s.failures[k * f / m]->coordinates;
          u[size_t(j)] = rng.Uniform01();
          plan.centres.push_back(std::move(u));
        }
      }
    } else if (s.phase == Phase::kWalk) {
      // Each chain moves the coordinates failing depends on by a normal step, reflected.
      if (!s.walk_rng)
        s.walk_rng = std::make_unique<geometry::Rng>(s.options.run.seed ^ 0x3A1C5EEDULL, s.next);
      s.moves = s.chains;
      for (std::vector<double>& u : s.moves) {
        for (size_t j = 0; j < u.size(); ++j) {
          if (s.step[j] > 0)
            u[j] = Reflect(u[j] + s.step[j] * geometry::MapNormal(s.walk_rng->Uniform01()));
        }
      }
      plan.mode = "given";
      plan.centres = s.moves;
    } else {
      draw = s.phase == Phase::kExplore ? &s.explore : s.final ? &s.proposal : &uniform;
      plan.mode = "mixture";
      plan.mean = draw->mean;
      plan.std = draw->std;
      plan.centres = draw->centres;
      plan.uniform_share = draw->uniform_share;
      plan.centre_std = draw->centre_std;
      plan.wide_share = draw->wide_share;
      plan.wide_factor = draw->wide_factor;
    }
    plan.strategy = PhaseTag(s.phase);
  }
  plan.generation = s.generation;
  s.plan = plan;
  s.planned = true;
  return plan;
}

void EstimatePlanner::Add(std::vector<harness::EpisodeRecord> records) {
  State& s = *state_;
  if (!s.planned) throw std::logic_error("EstimatePlanner::Add without Next");
  if (int64_t(records.size()) != s.plan.count) {
    throw std::invalid_argument("a generation's records are not the ones it planned");
  }
  s.planned = false;
  s.next += records.size();
  ++s.generation;
  const Layout& l = s.layout;
  switch (s.phase) {
    case Phase::kSearch: {
      // The search planner reads what a campaign's replay gives it (index, outcome, score,
      // coordinates); the second search sees the first one's failure region as safe.
      std::vector<harness::EpisodeRecord> seen(records.size());
      for (size_t i = 0; i < records.size(); ++i) {
        seen[i].index = records[i].index;
        seen[i].result = records[i].result;
        seen[i].coordinates = records[i].coordinates;
        if (s.searches == 1 && s.InFirstRegion(seen[i].coordinates)) {
          seen[i].result.outcome = "success";
          seen[i].result.score = 1e9;
        }
      }
      s.search->Add(std::move(seen));
      for (harness::EpisodeRecord& r : records) s.adaptation.push_back(std::move(r));
      if (!s.search->done()) return;
      if (++s.searches == 1) {
        const SearchSummary first = s.search->TakeSummary();
        s.first_mean = first.proposal_mean;
        s.first_std = first.proposal_std;
        s.failures = Failures(s.adaptation);
        if (!s.failures.empty()) {
          MixtureProposal region = s.proposal;
          FitToFailures(s.failures, nullptr, region);
          s.first_region = region;
          s.modes.push_back(region.mean);
        }
        s.StartSearch(l.second_search);
        return;
      }
      // The second search's failures outside the first one's region: another cause.
      std::vector<const harness::EpisodeRecord*> second;
      for (const harness::EpisodeRecord* r : Failures(s.adaptation)) {
        if (r->index >= uint64_t(l.search - l.second_search + l.probe) &&
            !s.InFirstRegion(r->coordinates)) {
          second.push_back(r);
        }
      }
      if (!second.empty()) {
        MixtureProposal region = s.proposal;
        FitToFailures(second, nullptr, region);
        s.modes.push_back(region.mean);
      }
      // The sampling's starting point: the first search's last proposal, on the coordinates
      // failing depends on (the probe's), fitted to every failure of both searches when there
      // are enough (the optimal proposal is the law restricted to the failures).
      if (!s.first_mean.empty()) {
        s.proposal.mean = s.first_mean;
        for (size_t j = 0; j < s.first_std.size(); ++j) {
          if (s.proposal.std[j] > 0) s.proposal.std[j] = s.first_std[j];
        }
      }
      s.failures = Failures(s.adaptation);
      if (int64_t(s.failures.size()) >= kMinFailuresToFit) {
        FitToFailures(s.failures, nullptr, s.proposal);
      }
      s.proposal.uniform_share = s.options.uniform_share;
      // Nothing to aim at: the program's own law, whose episodes bound the failure rate best.
      if (s.failures.empty()) s.proposal.uniform_share = 1;
      if (int64_t(s.failures.size()) < kMinFailuresToFit) s.Finalise();
      // The search's failures crowd around its best point: explore around them widely (around
      // each cause, at the width of one cause's region, when the second search found another).
      s.explore = s.proposal;
      if (s.modes.size() > 1) {
        s.explore.std = CalcPooledSpread(s.failures, s.modes, s.explore.std);
        s.explore.centres = s.modes;
      }
      for (double& std : s.explore.std) std = std > 0 ? std::max(4 * std, 0.1) : 0;
      return;
    }
    case Phase::kProbe: {
      // A coordinate whose redraw keeps half of the failures failing or more stays uniform
      // (std 0), in every proposal after, and in the first search's failure region.
      const size_t m = size_t(l.probe_per_coordinate);
      for (int j = 0; j < s.dimension; ++j) {
        size_t still = 0;
        for (size_t k = 0; k < m; ++k) {
          still += records[size_t(j) * m + k].result.outcome != "success";
        }
        if (2 * still >= m) s.proposal.std[size_t(j)] = 0;
      }
      for (harness::EpisodeRecord& r : records) s.adaptation.push_back(std::move(r));
      return;
    }
    case Phase::kExplore: {
      // The failures found there, with their weights, reach the whole failure region: fit
      // them, place kernels, and walk from the kernels' centres.
      const std::vector<const harness::EpisodeRecord*> found = Failures(records);
      if (int64_t(found.size()) >= kMinFailuresToFit) {
        FitToFailures(found, &s.explore, s.proposal);
        PlaceKernels(found, s.explore, s.proposal);
        // The chains start at centres spread over all of them (over every cause).
        const size_t centres = s.proposal.centres.size();
        for (int64_t k = 0; k < l.chains; ++k) {
          s.chains.push_back(s.proposal.centres[size_t(k) * centres / size_t(l.chains)]);
        }
        s.step = s.proposal.std;
        for (double& std : s.step) std = std > 0 ? 2 * std : 0;
        if (l.rounds == 0) s.Finalise();
      } else {
        s.proposal = s.explore;
        s.Finalise();
      }
      s.weighted.push_back({std::move(records), DrawnFrom(s.plan), "explore"});
      return;
    }
    case Phase::kWalk: {
      // A move is kept when the episode there fails at that very point (Metropolis for the
      // law restricted to the failures); the step adapts toward a third of the moves kept.
      int kept = 0;
      for (size_t k = 0; k < s.chains.size(); ++k) {
        if (records[k].result.outcome != "success" && records[k].coordinates == s.moves[k]) {
          s.chains[k] = s.moves[k];
          ++kept;
        }
        if (s.round >= l.rounds / 3) s.states.push_back(s.chains[k]);  // after a burn-in
      }
      const double rate = double(kept) / double(s.chains.size());
      for (double& step : s.step) step *= rate < 0.2 ? 0.7 : rate > 0.45 ? 1.4 : 1.0;
      for (harness::EpisodeRecord& r : records) s.adaptation.push_back(std::move(r));
      if (++s.round == l.rounds) {
        if (s.states.size() >= size_t(kMinFailuresToFit)) PlaceKernelsAt(s.states, s.proposal);
        s.Finalise();
      }
      return;
    }
    case Phase::kSample:
      s.weighted.push_back({std::move(records), DrawnFrom(s.plan), "sample"});
      return;
  }
}

EstimateSummary EstimatePlanner::Finish() {
  State& s = *state_;
  if (!done()) throw std::logic_error("EstimatePlanner::Finish before the last generation");
  EstimateSummary summary;
  summary.proposal = s.proposal;
  for (const harness::EpisodeRecord& r : s.adaptation) {
    summary.scored = summary.scored || r.result.score.has_value();
  }
  summary.adapt_episodes = int64_t(s.adaptation.size());
  // The weighted generations as draws of their deterministic mixture (the balance heuristic):
  // an episode's weight is 1 / (sum_g n_g q_g / sum_g n_g) at its point. The estimate is
  // self-normalised when an attempt was rejected (a scene's point is not its first attempt's):
  // the accepted set may then be smaller than the cube, and the weights' mean is not 1.
  double n = 0;
  bool rejected = false;
  for (const auto& [records, drawn_from, phase] : s.weighted) {
    n += double(records.size());
    const MixturePoints points(drawn_from);
    std::vector<double> first(size_t(s.dimension));
    for (const harness::EpisodeRecord& r : records) {
      points.Point(s.options.run.seed, r.index, 0, first.data());
      rejected = rejected || r.coordinates != first;
    }
  }
  summary.records = std::move(s.adaptation);
  std::vector<WeightedOutcome> weighted;
  for (auto& [records, drawn_from, phase] : s.weighted) {
    for (harness::EpisodeRecord& r : records) {
      const double* u = r.coordinates.data();
      double density = 0;
      for (const auto& other : s.weighted) {
        density += double(other.records.size()) * other.drawn_from.CalcDensity(u);
      }
      const WeightedOutcome w{r.result.outcome,
                              n / density,
                              s.proposal.uniform_share,
                              rejected,
                              r.result.score.value_or(NAN),
                              s.proposal.CalcKernelShare(u)};
      weighted.push_back(w);
      r.search = {{"strategy", "importance"},   {"phase", phase},
                  {"weight", w.weight},         {"uniform_share", w.uniform_share},
                  {"normalised", w.normalised}, {"kernel_share", w.kernel_share}};
      summary.records.push_back(std::move(r));
    }
  }
  s.weighted.clear();
  // Every failure kind of every phase gets a row, a bound at least (the adaptation's too).
  std::set<std::string> seen;
  for (const harness::EpisodeRecord& r : summary.records) seen.insert(r.result.outcome);
  summary.estimate = CalcEstimate(weighted, std::vector<std::string>(seen.begin(), seen.end()));
  return summary;
}

EstimateSummary RunEstimate(const lang::CompiledProgram& program,
                            const harness::ControllerFactory& factory,
                            const EstimateOptions& options) {
  EstimatePlanner planner(program, options);
  harness::RunOptions run = options.run;
  int threads = 1;
  while (!planner.done()) {
    const GenerationPlan plan = planner.Next();
    // The adaptation's records as they come; the weighted ones once their weights are known.
    run.on_record = EstimatePlanner::IsWeighted(plan) ? nullptr : options.on_record;
    harness::RunSummary ran = RunGeneration(program, factory, plan, run, plan.start, plan.count);
    threads = ran.threads;
    planner.Add(std::move(ran.records));
  }
  EstimateSummary summary = planner.Finish();
  summary.threads = threads;
  if (options.on_record) {
    for (size_t i = size_t(summary.adapt_episodes); i < summary.records.size(); ++i) {
      options.on_record(summary.records[i]);
    }
  }
  return summary;
}

}  // namespace prs::search
