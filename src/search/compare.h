// Paired comparison (docs/search.md, "Before and after a change"): two runs of a controller on
// the same scenes (prs test, prs search, or a replay), before and after a change, matched scene
// by scene by (seed, index). Which scenes the change fixed and which it broke, the outcome
// counts side by side, and McNemar's exact test of "the change made a difference" on the
// scenes whose pass/fail changed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "search/report.h"

namespace prs::search {

/// One scene of both runs: the records (indexes into the before and after runs).
struct PairedScene {
  size_t before = 0, after = 0;
};

struct PairedComparison {
  std::string before_path, after_path;
  std::vector<ReportRecord> before, after;
  std::vector<PairedScene> scenes;  // every scene, by (seed, index)
  std::vector<PairedScene> fixed;   // failed before, succeeds after
  std::vector<PairedScene> broke;   // succeeded before, fails after
  std::vector<PairedScene> changed_failure;  // fails in both, another outcome after
  int64_t both_succeed = 0, both_fail = 0;
  /// Every outcome seen, "success" first, then by count before and after, then by name.
  std::vector<std::string> outcomes;
  /// McNemar's exact two-sided p-value for fixed against broke (CalcMcNemarExactP).
  double mcnemar_p = 1;
};

/// The exact two-sided McNemar test of `fixed` against `broke` discordant pairs: under "the
/// change made no difference" each discordant scene is fixed or broke with probability 1/2,
/// so p = min(1, 2·P[Binomial(fixed + broke, 1/2) ≤ min(fixed, broke)]). 1 when there are no
/// discordant scenes.
double CalcMcNemarExactP(int64_t fixed, int64_t broke);

/// Matches the runs scene by scene. Throws std::runtime_error, naming the files and the first
/// scene concerned, when a record has no seed, a scene appears twice in a run, a scene is in
/// one run only, or a scene is not the same in both (its program fingerprint, scene
/// coordinates or recorded scene features differ).
PairedComparison ComparePairedRuns(std::vector<ReportRecord> before, const std::string& before_path,
                                   std::vector<ReportRecord> after, const std::string& after_path);

/// The comparison as Markdown: the outcome table side by side, the test and what it means, and
/// the fixed and broken scenes with their details and regenerate commands.
std::string FormatComparisonMarkdown(const PairedComparison& comparison);

/// The comparison as one JSON object (docs/search.md gives its fields), without a newline.
std::string FormatComparisonJson(const PairedComparison& comparison);

}  // namespace prs::search
