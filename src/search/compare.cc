// Paired comparison of two runs on the same scenes (see compare.h).
#include "search/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

namespace prs::search {

namespace {

using SceneKey = std::pair<uint64_t, uint64_t>;  // (seed, index)

std::string Describe(const SceneKey& key) {
  return fmt::format("seed {} index {}", key.first, key.second);
}

// Each record of a run by its scene; throws on a record without a seed or a scene seen twice.
std::map<SceneKey, size_t> IndexRun(const std::vector<ReportRecord>& run, const std::string& path) {
  std::map<SceneKey, size_t> by_scene;
  for (size_t i = 0; i < run.size(); ++i) {
    const ReportRecord& r = run[i];
    if (!r.seed) {
      throw std::runtime_error(fmt::format(
          "{}:{}: the record has no \"seed\", so its scene cannot be matched; give records "
          "written by prs test or prs search",
          path, r.line));
    }
    const SceneKey key{*r.seed, r.index};
    const auto [at, added] = by_scene.emplace(key, i);
    if (!added) {
      throw std::runtime_error(fmt::format(
          "{}:{}: {} is also on line {}; a paired comparison needs each scene once per run",
          path, r.line, Describe(key), run[at->second].line));
    }
  }
  return by_scene;
}

// "fingerprint 0123abcd, scene options '--settle=3'" for what identifies a run's scenes.
std::string DescribeScenes(const ReportRecord& r) {
  if (r.spec.empty()) return "no program fingerprint (scenes read from files, or an older prs)";
  return fmt::format("the program fingerprint {}, scene options '{}'", r.spec,
                     r.scene_options.value_or("(not recorded)"));
}

// Throws unless the two runs' records name the same program and scene options (when both say),
// naming both sides: two programs' scene (seed, index) are different scenes.
void CheckSamePrograms(const std::vector<ReportRecord>& before, const std::string& before_path,
                       const std::vector<ReportRecord>& after, const std::string& after_path) {
  const auto refuse = [&](const ReportRecord& b, const ReportRecord& a) {
    throw std::runtime_error(fmt::format(
        "{}:{} and {}:{}: the runs are not of the same scenes: {} has {}, {} has {}. A paired "
        "comparison needs two runs of the same program with the same scene options (-p, "
        "--settle, --stable, --sampler, --design), before and after a change to the controller",
        before_path, b.line, after_path, a.line, before_path, DescribeScenes(b), after_path,
        DescribeScenes(a)));
  };
  for (const auto* run : {&before, &after}) {
    for (const ReportRecord& r : *run) {
      const ReportRecord& first = run->front();
      if (r.spec != first.spec || r.scene_options != first.scene_options) {
        const std::string& path = run == &before ? before_path : after_path;
        throw std::runtime_error(fmt::format(
            "{}:{}: the record has {}, line {} has {}: one run's records must come from one "
            "program and one set of scene options",
            path, r.line, DescribeScenes(r), first.line, DescribeScenes(first)));
      }
    }
  }
  const ReportRecord &b = before.front(), &a = after.front();
  if (b.spec.empty() != a.spec.empty() || b.spec != a.spec) refuse(b, a);
  if (b.scene_options && a.scene_options && *b.scene_options != *a.scene_options) refuse(b, a);
}

// Throws unless the two records describe the same scene, as far as they say.
void CheckSameScene(const ReportRecord& before, const std::string& before_path,
                    const ReportRecord& after, const std::string& after_path) {
  const SceneKey key{*before.seed, before.index};
  const auto refuse = [&](const std::string& what) {
    throw std::runtime_error(fmt::format(
        "{}:{} and {}:{}: {} is not the same scene in both runs: {}. Compare two runs of the "
        "same program with the same scene options (--settle, --stable, --design, ...)",
        before_path, before.line, after_path, after.line, Describe(key), what));
  };
  if (!before.spec.empty() && !after.spec.empty() && before.spec != after.spec) {
    refuse(fmt::format("the program's fingerprint is {} before and {} after", before.spec,
                       after.spec));
  }
  if (!before.coordinates.empty() && !after.coordinates.empty() &&
      before.coordinates != after.coordinates) {
    refuse("its scene coordinates differ");
  }
  const std::map<std::string, double> after_features(after.features.begin(),
                                                     after.features.end());
  // The same objects: without a fingerprint, the features are all that identify a scene.
  if (before.spec.empty() && (before.features.empty() || after.features.empty())) {
    refuse("the records carry neither a program fingerprint nor scene features to match");
  }
  for (const auto& [name, value] : before.features) {
    const auto other = after_features.find(name);
    if (other == after_features.end()) {
      if (after.features.empty()) continue;
      refuse(fmt::format("{} has {}, the other not", before_path, name.substr(0, name.rfind('.'))));
    }
    if (std::abs(value - other->second) > 1e-9 * std::max(1.0, std::abs(value))) {
      refuse(fmt::format("{} is {} before and {} after", name, value, other->second));
    }
  }
}

// Throws for a run that replays only the other's failures (`prs test --replay R --failed`):
// its scenes were chosen by the other run's outcome, so they could be fixed but never broken,
// and a paired test on them would always find an improvement.
void CheckNotAReplayOfFailures(const std::vector<ReportRecord>& before,
                               const std::string& before_path,
                               const std::vector<ReportRecord>& after,
                               const std::string& after_path) {
  for (const auto* run : {&before, &after}) {
    const ReportRecord& r = run->front();
    if (!r.replay_failed_only) continue;
    throw std::runtime_error(fmt::format(
        "{}:{}: the run replays only the failures of {} (--replay --failed): its scenes were "
        "chosen because they failed, so they can be fixed but not broken, and a paired test on "
        "them would always find an improvement. Replay every scene (`prs test PROGRAM.prs "
        "--replay {}` without --failed) and compare that run; the --failed replay's own table "
        "says how many of the failures pass now",
        run == &before ? before_path : after_path, r.line, r.replay_of, r.replay_of));
  }
}

std::vector<std::string> ListOutcomes(const PairedComparison& c) {
  std::map<std::string, int64_t> count;
  for (const ReportRecord& r : c.before) ++count[r.outcome];
  for (const ReportRecord& r : c.after) ++count[r.outcome];
  std::vector<std::string> outcomes;
  for (const auto& [name, n] : count) outcomes.push_back(name);
  std::stable_sort(outcomes.begin(), outcomes.end(), [&](const auto& a, const auto& b) {
    if ((a == "success") != (b == "success")) return a == "success";
    return count[a] > count[b];
  });
  return outcomes;
}

int64_t Count(const std::vector<ReportRecord>& run, const std::string& outcome) {
  return std::count_if(run.begin(), run.end(),
                       [&](const ReportRecord& r) { return r.outcome == outcome; });
}

std::string Percent(int64_t k, size_t n) {
  return fmt::format("{:.1f} %", n ? 100.0 * static_cast<double>(k) / static_cast<double>(n) : 0.0);
}

// What the test says, in words.
std::string Verdict(const PairedComparison& c) {
  const size_t fixed = c.fixed.size(), broke = c.broke.size();
  if (fixed + broke == 0) {
    return "No scene changed between passing and failing, so the runs give no evidence that the "
           "change made a difference.";
  }
  const std::string direction = fixed > broke   ? "for the better"
                                : broke > fixed ? "for the worse"
                                                : "either way";
  if (c.mcnemar_p < 0.05) {
    return fmt::format(
        "The change made a difference {} (p < 0.05): {} fixed against {} broken is unlikely "
        "if each were a coin toss.",
        direction, fixed, broke);
  }
  return fmt::format(
      "No evidence at the 5 % level that the change made a difference: {} fixed against {} "
      "broken could be chance. More scenes would tell.",
      fixed, broke);
}

std::string RegenerateCell(const ReportRecord& a, const ReportRecord& b) {
  const std::string& command = !a.regenerate.empty() ? a.regenerate : b.regenerate;
  return command.empty() ? "" : "`" + command + "`";
}

// A table cell: no line breaks or pipes.
std::string Cell(std::string text) {
  for (char& ch : text) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  std::string out;
  for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

void AppendSceneTable(const PairedComparison& c, const std::vector<PairedScene>& scenes,
                      const std::string& title, std::string& md) {
  if (scenes.empty()) return;
  md += fmt::format("\n## {} ({})\n\n", title, scenes.size());
  md += "| seed | index | before | after | detail | regenerate |\n|---|---|---|---|---|---|\n";
  for (const PairedScene& s : scenes) {
    const ReportRecord& b = c.before[s.before];
    const ReportRecord& a = c.after[s.after];
    // The failing side's detail says what went wrong.
    const std::string& detail = a.outcome != "success" ? a.detail : b.detail;
    md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", *b.seed, b.index, b.outcome, a.outcome,
                      Cell(detail), RegenerateCell(a, b));
  }
}

nlohmann::json SceneListJson(const PairedComparison& c, const std::vector<PairedScene>& scenes) {
  nlohmann::json list = nlohmann::json::array();
  for (const PairedScene& s : scenes) {
    const ReportRecord& b = c.before[s.before];
    const ReportRecord& a = c.after[s.after];
    nlohmann::json item = {{"seed", *b.seed},       {"index", b.index},
                           {"before", b.outcome},   {"after", a.outcome},
                           {"before_detail", b.detail}, {"after_detail", a.detail}};
    const std::string& command = !a.regenerate.empty() ? a.regenerate : b.regenerate;
    if (!command.empty()) item["regenerate"] = command;
    list.push_back(std::move(item));
  }
  return list;
}

}  // namespace

double CalcMcNemarExactP(int64_t fixed, int64_t broke) {
  const int64_t n = fixed + broke, k = std::min(fixed, broke);
  if (n == 0) return 1;
  // P[X <= k] for X ~ Binomial(n, 1/2), summed in logs (n may be in the thousands).
  double tail = 0;
  for (int64_t i = 0; i <= k; ++i) {
    const double log_term = std::lgamma(n + 1.0) - std::lgamma(i + 1.0) -
                            std::lgamma(static_cast<double>(n - i) + 1) - n * std::log(2.0);
    tail += std::exp(log_term);
  }
  return std::min(1.0, 2 * tail);
}

PairedComparison ComparePairedRuns(std::vector<ReportRecord> before, const std::string& before_path,
                                   std::vector<ReportRecord> after, const std::string& after_path) {
  const std::map<SceneKey, size_t> before_scenes = IndexRun(before, before_path);
  const std::map<SceneKey, size_t> after_scenes = IndexRun(after, after_path);
  // Every scene of `from` must be in `in`.
  const auto check_all_in = [](const std::map<SceneKey, size_t>& from,
                               const std::vector<ReportRecord>& from_run,
                               const std::string& from_path, const std::map<SceneKey, size_t>& in,
                               const std::string& in_path) {
    for (const auto& [key, i] : from) {
      if (in.count(key)) continue;
      throw std::runtime_error(fmt::format(
          "{}:{}: {} is not in {} ({} scenes against {}); a paired comparison needs the same "
          "scenes in both runs: run the controller after the change with the same -s, -n and "
          "scene options, or on the same scenes",
          from_path, from_run[i].line, Describe(key), in_path, from.size(), in.size()));
    }
  };
  CheckSamePrograms(before, before_path, after, after_path);
  CheckNotAReplayOfFailures(before, before_path, after, after_path);
  check_all_in(before_scenes, before, before_path, after_scenes, after_path);
  check_all_in(after_scenes, after, after_path, before_scenes, before_path);
  PairedComparison c;
  c.before_path = before_path;
  c.after_path = after_path;
  c.before = std::move(before);
  c.after = std::move(after);
  for (const auto& [key, b] : before_scenes) {
    const PairedScene scene{b, after_scenes.at(key)};
    const ReportRecord& rb = c.before[scene.before];
    const ReportRecord& ra = c.after[scene.after];
    CheckSameScene(rb, before_path, ra, after_path);
    c.scenes.push_back(scene);
    if (!rb.failed() && !ra.failed()) {
      ++c.both_succeed;
    } else if (rb.failed() && !ra.failed()) {
      c.fixed.push_back(scene);
    } else if (!rb.failed() && ra.failed()) {
      c.broke.push_back(scene);
    } else {
      ++c.both_fail;
      if (rb.outcome != ra.outcome) c.changed_failure.push_back(scene);
    }
  }
  c.outcomes = ListOutcomes(c);
  c.mcnemar_p = CalcMcNemarExactP(static_cast<int64_t>(c.fixed.size()),
                                  static_cast<int64_t>(c.broke.size()));
  return c;
}

std::string FormatComparisonMarkdown(const PairedComparison& c) {
  const size_t n = c.scenes.size();
  std::string md = fmt::format("# {} against {}\n\n", c.after_path, c.before_path);
  md += fmt::format(
      "{} scenes, the same in both runs (matched by seed and index). Before: `{}`; after: "
      "`{}`.\n\n",
      n, c.before_path, c.after_path);
  md += "| outcome | before | after | change |\n|---|---|---|---|\n";
  for (const std::string& outcome : c.outcomes) {
    const int64_t b = Count(c.before, outcome), a = Count(c.after, outcome);
    md += fmt::format("| {} | {} ({}) | {} ({}) | {:+d} |\n", outcome, b, Percent(b, n), a,
                      Percent(a, n), a - b);
  }
  md += fmt::format(
      "\nScene by scene: **{} fixed** (failed before, succeed after), **{} broken** (succeeded "
      "before, fail after), {} succeed in both, {} fail in both ({} of them another way).\n\n",
      c.fixed.size(), c.broke.size(), c.both_succeed, c.both_fail, c.changed_failure.size());
  md += fmt::format(
      "McNemar's exact test (two-sided) on the {} scenes whose pass/fail changed: p = {:.4g}. {}\n",
      c.fixed.size() + c.broke.size(), c.mcnemar_p, Verdict(c));
  AppendSceneTable(c, c.fixed, "Fixed", md);
  AppendSceneTable(c, c.broke, "Broken", md);
  AppendSceneTable(c, c.changed_failure, "Failing another way", md);
  return md;
}

std::string FormatComparisonJson(const PairedComparison& c) {
  nlohmann::json outcomes = nlohmann::json::object();
  for (const std::string& outcome : c.outcomes) {
    outcomes[outcome] = {{"before", Count(c.before, outcome)}, {"after", Count(c.after, outcome)}};
  }
  const nlohmann::json j = {
      {"before", c.before_path},
      {"after", c.after_path},
      {"scenes", c.scenes.size()},
      {"outcomes", outcomes},
      {"both_succeed", c.both_succeed},
      {"both_fail", c.both_fail},
      {"fixed", SceneListJson(c, c.fixed)},
      {"broke", SceneListJson(c, c.broke)},
      {"changed_failure", SceneListJson(c, c.changed_failure)},
      {"mcnemar", {{"fixed", c.fixed.size()}, {"broke", c.broke.size()}, {"p", c.mcnemar_p}}}};
  return j.dump();
}

}  // namespace prs::search
