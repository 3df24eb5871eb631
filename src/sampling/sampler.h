// The sampler: scene `index` of seed `seed` as a pure function of the compiled program, by
// restarting whole attempts (spec §7) on a stream seeded by (seed, index), with rejections
// counted per reason.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang/lang.h"

namespace prs::sampling {

/// Attempts and rejections counted as they happen, across threads (for progress displays
/// while one scene is hard to find). Never changes a result.
struct LiveCounts {
  std::atomic<int64_t> attempts{0};
  std::atomic<int64_t> rejections{0};
};

/// The points of the unit cube at which a sampler's attempts run (scene coordinates,
/// docs/search.md): a space-filling design, or a search's proposals. Must be thread-safe and
/// a pure function of its arguments, so scenes stay the same for any thread count.
class AttemptPoints {
 public:
  virtual ~AttemptPoints() = default;
  /// The number of coordinates of each point (DescribeCoordinates(...).size()).
  virtual int dimension() const = 0;
  /// Fills u[0..dimension()) with numbers of [0, 1) for attempt `attempt` (0 for the first)
  /// of scene `index` of `seed` and returns true; or returns false, and that attempt reads the
  /// Rng stream alone, as without points.
  virtual bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const = 0;
};

/// A test a scene must pass after the program's own, handed down by the stage that owns it (a
/// physics check: sim/stability.h, sim/settle.h): the rejection, or nullopt to accept. A
/// failed test rejects the attempt like any other reason, so the accepted scenes are the
/// program's scenes conditioned on passing it. A test may also change the scene it accepts
/// (--settle moves the free bodies to where they come to rest). Must be thread-safe and a pure
/// function of the scene, so that scenes stay the same for any thread count.
using SceneTest = std::function<std::optional<lang::Rejection>(lang::Scene&)>;

class GibbsRequest;  // sampling/gibbs.h
class GibbsChain;
class PartialRejectionRequest;  // sampling/partial_rejection.h
class PartialRejectionSampler;

struct SampleOptions {
  lang::RunOptions run;
  int64_t max_attempts = 10'000;
  LiveCounts* live = nullptr;  // optional; must outlive the samplers
  /// Optional; must outlive the samplers. Without it every attempt reads the stream.
  const AttemptPoints* points = nullptr;
  /// False: every attempt starts from nothing, no work kept between scenes (lang::RunCache).
  /// Slower, and the same scenes: for tests of the caches.
  bool use_run_cache = true;
  /// Optional: run on every scene an attempt makes (e.g. --stable).
  SceneTest accept;
  /// Optional (--sampler gibbs): scenes from a Markov chain over the scene coordinates instead
  /// of whole-scene rejection (sampling/gibbs.h); shared by the samplers of a run, which work
  /// out its plan once. Not with `points`.
  std::shared_ptr<GibbsRequest> gibbs;
  /// Optional (--sampler partial-rejection): exact scenes of clutter by partial rejection
  /// sampling (sampling/partial_rejection.h); shared like `gibbs`, and not with it or `points`.
  std::shared_ptr<PartialRejectionRequest> partial_rejection;
};

/// Rejections of one scene (or many), keyed by (kind, culprit).
struct RejectionCounts {
  std::map<std::pair<lang::RejectionKind, std::string>, int64_t> by_culprit;
  std::map<lang::RejectionKind, int64_t> by_kind;
  int64_t total = 0;
  /// The first rejection of each (kind, culprit), for locating the culprit in messages.
  std::map<std::pair<lang::RejectionKind, std::string>, lang::Rejection> examples;

  void Add(const lang::Rejection& rejection);
  void Merge(const RejectionCounts& other);
};

struct SampledScene {
  uint64_t seed = 0;
  uint64_t index = 0;
  int64_t attempts = 0;
  RejectionCounts rejections;
  lang::Scene scene;
  /// The scene coordinates of the accepted attempt when it ran at a point (AttemptPoints),
  /// else empty.
  std::vector<double> coordinates;
};

/// Samples scenes of one program. Holds per-thread caches (regions that are the same in every
/// scene), so give each thread its own SceneSampler; the program may be shared. The result of
/// Sample(seed, index) does not depend on the caches, on earlier calls, or on the thread.
class SceneSampler {
 public:
  explicit SceneSampler(const lang::CompiledProgram& program, SampleOptions options = {});
  ~SceneSampler();
  SceneSampler(const SceneSampler&) = delete;
  SceneSampler& operator=(const SceneSampler&) = delete;

  /// Scene `index` of `seed`. Throws lang::ScenarioError for program errors, and for a
  /// sampling failure after `max_attempts` (naming the most frequent culprit and the counts).
  SampledScene Sample(uint64_t seed, uint64_t index);

  const lang::CompiledProgram& program() const { return program_; }
  const SampleOptions& options() const { return options_; }

 private:
  const lang::CompiledProgram& program_;
  SampleOptions options_;
  std::unique_ptr<lang::RunCache, lang::RunCacheDeleter> cache_;
  std::unique_ptr<GibbsChain> gibbs_;  // with options_.gibbs
  std::unique_ptr<PartialRejectionSampler> partial_;  // with options_.partial_rejection
};

/// Throws "sampling-failed" located at the most frequent culprit of `counts`, with counts per
/// reason; when `tested` scenes met the program's constraints and the scene test (of kind
/// `tested_kind`) rejected every one, says that instead. For the samplers.
[[noreturn]] void ThrowSamplingFailure(const RejectionCounts& counts, int64_t attempts,
                                       int64_t tested, lang::RejectionKind tested_kind);

/// The scene coordinates of the program (docs/search.md): one entry per number the longest of
/// `probe_attempts` attempts (scene 0 of seed 0 and its retries, on the stream) drew, at most
/// kMaxCoordinates. Programs whose draws vary (random loops, resampling) may draw more in
/// other attempts; those draws read the stream. Throws lang::ScenarioError for program errors.
inline constexpr int kMaxCoordinates = static_cast<int>(lang::kMaxLoggedCoordinates);
std::vector<lang::CoordinateInfo> DescribeCoordinates(const lang::CompiledProgram& program,
                                                      const SampleOptions& options = {},
                                                      int probe_attempts = 64);

/// Samples scene `index` of `seed` with a fresh SceneSampler (convenient, but without the
/// caches' speed-up across calls).
SampledScene SampleScene(const lang::CompiledProgram& program, uint64_t seed, uint64_t index,
                         const SampleOptions& options = {});

}  // namespace prs::sampling
