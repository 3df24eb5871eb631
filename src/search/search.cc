// The search loop: generation after generation, a proposal over scene coordinates (i.i.d.,
// cross-entropy or annealing), one batch of episodes at its points on all threads, and an
// update from the batch's outcomes and scores.
#include "search/search.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/random.h"
#include "search/design.h"
#include "search/like.h"
#include "search/mixture.h"

namespace prs::search {
namespace {

constexpr uint64_t kAcceptSalt = 0x3C6EF372FE94F82BULL;

// Cross-entropy method (Rubinstein & Kroese), elitist: the elite is the best fraction of
// everything evaluated so far (as many as one generation holds), so a good point found early
// is not forgotten, and the proposal is centred on the best point so far with the elite's
// spread; smoothing of the update, the smallest standard deviation (in coordinate units), and
// the share of uniform points kept in every generation so that the proposal never loses sight
// of the whole space. Tuned on the planted failures, seeds 1..20, and checked on 21..40
// (docs/benchmarks.md).
constexpr double kEliteFraction = 0.2;
constexpr double kSmoothing = 0.95;
constexpr double kUniformShare = 0.05;
// Simulated annealing: the first step (coordinate units), the decay of step and temperature
// per generation, the smallest step, and the first temperature as a share of the spread of
// the first generation's badness (low: mostly downhill, as the planted failures favour).
constexpr double kFirstStep = 0.2;
constexpr double kDecay = 0.9;
constexpr double kMinStep = 0.01;
constexpr double kFirstTemperature = 0.01;

// Where a generation's points come from.
class ProposalPoints : public sampling::AttemptPoints {
 public:
  enum class Mode { kUniform, kSobol, kGaussian, kChain, kGiven, kMixture };

  explicit ProposalPoints(const GenerationPlan& plan)
      : centres(plan.centres),
        step(plan.step),
        mode_(ParseMode(plan.mode)),
        dimension_(plan.dimension),
        first_index_(plan.start) {
    if (mode_ == Mode::kSobol) design_ = std::make_unique<Design>(DesignKind::kSobol, dimension_);
    if (mode_ == Mode::kGaussian) {
      gaussian_ = std::make_unique<GaussianPoints>(plan.mean, plan.std, kUniformShare);
    }
    if (mode_ == Mode::kMixture) {
      if (int(plan.mean.size()) != dimension_ || int(plan.std.size()) != dimension_ ||
          !(plan.uniform_share > 0 && plan.uniform_share <= 1)) {
        throw std::invalid_argument("a mixture's plan has sizes or a uniform share out of range");
      }
      for (const auto& centre : plan.centres) {
        if (int(centre.size()) != dimension_) throw std::invalid_argument("a centre's size");
      }
      if (!plan.centre_std.empty() && plan.centre_std.size() != plan.centres.size()) {
        throw std::invalid_argument("a mixture's plan has a spread per centre for some only");
      }
      for (const auto& spread : plan.centre_std) {
        if (int(spread.size()) != dimension_) throw std::invalid_argument("a spread's size");
      }
      if (!(plan.wide_share >= 0 && plan.wide_share < 1 && plan.wide_factor > 0)) {
        throw std::invalid_argument("a mixture's wide layer is out of range");
      }
      mixture_ = std::make_unique<MixturePoints>(
          MixtureProposal{plan.mean, plan.std, plan.uniform_share, plan.centres, plan.centre_std,
                          plan.wide_share, plan.wide_factor});
    }
    if ((mode_ == Mode::kChain || mode_ == Mode::kGiven) &&
        static_cast<int64_t>(centres.size()) < plan.count) {
      throw std::invalid_argument("a generation plan has fewer centres than episodes");
    }
  }

  static Mode ParseMode(const std::string& name) {
    if (name == "sobol") return Mode::kSobol;
    if (name == "gaussian") return Mode::kGaussian;
    if (name == "chain") return Mode::kChain;
    if (name == "given") return Mode::kGiven;
    if (name == "uniform") return Mode::kUniform;
    if (name == "mixture") return Mode::kMixture;
    throw std::invalid_argument("unknown proposal mode '" + name + "'");
  }

  int dimension() const override { return dimension_; }

  bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const override {
    // Every attempt of a mixture's scene at its points, so that 1 / density is its weight.
    if (mode_ == Mode::kMixture) return mixture_->Point(seed, index, attempt, u);
    if (attempt >= kMaxProposalAttempts) return false;
    geometry::Rng rng = MakeProposalRng(seed, index, attempt);
    switch (mode_) {
      case Mode::kSobol:
        if (attempt == 0) {
          design_->CalcPoint(seed, index, u);
          return true;
        }
        break;
      case Mode::kGaussian:
        return gaussian_->Point(seed, index, attempt, u);
      case Mode::kChain: {
        const std::vector<double>& centre = centres[index - first_index_];
        for (int j = 0; j < dimension_; ++j) {
          double x = centre[j] + step * geometry::MapNormal(rng.Uniform01());
          x = std::fmod(std::abs(x), 2.0);  // reflect at 0 and 1
          if (x >= 1) x = 2 - x;
          u[j] = std::min(x, 1.0 - 0x1.0p-53);
        }
        return true;
      }
      case Mode::kGiven:
        if (attempt == 0) {
          const std::vector<double>& given = centres[index - first_index_];
          std::copy(given.begin(), given.end(), u);
          return true;
        }
        break;  // the given point was rejected: i.i.d. points after it
      case Mode::kUniform:
      case Mode::kMixture:
        break;
    }
    for (int j = 0; j < dimension_; ++j) u[j] = rng.Uniform01();
    return true;
  }

  std::vector<std::vector<double>> centres;  // kChain, kGiven: per episode of the generation
  double step = kFirstStep;                  // kChain

 private:
  Mode mode_;
  int dimension_;
  uint64_t first_index_;
  std::unique_ptr<Design> design_;
  std::unique_ptr<GaussianPoints> gaussian_;
  std::unique_ptr<MixturePoints> mixture_;
};

bool HasScore(const std::vector<harness::EpisodeRecord>& records) {
  return std::any_of(records.begin(), records.end(),
                     [](const harness::EpisodeRecord& r) { return r.result.score.has_value(); });
}

// The best `batch.size()` records of everything evaluated (earlier and this generation).
std::vector<harness::EpisodeRecord> BestSoFar(const std::vector<harness::EpisodeRecord>& earlier,
                                              const std::vector<harness::EpisodeRecord>& batch) {
  std::vector<const harness::EpisodeRecord*> all;
  for (const auto& r : earlier) all.push_back(&r);
  for (const auto& r : batch) all.push_back(&r);
  const size_t keep = std::min(all.size(), batch.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end(),
                    [](auto* a, auto* b) {
                      const double ba = CalcBadness(*a), bb = CalcBadness(*b);
                      return ba < bb || (ba == bb && a->index < b->index);
                    });
  std::vector<harness::EpisodeRecord> best;
  best.reserve(keep);
  for (size_t k = 0; k < keep; ++k) best.push_back(*all[k]);
  return best;
}

// The cross-entropy update: the best point and the spread of the elite, smoothed.
void UpdateCrossEntropy(const std::vector<harness::EpisodeRecord>& batch, int dimension,
                        std::vector<double>* mean, std::vector<double>* std) {
  std::vector<const harness::EpisodeRecord*> ranked;
  for (const auto& r : batch) {
    if (static_cast<int>(r.coordinates.size()) == dimension) ranked.push_back(&r);
  }
  const bool scored = HasScore(batch);
  const auto failed = [](const harness::EpisodeRecord* r) {
    return r->result.outcome != "success";
  };
  const int64_t failures = std::count_if(ranked.begin(), ranked.end(), failed);
  // Outcomes alone say nothing about where to go until something failed.
  if (!scored && failures == 0) return;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](auto* a, auto* b) { return CalcBadness(*a) < CalcBadness(*b); });
  size_t elite = static_cast<size_t>(std::ceil(kEliteFraction * static_cast<double>(batch.size())));
  if (!scored) elite = static_cast<size_t>(failures);
  elite = std::clamp<size_t>(elite, 1, ranked.size());
  for (int j = 0; j < dimension; ++j) {
    double m = 0;
    for (size_t k = 0; k < elite; ++k) m += ranked[k]->coordinates[j];
    m /= static_cast<double>(elite);
    double v = 0;
    for (size_t k = 0; k < elite; ++k) v += std::pow(ranked[k]->coordinates[j] - m, 2);
    const double s = std::sqrt(v / static_cast<double>(elite));
    (*mean)[j] = kSmoothing * ranked[0]->coordinates[j] + (1 - kSmoothing) * (*mean)[j];
    (*std)[j] = std::max(kMinProposalStd, kSmoothing * s + (1 - kSmoothing) * (*std)[j]);
  }
}

