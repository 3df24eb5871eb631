// `--sampler gibbs` (docs/sampling.md, "Clutter: --sampler gibbs"): a Markov chain over the
// scene coordinates whose stationary law is the program's own law, for scenes that whole-scene
// rejection cannot reach (twenty objects that must not overlap in a bin).
//
// Every scene is the program run at a point u of the unit cube, and the program's law is the
// image of the uniform law on the set A of points whose run is accepted. The chain keeps a
// point of A and, one object at a time, redraws that object's coordinates (its block) from
// their exact conditional: uniform on the block's cube, retried until the run is accepted,
// which is uniform on the block's slice of A. Each move therefore leaves the law invariant; the
// scenes are exact only in the limit and are correlated, which the sampler measures and says.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sampling/sampler.h"

namespace prs::sampling {

/// What the chain's schedule was chosen from: a pilot chain run once per program and options
/// (seed-independent, so the schedule is the same for every seed, thread count and shard).
struct GibbsPlan {
  int dimension = 0;         // coordinates of a scene
  int blocks = 0;            // objects (and free draws) redrawn one at a time
  int64_t pilot_sweeps = 0;  // sweeps the pilot measured
  int64_t pilot_runs = 0;    // program runs the pilot made, start included
  /// The integrated autocorrelation time, in sweeps, of the autocorrelation function averaged
  /// over the `statistics` that vary (every object's position and every coordinate).
  double tau_sweeps = 1;
  int statistics = 0;
  double tau_worst_sweeps = 1;  // the slowest single statistic's (a noisier estimate)
  std::string tau_statistic;    // which statistic that was ("Cube#3.x")
  int64_t burn_in_sweeps = 0;   // sweeps from the start before a chain's first scene
  int64_t thin_sweeps = 1;      // sweeps between a chain's scenes
  double tau_scenes = 1;        // the autocorrelation time between consecutive scenes
  int64_t scenes_per_chain = 64;

  /// The effective sample size of `scenes` consecutive scenes: scenes / tau_scenes.
  double CalcEffectiveScenes(int64_t scenes) const;
};

struct GibbsSettings {
  int64_t scenes_per_chain = 64;
  /// Negative: from the pilot (10 autocorrelation times, at least 20). 0: none, so a chain's
  /// first scene is its start, a sequential placement (not the program's law: for tests).
  int64_t burn_in_sweeps = -1;
  int64_t thin_sweeps = -1;    // negative: from the pilot (one autocorrelation time rounded down)
  int64_t pilot_sweeps = 200;  // at most; fewer for many blocks (4,000 block redraws, at least 50)
  /// Tries to redraw one block before the move keeps the old values (a move that keeps them
  /// still leaves the law invariant).
  int64_t max_block_tries = 1000;
  /// Runs copy the objects whose numbers did not change from the run before
  /// (lang::RunOptions::reuse_objects). False: every run makes every object; the same scenes,
  /// slower (for tests).
  bool reuse_objects = true;
};

/// The request for Gibbs sampling, shared by every sampler of a run: settings in, and the plan
/// worked out once, by whichever sampler needs it first.
class GibbsRequest {
 public:
  explicit GibbsRequest(GibbsSettings settings = {}) : settings_(settings) {}

  const GibbsSettings& settings() const { return settings_; }
  /// The plan for `program`, worked out on first use (thread-safe; the same for every call).
  /// Throws lang::ScenarioError as sampling does.
  const GibbsPlan& Plan(const lang::CompiledProgram& program, const SampleOptions& options);
  /// The plan when one was worked out, else nullopt.
  std::optional<GibbsPlan> plan() const;

 private:
  GibbsSettings settings_;
  mutable std::mutex mutex_;
  std::optional<GibbsPlan> plan_;
};

/// One chain at a time, kept between calls so that consecutive scenes of a chain cost one
/// thinning interval each. Scene `index` of `seed` is scene index % scenes_per_chain of chain
/// (seed, index / scenes_per_chain): the same for any thread count or order of calls.
class GibbsChain {
 public:
  GibbsChain(const lang::CompiledProgram& program, const SampleOptions& options);
  ~GibbsChain();
  /// Throws lang::ScenarioError: no starting scene within options.max_attempts program runs,
  /// or a program that draws other than its scene coordinates ("gibbs-unsupported").
  SampledScene Sample(uint64_t seed, uint64_t index);

 private:
  struct State;
  const lang::CompiledProgram& program_;
  const SampleOptions& options_;
  std::unique_ptr<State> state_;
};

/// The autocorrelation function of a series at lags 0..max_lag (below half its length); empty
/// for a series that does not vary.
std::vector<double> CalcAutocorrelation(const std::vector<double>& series, size_t max_lag);

/// The integrated autocorrelation time 1 + 2 sum rho(k) of an autocorrelation function, summed
/// over Sokal's self-consistent window (the smallest M with M >= 5 tau(M)); at least 1.
double CalcWindowedTime(const std::vector<double>& rho);

/// CalcWindowedTime of a series' autocorrelation function; 1 for a series without
/// correlation or that does not vary.
double CalcAutocorrelationTime(const std::vector<double>& series);

}  // namespace prs::sampling
