// Tables and sentences of `prs search` and `prs check --coordinates`.
#include "cli/search_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "cli/common.h"
#include "cli/text_table.h"

namespace prs::cli {

std::string FormatGenerationTable(const search::SearchSummary& summary) {
  TextTable table({"generation", "episodes", "failures", "lowest score"}, "rrrr");
  size_t at = 0;
  for (int g = 0; g < summary.generations; ++g) {
    int64_t episodes = 0, failures = 0;
    double lowest = INFINITY;
    for (; at < summary.records.size(); ++at) {
      const harness::EpisodeRecord& r = summary.records[at];
      if (r.search.value("generation", -1) != g) break;
      ++episodes;
      failures += r.result.outcome != "success";
      if (r.result.score) lowest = std::min(lowest, *r.result.score);
    }
    table.AddRow({std::to_string(g), std::to_string(episodes), std::to_string(failures),
                  std::isfinite(lowest) ? fmt::format("{:.4g}", lowest) : "-"});
  }
  return table.Format(0);
}

std::string FormatSearchVerdict(const search::SearchSummary& summary, search::Strategy strategy) {
  const int64_t episodes = static_cast<int64_t>(summary.records.size());
  std::string text =
      fmt::format("{} found {} in {}", search::StrategyName(strategy),
                  FormatCount(summary.failures, "failure"), FormatCount(episodes, "episode"));
  if (episodes > 0) {
    text += fmt::format(" ({:.1f}%)", 100.0 * static_cast<double>(summary.failures) /
                                          static_cast<double>(episodes));
  }
  if (summary.first_failure > 0) {
    text += fmt::format("; the first at episode {}", summary.first_failure);
  }
  return text;
}

std::string FormatBatchUseNote(int64_t batch, int threads) {
  if (threads <= 1 || batch <= 0) return "";
  const int64_t waves = (batch + threads - 1) / threads;
  const int64_t slots = waves * threads;
  const double busy = static_cast<double>(batch) / static_cast<double>(slots);
  if (busy >= 0.9) return "";
  return fmt::format(
      "generations of {} run on {} threads in {} waves, the last of {}: the threads are busy "
      "about {:.0f}% of the time; --batch {} keeps them all busy (the records depend on the "
      "batch, not on the thread count)",
      batch, threads, waves, FormatCount(batch - (waves - 1) * threads, "episode"), 100 * busy,
      slots);
}

std::string FormatCoordinateTable(const std::vector<lang::CoordinateInfo>& coordinates,
                                  const lang::SourceManager& sources) {
  TextTable table({"#", "coordinate", "draw", "source"}, "rlll");
  for (size_t i = 0; i < coordinates.size(); ++i) {
    const lang::CoordinateInfo& c = coordinates[i];
    const lang::LineColumn where = sources.CalcLineColumn(c.span.file, c.span.begin);
    table.AddRow({std::to_string(i), c.name, c.draw,
                  fmt::format("{}:{}:{}",
                              std::filesystem::path(sources.path(c.span.file)).filename().string(),
                              where.line, where.column)});
  }
  return table.Format(0);
}

}  // namespace prs::cli
