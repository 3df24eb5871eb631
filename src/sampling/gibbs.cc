// --sampler gibbs: the chain's engine (a start by sequential placement, systematic-scan sweeps
// of exact block redraws), the pilot that picks burn-in and thinning from measured
// autocorrelation, and the per-thread chain cache behind SceneSampler::Sample.
#include "sampling/gibbs.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

namespace prs::sampling {
namespace {

// Chains and the pilot read streams of their own, apart from the scenes' (seed, index).
constexpr uint64_t kPointStream = uint64_t{1} << 63;
constexpr uint64_t kProgramStream = uint64_t{3} << 62;
constexpr uint64_t kPilotSeed = 0x6769626273;  // "gibbs"; the pilot is the same for every seed
constexpr uint64_t kPilotChain = (uint64_t{1} << 40) - 1;

bool IsSameStream(geometry::Rng a, geometry::Rng b) { return a.NextU64() == b.NextU64(); }

// `span`: what in the program makes it unsupported, where that is known.
[[noreturn]] void ThrowUnsupported(const std::string& why, std::optional<lang::SourceSpan> span) {
  lang::Diagnostic d;
  d.id = "gibbs-unsupported";
  d.has_span = span.has_value();
  if (span) d.span = *span;
  d.message = "--sampler gibbs cannot sample this program: " + why;
  d.notes.push_back(
      {{},
       false,
       "use the default sampler (whole-scene rejection), which is exact for any program"});
  throw lang::ScenarioError(std::move(d));
}

// Whose coordinate this is: the object in "Cube#3.position[0]" or "tr_1.yaw"; empty for a
// draw of no object ("Range at bin.prs:4:38").
std::string OwnerOf(const std::string& name) {
  const size_t dot = name.find('.');
  if (dot == std::string::npos || dot == 0) return "";
  const std::string owner = name.substr(0, dot);
  return owner.find(' ') == std::string::npos ? owner : "";
}

// Whether `text` names `object` as a whole word ("Cube#3" in "Cube#3 and Cube#7", not in
// "Cube#30").
bool Names(const std::string& text, const std::string& object) {
  for (size_t at = text.find(object); at != std::string::npos; at = text.find(object, at + 1)) {
    const size_t end = at + object.size();
    const auto is_name_char = [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '#';
    };
    const bool starts = at == 0 || !is_name_char(text[at - 1]);
    const bool ends = end == text.size() || !is_name_char(text[end]);
    if (starts && ends) return true;
  }
  return false;
}

}  // namespace

// One chain: a point u of the accepted set, the scene it makes, and the moves.
class ChainEngine {
 public:
  ChainEngine(const lang::CompiledProgram& program, const SampleOptions& options,
              lang::RunCache* cache, uint64_t seed, uint64_t chain)
      : program_(program),
        options_(options),
        points_(seed, kPointStream | chain),
        stream_(seed, kProgramStream | chain) {
    run_ = options.run;
    run_.cache = cache;
    run_.explained = &explained_;
    run_.reuse_objects = options.gibbs && options.gibbs->settings().reuse_objects;
  }