// One Metropolis step per chain: keep the proposal when it is no better with probability
// exp(-(worse by) / temperature).
void UpdateChains(const std::vector<harness::EpisodeRecord>& batch, uint64_t seed, int generation,
                  double temperature, std::vector<std::vector<double>>* centres,
                  std::vector<double>* badness) {
  for (size_t c = 0; c < batch.size() && c < centres->size(); ++c) {
    const harness::EpisodeRecord& r = batch[c];
    if (r.coordinates.size() != (*centres)[c].size()) continue;  // drawn from the stream
    const double b = CalcBadness(r);
    geometry::Rng rng(seed ^ kAcceptSalt, (static_cast<uint64_t>(generation) << 32) + c);
    const bool accept = generation == 0 || b <= (*badness)[c] ||
                        rng.Uniform01() < std::exp(-(b - (*badness)[c]) / temperature);
    if (accept) {
      (*centres)[c] = r.coordinates;
      (*badness)[c] = b;
    }
  }
}

// A proposer's points: `count` of them, each of `d` numbers in [0, 1).
void CheckProposal(const std::vector<std::vector<double>>& points, int64_t count, int d) {
  if (static_cast<int64_t>(points.size()) != count) {
    throw std::invalid_argument("the proposer gave " + std::to_string(points.size()) +
                                " points for a generation of " + std::to_string(count));
  }
  for (const auto& u : points) {
    if (static_cast<int>(u.size()) != d ||
        !std::all_of(u.begin(), u.end(), [](double x) { return x >= 0 && x < 1; })) {
      throw std::invalid_argument("the proposer gave a point that is not " + std::to_string(d) +
                                  " numbers of [0, 1)");
    }
  }
}

// Simulated annealing's chains: their current points and badness, the temperature and step.
struct AnnealState {
  std::vector<std::vector<double>> centres;
  std::vector<double> badness;
  double temperature = 1;
  double step = kFirstStep;

  void Update(const std::vector<harness::EpisodeRecord>& batch, uint64_t seed, int generation,
              int64_t slots, int dimension) {
    if (generation == 0) {
      centres.assign(slots, std::vector<double>(dimension, 0.5));
      badness.assign(slots, INFINITY);
      // The first temperature: the spread of the first generation's badness.
      double sum = 0, sum2 = 0;
      for (const auto& r : batch) {
        sum += CalcBadness(r);
        sum2 += CalcBadness(r) * CalcBadness(r);
      }
      const double n = static_cast<double>(batch.size());
      const double spread = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
      temperature = kFirstTemperature * (spread > 0 ? spread : 1);
    } else {
      temperature *= kDecay;
      step = std::max(kMinStep, step * kDecay);
    }
    UpdateChains(batch, seed, generation, temperature, &centres, &badness);
  }
};

}  // namespace

double CalcBadness(const harness::EpisodeRecord& record) {
  const bool failed = record.result.outcome != "success";
  if (record.result.score) return *record.result.score - (failed ? 1e9 : 0);
  return failed ? -1 : 1;
}

const char* StrategyName(Strategy strategy) {
  switch (strategy) {
    case Strategy::kRandom:
      return "random";
    case Strategy::kCrossEntropy:
      return "ce";
    case Strategy::kAnneal:
      return "anneal";
    case Strategy::kExternal:
      return "external";
  }
  return "random";
}

std::vector<std::string> StrategyNames() { return {"random", "ce", "anneal"}; }

bool ParseStrategy(const std::string& name, Strategy* strategy) {
  for (Strategy s : {Strategy::kRandom, Strategy::kCrossEntropy, Strategy::kAnneal}) {
    if (name == StrategyName(s)) {
      *strategy = s;
      return true;
    }
  }
  return false;
}

int64_t DefaultBatch(int64_t budget) {
  return std::min(budget, std::clamp<int64_t>(budget / 50, 20, 200));
}

struct SearchPlanner::State {
  SearchOptions options;
  int64_t batch = 0;
  int dimension = 0;
  std::vector<double> mean, std;  // the cross-entropy proposal
  AnnealState anneal;
  SearchSummary summary;
  int64_t done = 0;      // episodes planned and added
  bool planned = false;  // Next() was called and Add() not yet
};

