// `--sampler partial-rejection` (docs/sampling.md, "Exact clutter"): exact scenes of
// programs whose random objects are clutter — objects of creation sites that are functions of
// their own draws (lang/own_draws.cc), coupled only by not overlapping, beside fixed objects —
// by partial rejection sampling of a hard-core point process (Guo and Jerrum) and keeping
// the draws with the program's numbers of objects.
//
// The objects of one site are the points of a Poisson process: Poisson(λ) candidates, each the
// site's object made alone from fresh numbers (a probe run: the fixed objects and this one),
// kept when that run is accepted. While two kept objects overlap, the objects of every
// overlapping pair are removed and the process is drawn again on the set of objects that would
// overlap one of them — every candidate of a fresh Poisson(λ) draw kept only when it does —
// which leaves the law of the process conditioned on no overlap (the hard-core process)
// exactly. A draw with exactly as many objects of each site as the program makes, its objects
// given to the site's creations in random order, is the program's law conditioned on
// everything but its requirements; the program run at those numbers then accepts or rejects
// the scene, which makes it exact for the requirements too.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "sampling/sampler.h"

namespace prs::sampling {

/// One creation site whose objects are clutter: where its objects are made in a run, and the
/// intensity its Poisson process is drawn at.
struct ClutterSite {
  std::string name;           // "Cube at bin.prs:6:5"
  lang::SourceSpan span;      // its first object's creation
  std::vector<int> ordinals;  // its objects' creation ordinals in a run (lang::RunOptions)
  int coordinates = 0;        // numbers one object draws
  int probe_index = 0;        // where a probe run's scene holds the object
  /// The creations a probe run leaves out (lang::RunOptions::skip_objects): every other
  /// site's and all but this site's first.
  std::vector<bool> probe_skips;
  /// The fixed objects made after the site's first creation: a probe run ends once its object
  /// is made, so the sampler checks it against these itself.
  std::vector<lang::SceneObject> later_fixed;
  double intensity = 0;  // λ: expected candidates of one Poisson draw
};

/// What the sampler worked out once per program and options (seed-independent): the sites,
/// and the intensities chosen by a pilot so that draws often hold the program's numbers.
struct PartialRejectionPlan {
  std::vector<ClutterSite> sites;
  int dimension = 0;            // scene coordinates of a run
  int64_t pilot_draws = 0;      // hard-core draws the pilot made
  double mean_rounds = 0;       // rounds of redrawing a draw took, on average
  double mean_probes = 0;       // probe runs a draw took, on average
  double count_acceptance = 0;  // fraction of the pilot's last draws with the right counts
};

struct PartialRejectionSettings {
  /// Rounds of redrawing one hard-core draw may take before the sampler gives up with an
  /// error (the objects are too dense for partial rejection; never a restart, which would
  /// bias the law).
  int64_t max_rounds = 10'000;
  int pilot_iterations = 5;       // intensity updates of the pilot
  int pilot_draws_per_step = 40;  // hard-core draws per update
};

/// Shared by the samplers of a run: settings in, the plan worked out once.
class PartialRejectionRequest {
 public:
  explicit PartialRejectionRequest(PartialRejectionSettings settings = {}) : settings_(settings) {}

  const PartialRejectionSettings& settings() const { return settings_; }
  /// The plan for `program`, worked out on first use (thread-safe). Throws lang::ScenarioError
  /// ("partial-rejection-unsupported") for a program outside the sampler's reach.
  const PartialRejectionPlan& Plan(const lang::CompiledProgram& program,
                                   const SampleOptions& options);
  std::optional<PartialRejectionPlan> plan() const;

 private:
  PartialRejectionSettings settings_;
  mutable std::mutex mutex_;
  std::optional<PartialRejectionPlan> plan_;
};

/// One thread's sampler. Scene `index` of `seed` reads streams of its own (seed, index), so it
/// is the same for any thread count or order of calls.
class PartialRejectionSampler {
 public:
  PartialRejectionSampler(const lang::CompiledProgram& program, const SampleOptions& options);
  ~PartialRejectionSampler();
  /// Throws lang::ScenarioError: an unsupported program, a draw past its rounds, or no scene
  /// within options.max_attempts draws.
  SampledScene Sample(uint64_t seed, uint64_t index);

 private:
  const lang::CompiledProgram& program_;
  const SampleOptions& options_;
  std::unique_ptr<lang::RunCache, lang::RunCacheDeleter> cache_;
};

/// A Poisson(mean) count from `rng` (exact: products of uniforms, in pieces of mean at most
/// 64). For the sampler; tested on its own.
int64_t DrawPoisson(geometry::Rng& rng, double mean);

}  // namespace prs::sampling