  // Sequential placement: runs the program at a random point and, while it is rejected,
  // redraws the block of the last object its rejection names (else a random block), so each
  // object in turn finds room beside those before it. Not the program's law: burn-in follows.
  void Start() {
    std::vector<lang::CoordinateInfo> log;
    while (runs_ < options_.max_attempts) {
      log.clear();
      std::optional<lang::Rejection> rejection;
      const bool accepted = Run(&log, &rejection);
      if (log.size() >= lang::kMaxLoggedCoordinates) {
        ThrowUnsupported("it draws more than " + std::to_string(lang::kMaxLoggedCoordinates) +
                             " numbers a scene",
                         log.back().span);
      }
      if (log.size() > u_.size() || (accepted && log.size() != u_.size())) {
        // The run got further than ever, drawing past u from the stream: give the new
        // coordinates values of their own and run again at the whole point.
        while (u_.size() < log.size()) u_.push_back(points_.Uniform01());
        u_.resize(log.size());
        MakeBlocks(log);
        continue;
      }
      if (accepted) return;
      if (u_.empty() || rejection->certain) {
        ThrowUnsupported("every run is rejected the same way, before anything is drawn: " +
                             std::string(lang::RejectionKindName(rejection->kind)) + ": " +
                             rejection->culprit,
                         rejection->span);
      }
      int block = -1;
      for (size_t b = 0; b < owners_.size(); ++b) {
        if (!owners_[b].empty() && Names(rejection->culprit, owners_[b])) {
          block = static_cast<int>(b);
        }
      }
      // An object with no room beside those before it (or a rejection naming none): redraw
      // any block, so that the start cannot stay stuck.
      failures_in_a_row_ = block == last_block_ ? failures_in_a_row_ + 1 : 0;
      last_block_ = block;
      if (block < 0 || failures_in_a_row_ >= kMaxFailuresInARow) {
        block = static_cast<int>(points_.UniformInt(0, static_cast<int64_t>(blocks_.size()) - 1));
        failures_in_a_row_ = 0;
      }
      Redraw(block);
    }
    if (rejections_.total == 0) {
      ThrowUnsupported("its number of draws keeps growing", std::nullopt);
    }
    try {
      ThrowSamplingFailure(rejections_, runs_, 0, lang::RejectionKind::kUnstable);
    } catch (const lang::ScenarioError& error) {
      // The same counts and culprit, said of the chain's start.
      lang::Diagnostic d = error.diagnostic();
      const std::string generic = "no valid scene after " + std::to_string(runs_) + " attempts";
      if (d.message.rfind(generic, 0) == 0) {
        d.message = "--sampler gibbs found no starting scene for its chain in " +
                    std::to_string(runs_) + " program runs (each object redrawn until it fits " +
                    "beside those before it)" + d.message.substr(generic.size());
      }
      throw lang::ScenarioError(std::move(d));
    }
  }

  // One systematic scan: every block in turn from its exact conditional (uniform on its cube,
  // retried until accepted; after max_tries the old values stay, which keeps the law too).
  void Sweep(int64_t max_tries) {
    std::vector<double> saved;
    for (size_t b = 0; b < blocks_.size(); ++b) {
      saved.clear();
      for (int j : blocks_[b]) saved.push_back(u_[j]);
      bool moved = false;
      for (int64_t t = 0; t < max_tries && !moved; ++t) {
        Redraw(static_cast<int>(b));
        std::optional<lang::Rejection> rejection;
        moved = Run(nullptr, &rejection);
      }
      // A rejected run leaves scene_ as it was: restoring u_ is enough.
      if (!moved) {
        for (size_t k = 0; k < saved.size(); ++k) u_[blocks_[b][k]] = saved[k];
      }
    }
  }

  const lang::Scene& scene() const { return scene_; }
  const std::vector<double>& point() const { return u_; }
  int blocks() const { return static_cast<int>(blocks_.size()); }
  int64_t runs() const { return runs_; }
  RejectionCounts& rejections() { return rejections_; }

 private:
  // Runs the program at u_ (the stream after it: the chain's own, the same every run). True
  // and scene_ set when accepted (by the program and SampleOptions::accept); else *rejection.
  bool Run(std::vector<lang::CoordinateInfo>* log, std::optional<lang::Rejection>* rejection) {
    ++runs_;
    if (options_.live) options_.live->attempts.fetch_add(1, std::memory_order_relaxed);
    geometry::Rng rng = stream_;
    run_.coordinates = {u_.data(), static_cast<int>(u_.size()), log};
    lang::AttemptResult attempt = lang::RunAttempt(program_, rng, run_);
    if (!log && !IsSameStream(stream_, rng)) ThrowDrewMore();
    if (auto* scene = std::get_if<lang::Scene>(&attempt)) {
      std::optional<lang::Rejection> failed =
          options_.accept ? options_.accept(*scene) : std::nullopt;
      if (!failed) {
        scene_ = std::move(*scene);
        return true;
      }
      attempt = std::move(*failed);
    }
    if (options_.live) options_.live->rejections.fetch_add(1, std::memory_order_relaxed);
    *rejection = std::get<lang::Rejection>(std::move(attempt));
    rejections_.Add(**rejection);
    explained_.emplace((*rejection)->kind, (*rejection)->culprit);
    return false;
  }