SearchPlanner::SearchPlanner(const lang::CompiledProgram& program, const SearchOptions& options)
    : state_(std::make_unique<State>()) {
  if (options.budget < 1) {
    throw std::invalid_argument("the search budget must be at least 1 episode, got " +
                                std::to_string(options.budget));
  }
  const int64_t batch = options.batch == 0 ? DefaultBatch(options.budget) : options.batch;
  if (batch < 1) {
    throw std::invalid_argument("the generation size must be at least 1, got " +
                                std::to_string(batch));
  }
  if (options.strategy == Strategy::kExternal && !options.propose) {
    throw std::invalid_argument("the external strategy needs a proposer");
  }
  State& s = *state_;
  s.options = options;
  s.batch = batch;
  s.summary.batch = batch;
  s.summary.coordinates = sampling::DescribeCoordinates(program, options.run.sample);
  s.dimension = static_cast<int>(s.summary.coordinates.size());
  if (s.dimension == 0) {
    throw NothingToSearch(
        "this program draws nothing at random: every scene is the same, so "
        "there is nothing to search");
  }
  s.mean.assign(s.dimension, 0.5);  // wide: about uniform at first
  s.std.assign(s.dimension, 1.0);
}

SearchPlanner::~SearchPlanner() = default;

bool SearchPlanner::done() const { return state_->done >= state_->options.budget; }

GenerationPlan SearchPlanner::Next() {
  State& s = *state_;
  const Strategy strategy = s.options.strategy;
  GenerationPlan plan;
  plan.generation = s.summary.generations;
  plan.start = static_cast<uint64_t>(s.done);
  plan.count = std::min(s.batch, s.options.budget - s.done);
  plan.dimension = s.dimension;
  plan.strategy =
      strategy == Strategy::kExternal ? s.options.external_name : StrategyName(strategy);
  plan.mode = "uniform";
  if (strategy == Strategy::kExternal) {
    plan.mode = "given";
    plan.centres = s.options.propose(s.summary.records, plan.count, s.dimension, plan.generation);
    CheckProposal(plan.centres, plan.count, s.dimension);
  } else if (strategy != Strategy::kRandom) {
    plan.mode = plan.generation == 0                  ? "sobol"
                : strategy == Strategy::kCrossEntropy ? "gaussian"
                                                      : "chain";
  }
  if (plan.mode == "gaussian") {
    plan.mean = s.mean;
    plan.std = s.std;
  }
  if (plan.mode == "chain") {
    plan.centres = s.anneal.centres;
    plan.centres.resize(plan.count, std::vector<double>(s.dimension, 0.5));
    plan.step = s.anneal.step;
  }
  s.planned = true;
  return plan;
}

void SearchPlanner::Add(std::vector<harness::EpisodeRecord> records) {
  State& s = *state_;
  if (!s.planned) throw std::logic_error("SearchPlanner::Add without Next");
  s.planned = false;
  for (const harness::EpisodeRecord& record : records) {
    if (record.result.outcome != "success") {
      ++s.summary.failures;
      if (s.summary.first_failure < 0) {
        s.summary.first_failure = static_cast<int64_t>(record.index) + 1;
      }
    }
  }
  const int generation = s.summary.generations;
  if (s.options.strategy == Strategy::kCrossEntropy) {
    UpdateCrossEntropy(BestSoFar(s.summary.records, records), s.dimension, &s.mean, &s.std);
  } else if (s.options.strategy == Strategy::kAnneal) {
    s.anneal.Update(records, s.options.run.seed, generation, s.batch, s.dimension);
  }
  s.done += static_cast<int64_t>(records.size());
  for (auto& record : records) s.summary.records.push_back(std::move(record));
  s.summary.generations = generation + 1;
}

const SearchSummary& SearchPlanner::summary() const { return state_->summary; }

SearchSummary SearchPlanner::TakeSummary() {
  SearchSummary summary = std::move(state_->summary);
  if (state_->options.strategy == Strategy::kCrossEntropy) {
    summary.proposal_mean = state_->mean;
    summary.proposal_std = state_->std;
  }
  return summary;
}

