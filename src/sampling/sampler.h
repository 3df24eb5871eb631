// The sampler: scene `index` of seed `seed` as a pure function of the compiled program, by
// restarting whole attempts (spec §7) on a stream seeded by (seed, index), with rejections
// counted per reason.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "lang/lang.h"

namespace prs::sampling {

struct SampleOptions {
  lang::RunOptions run;
  int64_t max_attempts = 10'000;
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
};

/// Samples scene `index` of `seed`. Throws lang::ScenarioError for program errors, and for a
/// sampling failure after `max_attempts` (naming the most frequent culprit and the counts).
SampledScene SampleScene(const lang::CompiledProgram& program, uint64_t seed, uint64_t index,
                         const SampleOptions& options = {});

}  // namespace prs::sampling