  void Redraw(int block) {
    redrawn_ = block;
    for (int j : blocks_[block]) u_[j] = points_.Uniform01();
  }

  // A run read the stream past u: the block just redrawn changed how many numbers a run draws
  // (a random count of objects, a loop's), so the refusal points at that block's draw.
  [[noreturn]] void ThrowDrewMore() const {
    std::string what = "a run drew more numbers than its " + std::to_string(u_.size()) +
                       " scene coordinates";
    std::optional<lang::SourceSpan> span;
    if (redrawn_ >= 0) {
      const int first = blocks_[static_cast<size_t>(redrawn_)].front();
      span = coordinates_[static_cast<size_t>(first)].span;
      what += " when " + coordinates_[static_cast<size_t>(first)].name +
              " was redrawn: it decides how many objects or draws a run makes";
    } else {
      what += " (a random number of objects or draws, or a region sampled by retries)";
    }
    ThrowUnsupported(what, span);
  }

  // One block per object (its position, orientation and property draws together), and one per
  // draw of no object.
  void MakeBlocks(const std::vector<lang::CoordinateInfo>& log) {
    blocks_.clear();
    owners_.clear();
    coordinates_ = log;
    std::map<std::string, size_t> block_of;
    for (size_t j = 0; j < log.size(); ++j) {
      const std::string owner = OwnerOf(log[j].name);
      const auto found = owner.empty() ? block_of.end() : block_of.find(owner);
      if (found != block_of.end()) {
        blocks_[found->second].push_back(static_cast<int>(j));
        continue;
      }
      if (!owner.empty()) block_of[owner] = blocks_.size();
      blocks_.push_back({static_cast<int>(j)});
      owners_.push_back(owner);
    }
  }