harness::RunSummary RunGeneration(const lang::CompiledProgram& program,
                                  const harness::ControllerFactory& factory,
                                  const GenerationPlan& plan, harness::RunOptions run,
                                  uint64_t first, int64_t count) {
  if (first < plan.start || count < 0 ||
      first + static_cast<uint64_t>(count) > plan.start + static_cast<uint64_t>(plan.count)) {
    throw std::invalid_argument("episodes outside the generation's plan");
  }
  const ProposalPoints points(plan);
  run.sample.points = &points;
  run.spec_hash = CalcSpecHash(program);
  run.start = first;
  run.count = count;
  const nlohmann::json tag = {{"strategy", plan.strategy}, {"generation", plan.generation}};
  const auto on_record = run.on_record;
  run.on_record = [&](const harness::EpisodeRecord& record) {
    if (!on_record) return;
    harness::EpisodeRecord tagged = record;
    tagged.search = tag;
    on_record(tagged);
  };
  harness::RunSummary ran = harness::RunEpisodes(program, factory, run);
  for (harness::EpisodeRecord& record : ran.records) record.search = tag;
  return ran;
}

SearchSummary RunSearch(const lang::CompiledProgram& program,
                        const harness::ControllerFactory& factory, const SearchOptions& options) {
  SearchPlanner planner(program, options);
  harness::RunOptions run = options.run;
  run.on_record = options.on_record;
  int threads = 1;
  while (!planner.done()) {
    const GenerationPlan plan = planner.Next();
    harness::RunSummary ran = RunGeneration(program, factory, plan, run, plan.start, plan.count);
    threads = ran.threads;
    planner.Add(std::move(ran.records));
  }
  SearchSummary summary = planner.TakeSummary();
  summary.threads = threads;
  return summary;
}

nlohmann::json PlanToJson(const GenerationPlan& plan) {
  nlohmann::json json = {
      {"generation", plan.generation}, {"start", plan.start}, {"count", plan.count},
      {"dimension", plan.dimension},   {"mode", plan.mode},   {"strategy", plan.strategy}};
  if (!plan.mean.empty()) json["mean"] = plan.mean;
  if (!plan.std.empty()) json["std"] = plan.std;
  if (!plan.centres.empty()) json["centres"] = plan.centres;
  if (plan.mode == "chain") json["step"] = plan.step;
  if (plan.mode == "mixture") json["uniform_share"] = plan.uniform_share;
  if (!plan.centre_std.empty()) json["centre_std"] = plan.centre_std;
  if (plan.wide_share > 0) {
    json["wide_share"] = plan.wide_share;
    json["wide_factor"] = plan.wide_factor;
  }
  return json;
}

GenerationPlan PlanFromJson(const nlohmann::json& json) {
  try {
    GenerationPlan plan;
    plan.generation = json.at("generation").get<int>();
    plan.start = json.at("start").get<uint64_t>();
    plan.count = json.at("count").get<int64_t>();
    plan.dimension = json.at("dimension").get<int>();
    plan.mode = json.at("mode").get<std::string>();
    plan.strategy = json.at("strategy").get<std::string>();
    plan.mean = json.value("mean", std::vector<double>{});
    plan.std = json.value("std", std::vector<double>{});
    plan.centres = json.value("centres", std::vector<std::vector<double>>{});
    plan.step = json.value("step", 0.0);
    plan.uniform_share = json.value("uniform_share", 1.0);
    plan.centre_std = json.value("centre_std", std::vector<std::vector<double>>{});
    plan.wide_share = json.value("wide_share", 0.0);
    plan.wide_factor = json.value("wide_factor", 1.0);
    ProposalPoints check(plan);  // throws for an unknown mode or missing centres
    if (plan.count < 0 || plan.dimension < 1 ||
        (plan.mode == "gaussian" && (static_cast<int>(plan.mean.size()) != plan.dimension ||
                                     static_cast<int>(plan.std.size()) != plan.dimension))) {
      throw std::invalid_argument("inconsistent sizes");
    }
    return plan;
  } catch (const std::exception& error) {
    throw std::runtime_error(std::string("not a generation plan: ") + error.what());
  }
}

bool ParseRecordForSearch(const std::string& line, harness::EpisodeRecord* record) {
  const auto json = nlohmann::json::parse(line, nullptr, false);
  if (!json.is_object()) return false;
  try {
    record->index = json.at("index").get<uint64_t>();
    record->result.outcome = json.at("outcome").get<std::string>();
    record->result.score.reset();
    if (json.contains("score")) record->result.score = json.at("score").get<double>();
    record->coordinates = json.value("coordinates", std::vector<double>{});
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

}  // namespace prs::search
