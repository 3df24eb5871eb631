// Formats the measurements of `prs stats` as text tables or JSON. Rates are per attempt, so
// the rejection rates and the acceptance rate add up to 100%.
#include "cli/stats_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli/common.h"
#include "cli/text_table.h"

namespace prs::cli {
namespace {

using CulpritKey = std::pair<lang::RejectionKind, std::string>;

struct CulpritRow {
  const CulpritKey* key;
  int64_t count;
  const lang::Rejection* example;  // may be null
};

// Culprits, most frequent first (ties in the counts' own order, so the report is stable).
std::vector<CulpritRow> SortCulprits(const sampling::RejectionCounts& counts) {
  std::vector<CulpritRow> rows;
  for (const auto& [key, n] : counts.by_culprit) {
    const auto example = counts.examples.find(key);
    rows.push_back({&key, n, example == counts.examples.end() ? nullptr : &example->second});
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const CulpritRow& a, const CulpritRow& b) { return a.count > b.count; });
  return rows;
}

struct Location {
  std::string path;
  lang::LineColumn line_column;
  bool known = false;
};

Location LocateExample(const lang::Rejection* example, const lang::SourceManager& sources) {
  if (!example || example->span.file >= sources.file_count()) return {};
  return {sources.path(example->span.file),
          sources.CalcLineColumn(example->span.file, example->span.begin), true};
}

std::string FormatLocation(const Location& where) {
  if (!where.known) return "-";
  return fmt::format("{}:{}:{}", where.path, where.line_column.line, where.line_column.column);
}

double Ratio(double part, double whole) { return whole > 0 ? part / whole : 0.0; }

std::string Percent(double part, double whole) {
  return fmt::format("{:.2f}%", 100 * Ratio(part, whole));
}

// "17.4 µs", "50.0 ms", "2.50 s".
std::string FormatSeconds(double seconds) {
  if (seconds < 1e-3) return fmt::format("{:.1f} µs", seconds * 1e6);
  if (seconds < 1) return fmt::format("{:.1f} ms", seconds * 1e3);
  return fmt::format("{:.2f} s", seconds);
}

// --sampler gibbs: what the scenes are worth, and that they are correlated.
std::string FormatGibbs(const SamplingStats& stats) {
  if (!stats.gibbs) return "";
  const sampling::GibbsPlan& g = *stats.gibbs;
  const int64_t scenes = stats.summary.scenes;
  return fmt::format(
      "  gibbs sampler    correlated scenes: {:.0f} effective ({:.0f}/s); autocorrelation {:.1f} "
      "sweeps\n"
      "                   (the slowest statistic, {}: {:.1f}); {} between scenes, {} of burn-in,\n"
      "                   {} blocks, {} scenes a chain\n",
      g.CalcEffectiveScenes(scenes), Ratio(g.CalcEffectiveScenes(scenes), stats.seconds),
      g.tau_sweeps, g.tau_statistic, g.tau_worst_sweeps, FormatCount(g.thin_sweeps, "sweep"),
      FormatCount(g.burn_in_sweeps, "sweep"), g.blocks, g.scenes_per_chain);
}

// --sampler partial-rejection: how its draws went (from the pilot).
std::string FormatPartialRejection(const SamplingStats& stats) {
  if (!stats.partial_rejection) return "";
  const sampling::PartialRejectionPlan& p = *stats.partial_rejection;
  std::string sites;
  for (const sampling::ClutterSite& site : p.sites) {
    sites += fmt::format("{}{} x {} (intensity {:.1f})", sites.empty() ? "" : ", ",
                         site.ordinals.size(), site.name, site.intensity);
  }
  return fmt::format(
      "  partial rejection  exact, independent scenes; sites: {}\n"
      "                     pilot: {:.1f} rounds and {:.0f} probe runs a hard-core draw, {} of "
      "draws with the program's counts\n",
      sites, p.mean_rounds, p.mean_probes, Percent(p.count_acceptance, 1));
}

std::string FormatOverview(const SamplingStats& stats) {
  const auto& s = stats.summary;
  if (stats.partial_rejection) {
    // A scene takes hard-core draws of probe runs (one object each), then one run of the whole
    // program, which its requirements may reject.
    return fmt::format(
               "{}: {} from seed {}, region sampling with --sampler partial-rejection, {}\n\n"
               "  program runs     {:.2f} a scene ({} in all, {} whole-scene runs rejected), {} "
               "max\n"
               "  time per scene   {}  ({:.0f} scenes/s; {} in all)\n",
               stats.file, FormatCount(s.scenes, "scene"), stats.seed,
               FormatCount(stats.threads, "thread"), Ratio(s.attempts, s.scenes), s.attempts,
               s.rejections.total, stats.max_attempts_per_scene,
               FormatSeconds(Ratio(stats.seconds, s.scenes)), Ratio(s.scenes, stats.seconds),
               FormatSeconds(stats.seconds)) +
           FormatPartialRejection(stats);
  }
  if (stats.gibbs) {
    // A Gibbs scene is not one accepted attempt among several: it takes a sweep of moves,
    // each run of the program a try of one move.
    return fmt::format(
               "{}: {} from seed {}, {} sampling with --sampler gibbs, {}\n\n"
               "  program runs     {:.2f} a scene ({} in all, {} of them accepted moves), {} max\n"
               "  time per scene   {}  ({:.0f} scenes/s; {} in all)\n",
               stats.file, FormatCount(s.scenes, "scene"), stats.seed,
               stats.naive ? "naive" : "region", FormatCount(stats.threads, "thread"),
               Ratio(s.attempts, s.scenes), s.attempts,
               Percent(s.attempts - s.rejections.total, s.attempts), stats.max_attempts_per_scene,
               FormatSeconds(Ratio(stats.seconds, s.scenes)), Ratio(s.scenes, stats.seconds),
               FormatSeconds(stats.seconds)) +
           FormatGibbs(stats);
  }
  return fmt::format(
      "{}: {} from seed {}, {} sampling, {}\n\n"
      "  acceptance rate  {}  ({} in {})\n"
      "  attempts/scene   {:.2f} mean, {} max\n"
      "  time per scene   {}  ({:.0f} scenes/s; {} in all)\n",
      stats.file, FormatCount(s.scenes, "scene"), stats.seed, stats.naive ? "naive" : "region",
      FormatCount(stats.threads, "thread"), Percent(s.scenes, s.attempts),
      FormatCount(s.scenes, "scene"), FormatCount(s.attempts, "attempt"),
      Ratio(s.attempts, s.scenes), stats.max_attempts_per_scene,
      FormatSeconds(Ratio(stats.seconds, s.scenes)), Ratio(s.scenes, stats.seconds),
      FormatSeconds(stats.seconds));
}

// Whole-scene rejection makes attempts at a scene; the other samplers make program runs that
// are no such attempts (docs/cli.md, "prs stats").
bool CountsProgramRuns(const SamplingStats& stats) {
  return stats.gibbs.has_value() || stats.partial_rejection.has_value();
}

std::string FormatReasonTable(const sampling::BatchSummary& s, bool program_runs) {
  // "per scene" is the paper's Table II figure: rejections per valid scene.
  TextTable table({"reason", "count", program_runs ? "per run" : "per attempt", "per scene"},
                  "lrrr");
  for (const auto& [kind, n] : s.rejections.by_kind) {
    table.AddRow({lang::RejectionKindName(kind), std::to_string(n), Percent(n, s.attempts),
                  fmt::format("{:.2f}", Ratio(n, s.scenes))});
  }
  table.AddRow({"total", std::to_string(s.rejections.total),
                Percent(s.rejections.total, s.attempts),
                fmt::format("{:.2f}", Ratio(s.rejections.total, s.scenes))});
  return "\nrejections by reason\n" + table.Format();
}

// The most frequent culprits; the rest are summed in one line (the JSON lists them all).
std::string FormatCulpritTable(const sampling::BatchSummary& s,
                               const lang::SourceManager& sources) {
  constexpr size_t kMaxRows = 20;
  const std::vector<CulpritRow> rows = SortCulprits(s.rejections);
  TextTable table({"count", "reason", "culprit", "where"}, "rlll");
  int64_t rest = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (i >= kMaxRows) {
      rest += rows[i].count;
      continue;
    }
    table.AddRow({std::to_string(rows[i].count), lang::RejectionKindName(rows[i].key->first),
                  rows[i].key->second, FormatLocation(LocateExample(rows[i].example, sources))});
  }
  std::string text = "\nrejections by culprit\n" + table.Format();
  if (rows.size() > kMaxRows) {
    text += fmt::format("  ... {} not shown, with {} (--json lists all)\n",
                        FormatCount(int64_t(rows.size() - kMaxRows), "culprit"),
                        FormatCount(rest, "rejection"));
  }
  return text;
}

