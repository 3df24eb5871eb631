// The report of `prs stats`: acceptance rate, rejections by reason and by culprit (located in
// the source), and time per scene, as a text table or as JSON ("prs-stats/1").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "lang/source.h"
#include "sampling/batch.h"
#include "sampling/gibbs.h"
#include "sampling/partial_rejection.h"

namespace prs::cli {

/// What one `prs stats` run measured.
struct SamplingStats {
  std::string file;
  uint64_t seed = 0;
  int threads = 1;
  bool naive = false;
  std::optional<sampling::GibbsPlan> gibbs;  // with --sampler gibbs
  std::optional<sampling::PartialRejectionPlan> partial_rejection;  // --sampler partial-rejection
  sampling::BatchSummary summary;
  int64_t max_attempts_per_scene = 0;  // the most attempts any one scene took
  double seconds = 0;                  // wall-clock time of the sampling
};

/// The report as aligned text tables, ending with a newline.
std::string FormatStatsTable(const SamplingStats& stats, const lang::SourceManager& sources);

/// The report as one JSON object (pretty-printed), ending with a newline.
std::string FormatStatsJson(const SamplingStats& stats, const lang::SourceManager& sources);

}  // namespace prs::cli
