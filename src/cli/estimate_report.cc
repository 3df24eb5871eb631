// What `prs estimate` and an estimate campaign's merge print (estimate_report.h).
#include "cli/estimate_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/text_table.h"

namespace prs::cli {
namespace {

// Below this many failing weighted episodes an interval rests on a variance estimated from
// those few, and the command says so.
constexpr int64_t kFewFailingEpisodes = 10;

std::string FormatPercent(double p) { return fmt::format("{:#.3g} %", 100 * p); }

}  // namespace

// One row per failure kind; i.i.d. records need no "as tight" column (they are the i.i.d.
// episodes).
std::string FormatEstimateTable(const search::Estimate& e) {
  std::vector<std::string> header = {"outcome", "p", "95% interval", "failed"};
  if (!e.iid) header.push_back("i.i.d. episodes for as tight");
  TextTable table(header, e.iid ? "lrrr" : "lrrrr");
  for (const search::OutcomeEstimate& o : e.outcomes) {
    std::vector<std::string> row = {o.outcome, FormatPercent(o.p),
                                    FormatPercent(o.ci_low) + " - " + FormatPercent(o.ci_high),
                                    std::to_string(o.episodes)};
    if (!e.iid) row.push_back(fmt::format("{:.0f}", o.iid_episodes));
    table.AddRow(row);
  }
  return table.Format(0);
}

// The --json object: {"episodes", "ess", "reliable", "estimates": {...}, "upper_bound_95"}.
std::string FormatEstimateJson(const search::Estimate& e) {
  nlohmann::ordered_json out;
  out["episodes"] = e.episodes;
  out["ess"] = e.ess;
  out["reliable"] = e.reliable;
  if (!std::isnan(e.uncovered_share)) out["uncovered_share"] = e.uncovered_share;
  if (!e.reliable) out["unreliable_because"] = search::DescribeUnreliable(e);
  out["estimates"] = nlohmann::ordered_json::object();
  if (e.reliable) {
    for (const search::OutcomeEstimate& o : e.outcomes) {
      out["estimates"][o.outcome] = {{"p", o.p},
                                     {"ci95", {o.ci_low, o.ci_high}},
                                     {"ess", e.ess},
                                     {"failing_episodes", o.episodes},
                                     {"iid_episodes_for_same_precision", o.iid_episodes}};
    }
    if (e.outcomes.empty()) out["upper_bound_95"] = e.upper_bound;
  }
  return out.dump() + "\n";
}

int PrintEstimate(const search::Estimate& e, bool json, bool quiet) {
  if (json) {
    std::cout << FormatEstimateJson(e) << std::flush;
  } else if (e.reliable) {
    if (!e.outcomes.empty()) std::cout << FormatEstimateTable(e) << std::flush;
  }
  if (!e.reliable) {
    PrintWarning(search::DescribeUnreliable(e));
  } else if (e.outcomes.empty() && !quiet) {
    PrintNote(
        fmt::format("no failure in {}: the probability of failing is below {} (a 95 % "
                    "upper bound; a failure rarer than that may still exist)",
                    FormatCount(e.episodes, e.iid ? "i.i.d. episode" : "weighted episode"),
                    FormatPercent(e.upper_bound)));
  } else if (!quiet) {
    const int64_t fewest =
        std::min_element(e.outcomes.begin(), e.outcomes.end(), [](const auto& a, const auto& b) {
          return a.episodes < b.episodes;
        })->episodes;
    if (!e.iid && fewest < kFewFailingEpisodes) {
      PrintNote(fmt::format(
          "a failure seen in fewer than {} weighted episodes has an approximate interval: its "
          "variance is estimated from those few; raise --budget to firm it up",
          kFewFailingEpisodes));
    }
  }
  return kExitSuccess;
}

}  // namespace prs::cli