nlohmann::ordered_json CulpritsToJson(const sampling::RejectionCounts& counts,
                                      const lang::SourceManager& sources) {
  nlohmann::ordered_json culprits = nlohmann::ordered_json::array();
  for (const CulpritRow& row : SortCulprits(counts)) {
    const Location where = LocateExample(row.example, sources);
    nlohmann::ordered_json entry = {{"reason", lang::RejectionKindName(row.key->first)},
                                    {"culprit", row.key->second},
                                    {"count", row.count}};
    entry["file"] = where.known ? nlohmann::ordered_json(where.path) : nullptr;
    entry["line"] = where.known ? nlohmann::ordered_json(where.line_column.line) : nullptr;
    entry["column"] = where.known ? nlohmann::ordered_json(where.line_column.column) : nullptr;
    culprits.push_back(std::move(entry));
  }
  return culprits;
}

nlohmann::ordered_json RejectionsToJson(const sampling::RejectionCounts& counts,
                                        const lang::SourceManager& sources) {
  nlohmann::ordered_json by_reason = nlohmann::ordered_json::object();
  for (const auto& [kind, n] : counts.by_kind) by_reason[lang::RejectionKindName(kind)] = n;
  return {{"total", counts.total},
          {"by_reason", by_reason},
          {"by_culprit", CulpritsToJson(counts, sources)}};
}

}  // namespace