  const lang::CompiledProgram& program_;
  const SampleOptions& options_;
  lang::RunOptions run_;
  std::set<std::pair<lang::RejectionKind, std::string>> explained_;
  geometry::Rng points_;        // the chain's draws of coordinates
  const geometry::Rng stream_;  // the program's stream for draws past u (none once started)
  std::vector<double> u_;
  std::vector<std::vector<int>> blocks_;
  std::vector<std::string> owners_;
  std::vector<lang::CoordinateInfo> coordinates_;  // what each coordinate is, and its draw
  int redrawn_ = -1;                               // the block Redraw drew last
  lang::Scene scene_;
  int64_t runs_ = 0;
  RejectionCounts rejections_;
  // The start's redraws of one block in a row.
  static constexpr int kMaxFailuresInARow = 20;
  int last_block_ = -1;
  int failures_in_a_row_ = 0;
};

double GibbsPlan::CalcEffectiveScenes(int64_t scenes) const {
  return static_cast<double>(scenes) / std::max(1.0, tau_scenes);
}

std::vector<double> CalcAutocorrelation(const std::vector<double>& series, size_t max_lag) {
  const size_t n = series.size();
  if (n < 4) return {};
  double mean = 0;
  for (double x : series) mean += x;
  mean /= static_cast<double>(n);
  double c0 = 0;
  for (double x : series) c0 += (x - mean) * (x - mean);
  // A constant series (up to rounding: a height computed from a varying position) has none.
  const double tiny = 1e-9 * (1 + std::fabs(mean));
  if (!(c0 > static_cast<double>(n) * tiny * tiny)) return {};
  std::vector<double> rho = {1.0};
  for (size_t m = 1; m <= max_lag && m < n / 2; ++m) {
    double c = 0;
    for (size_t i = 0; i + m < n; ++i) c += (series[i] - mean) * (series[i + m] - mean);
    rho.push_back(c / c0);
  }
  return rho;
}

double CalcAutocorrelationTime(const std::vector<double>& series) {
  return CalcWindowedTime(CalcAutocorrelation(series, series.size() / 2));
}

double CalcWindowedTime(const std::vector<double>& rho) {
  double tau = 1;
  for (size_t m = 1; m < rho.size(); ++m) {
    tau += 2 * rho[m];
    if (static_cast<double>(m) >= 5 * tau) break;  // Sokal's window
  }
  return std::max(1.0, tau);
}

const GibbsPlan& GibbsRequest::Plan(const lang::CompiledProgram& program,
                                    const SampleOptions& options) {
  std::lock_guard lock(mutex_);
  if (plan_) return *plan_;
  auto cache = lang::MakeRunCache();
  ChainEngine pilot(program, options, cache.get(), kPilotSeed, kPilotChain);
  pilot.Start();
  // A sweep costs about one run per block, and averaging over more statistics needs fewer
  // sweeps: kPilotBlockSweeps block redraws in all, within [kMinPilotSweeps, pilot_sweeps].
  constexpr int64_t kPilotBlockSweeps = 4000, kMinPilotSweeps = 50;
  const int64_t sweeps = std::clamp<int64_t>(kPilotBlockSweeps / std::max(1, pilot.blocks()),
                                             std::min(kMinPilotSweeps, settings_.pilot_sweeps),
                                             settings_.pilot_sweeps);
  const int64_t warm = std::max<int64_t>(10, sweeps / 4);
  for (int64_t s = 0; s < warm; ++s) pilot.Sweep(settings_.max_block_tries);
  // Statistics per sweep: every object's position and every coordinate.
  std::map<std::string, std::vector<double>> series;
  for (int64_t s = 0; s < sweeps; ++s) {
    pilot.Sweep(settings_.max_block_tries);
    const lang::Scene& scene = pilot.scene();
    for (size_t i = 0; i < scene.objects.size(); ++i) {
      const lang::SceneObject& o = scene.objects[i];
      if (o.fixed) continue;
      const std::string name = o.DisplayName(static_cast<int>(i));
      for (int axis = 0; axis < 3; ++axis) {
        series[name + "." + "xyz"[axis]].push_back(o.p_WO[axis]);
      }
    }
    for (size_t j = 0; j < pilot.point().size(); ++j) {
      series["u[" + std::to_string(j) + "]"].push_back(pilot.point()[j]);
    }
  }
  GibbsPlan plan;
  plan.dimension = static_cast<int>(pilot.point().size());
  plan.blocks = pilot.blocks();
  plan.pilot_sweeps = sweeps;
  plan.pilot_runs = pilot.runs();
  plan.scenes_per_chain = std::max<int64_t>(1, settings_.scenes_per_chain);
  // The chain's autocorrelation time from the autocorrelation function averaged over every
  // statistic that varies (one statistic's estimate from a short pilot is noisy, and the
  // largest of hundreds of them mostly measures the noise); the slowest statistic is kept too.
  const size_t max_lag = static_cast<size_t>(sweeps / 4);
  std::vector<double> mean_rho;
  int varying = 0;
  for (const auto& [name, values] : series) {
    const std::vector<double> rho = CalcAutocorrelation(values, max_lag);
    if (rho.empty()) continue;
    ++varying;
    if (mean_rho.size() < rho.size()) mean_rho.resize(rho.size(), 0.0);
    for (size_t k = 0; k < rho.size(); ++k) mean_rho[k] += rho[k];
    const double tau = CalcWindowedTime(rho);
    if (tau > plan.tau_worst_sweeps || plan.tau_statistic.empty()) {
      plan.tau_worst_sweeps = tau;
      plan.tau_statistic = name;
    }
  }
  for (double& r : mean_rho) r /= std::max(1, varying);
  plan.statistics = varying;
  plan.tau_sweeps = CalcWindowedTime(mean_rho);
  plan.thin_sweeps = settings_.thin_sweeps >= 1
                         ? settings_.thin_sweeps
                         : std::max<int64_t>(1, static_cast<int64_t>(std::floor(plan.tau_sweeps)));
  plan.burn_in_sweeps =
      settings_.burn_in_sweeps >= 0
          ? settings_.burn_in_sweeps
          : std::max<int64_t>(20, static_cast<int64_t>(std::ceil(10 * plan.tau_sweeps)));
  // Between scenes, the worst statistic's correlation as if it decayed geometrically (the
  // autocorrelation time of an AR(1) series is (1 + rho) / (1 - rho)).
  const double rho = (plan.tau_sweeps - 1) / (plan.tau_sweeps + 1);
  const double rho_scenes = std::pow(rho, static_cast<double>(plan.thin_sweeps));
  plan.tau_scenes = (1 + rho_scenes) / (1 - rho_scenes);
  plan_ = plan;
  return *plan_;
}

std::optional<GibbsPlan> GibbsRequest::plan() const {
  std::lock_guard lock(mutex_);
  return plan_;
}

struct GibbsChain::State {
  uint64_t seed = 0, chain = 0;
  int64_t position = -1;  // the scene of the chain the engine is at
  std::unique_ptr<ChainEngine> engine;
  std::unique_ptr<lang::RunCache, lang::RunCacheDeleter> cache = lang::MakeRunCache();
};

GibbsChain::GibbsChain(const lang::CompiledProgram& program, const SampleOptions& options)
    : program_(program), options_(options), state_(std::make_unique<State>()) {}

GibbsChain::~GibbsChain() = default;

SampledScene GibbsChain::Sample(uint64_t seed, uint64_t index) {
  const GibbsPlan& plan = options_.gibbs->Plan(program_, options_);
  const GibbsSettings& settings = options_.gibbs->settings();
  const auto per_chain = static_cast<uint64_t>(plan.scenes_per_chain);
  const uint64_t chain = index / per_chain;
  const auto position = static_cast<int64_t>(index % per_chain);
  State& s = *state_;
  // A scene's attempts and rejections are those of its own stretch of the chain (the start
  // and burn-in for a chain's first scene), whichever stretches this thread ran before.
  int64_t runs_before = 0;
  RejectionCounts rejections_before;
  const auto advance = [&](int64_t sweeps) {
    runs_before = s.engine->runs();
    rejections_before = s.engine->rejections();
    for (int64_t k = 0; k < sweeps; ++k) s.engine->Sweep(settings.max_block_tries);
  };
  if (!s.engine || s.seed != seed || s.chain != chain || s.position > position) {
    s.engine = std::make_unique<ChainEngine>(program_, options_, s.cache.get(), seed, chain);
    s.seed = seed;
    s.chain = chain;
    s.engine->Start();
    advance(plan.burn_in_sweeps);
    runs_before = 0;
    rejections_before = {};
    s.position = 0;
  }
  while (s.position < position) {
    advance(plan.thin_sweeps);
    ++s.position;
  }
  SampledScene result;
  result.seed = seed;
  result.index = index;
  result.scene = s.engine->scene();
  result.coordinates = s.engine->point();
  result.attempts = s.engine->runs() - runs_before;
  result.rejections = s.engine->rejections();
  // Subtract the counts of earlier stretches.
  for (const auto& [key, n] : rejections_before.by_culprit) result.rejections.by_culprit[key] -= n;
  for (const auto& [kind, n] : rejections_before.by_kind) result.rejections.by_kind[kind] -= n;
  result.rejections.total -= rejections_before.total;
  std::erase_if(result.rejections.by_culprit, [](const auto& e) { return e.second == 0; });
  std::erase_if(result.rejections.by_kind, [](const auto& e) { return e.second == 0; });
  return result;
}

}  // namespace prs::sampling