std::string FormatStatsTable(const SamplingStats& stats, const lang::SourceManager& sources) {
  std::string text = FormatOverview(stats);
  if (stats.summary.rejections.total == 0) return text + "\nno rejections\n";
  return text + FormatReasonTable(stats.summary, CountsProgramRuns(stats)) +
         FormatCulpritTable(stats.summary, sources);
}

std::string FormatStatsJson(const SamplingStats& stats, const lang::SourceManager& sources) {
  const auto& s = stats.summary;
  nlohmann::ordered_json report = {
      {"format", "prs-stats/1"},
      {"file", stats.file},
      {"seed", stats.seed},
      {"mode", stats.naive ? "naive" : "region"},
      {"threads", stats.threads},
      {"scenes", s.scenes},
  };
  const nlohmann::ordered_json per_scene = {{"mean", Ratio(s.attempts, s.scenes)},
                                            {"max", stats.max_attempts_per_scene}};
  if (CountsProgramRuns(stats)) {
    // No attempts: scenes + rejections.total is not what the sampler ran.
    report["program_runs"] = s.attempts;
    report["program_runs_per_scene"] = per_scene;
  } else {
    report["attempts"] = s.attempts;
    report["acceptance_rate"] = Ratio(s.scenes, s.attempts);
    report["attempts_per_scene"] = per_scene;
  }
  report["rejections"] = RejectionsToJson(s.rejections, sources);
  report["seconds"] = stats.seconds;
  report["seconds_per_scene"] = Ratio(stats.seconds, s.scenes);
  report["scenes_per_second"] = Ratio(s.scenes, stats.seconds);
  report["sampler"] = stats.gibbs               ? "gibbs"
                      : stats.partial_rejection ? "partial-rejection"
                                                : "rejection";
  if (stats.partial_rejection) {
    const sampling::PartialRejectionPlan& p = *stats.partial_rejection;
    nlohmann::ordered_json sites = nlohmann::ordered_json::array();
    for (const sampling::ClutterSite& site : p.sites) {
      sites.push_back({{"site", site.name},
                       {"objects", site.ordinals.size()},
                       {"coordinates", site.coordinates},
                       {"intensity", site.intensity}});
    }
    report["partial_rejection"] = {{"sites", sites},
                                   {"pilot_draws", p.pilot_draws},
                                   {"mean_rounds", p.mean_rounds},
                                   {"mean_probe_runs", p.mean_probes},
                                   {"count_acceptance", p.count_acceptance}};
  }
  if (stats.gibbs) {
    const sampling::GibbsPlan& g = *stats.gibbs;
    report["gibbs"] = {
        {"effective_scenes", g.CalcEffectiveScenes(s.scenes)},
        {"effective_scenes_per_second", Ratio(g.CalcEffectiveScenes(s.scenes), stats.seconds)},
        {"autocorrelation_sweeps", g.tau_sweeps},
        {"autocorrelation_statistics", g.statistics},
        {"slowest_statistic", g.tau_statistic},
        {"slowest_statistic_sweeps", g.tau_worst_sweeps},
        {"autocorrelation_scenes", g.tau_scenes},
        {"thin_sweeps", g.thin_sweeps},
        {"burn_in_sweeps", g.burn_in_sweeps},
        {"blocks", g.blocks},
        {"scenes_per_chain", g.scenes_per_chain},
        {"pilot_sweeps", g.pilot_sweeps}};
  }
  return report.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace prs::cli
