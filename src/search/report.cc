// The failure report: feature table, one-threshold splits, depth-2 and depth-3 trees (failure
// modes are the failure-rich leaves) and the Markdown/SVG that show them. The statistics are
// small and written here (the best split per feature by information gain): a library such as
// mlpack would bring Armadillo and far more than these lines; Python users have scikit-learn
// for deeper models.
#include "search/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "search/estimate.h"
#include "search/intervals.h"
#include "search/report_plot.h"

namespace prs::search {
namespace {

double Entropy(int64_t k, int64_t n) {
  if (n == 0 || k == 0 || k == n) return 0;
  const double p = static_cast<double>(k) / static_cast<double>(n);
  return -p * std::log2(p) - (1 - p) * std::log2(1 - p);
}

double Rate(int64_t k, int64_t n) { return n > 0 ? static_cast<double>(k) / n : 0.0; }

// The best split of feature f over the records in `subset`, or nullopt.
std::optional<Split> BestSplit(const FeatureTable& table, const std::vector<bool>& failed,
                               const std::vector<size_t>& subset, int f, int64_t min_leaf) {
  std::vector<std::pair<double, bool>> values;
  values.reserve(subset.size());
  for (size_t r : subset) {
    const double v = table.rows[r][f];
    if (!std::isnan(v)) values.emplace_back(v, failed[r]);
  }
  const int64_t n = static_cast<int64_t>(values.size());
  if (n < 2 * min_leaf) return std::nullopt;
  std::sort(values.begin(), values.end());
  int64_t total_failures = 0;
  for (const auto& v : values) total_failures += v.second;
  const double parent = Entropy(total_failures, n);
  std::optional<Split> best;
  int64_t below = 0, failures_below = 0;
  for (int64_t i = 0; i + 1 < n; ++i) {
    ++below;
    failures_below += values[i].second;
    if (values[i].first == values[i + 1].first) continue;
    const int64_t above = n - below, failures_above = total_failures - failures_below;
    if (below < min_leaf || above < min_leaf) continue;
    const double gain = parent - (static_cast<double>(below) / n) * Entropy(failures_below, below) -
                        (static_cast<double>(above) / n) * Entropy(failures_above, above);
    if (best && gain <= best->gain) continue;
    Split s;
    s.feature = f;
    s.threshold = 0.5 * (values[i].first + values[i + 1].first);
    s.failures_below = Rate(failures_below, below) >= Rate(failures_above, above);
    s.n_side = s.failures_below ? below : above;
    s.failures_side = s.failures_below ? failures_below : failures_above;
    s.n_other = s.failures_below ? above : below;
    s.failures_other = s.failures_below ? failures_above : failures_below;
    s.gain = gain;
    best = s;
  }
  return best;
}

TreeNode Grow(const FeatureTable& table, const std::vector<bool>& failed,
              const std::vector<size_t>& subset, int depth, int64_t min_leaf) {
  TreeNode node;
  node.n = static_cast<int64_t>(subset.size());
  for (size_t r : subset) node.failures += failed[r];
  if (depth == 0 || node.failures == 0 || node.failures == node.n) return node;
  std::optional<Split> best;
  for (int f = 0; f < static_cast<int>(table.names.size()); ++f) {
    const auto s = BestSplit(table, failed, subset, f, min_leaf);
    if (s && (!best || s->gain > best->gain)) best = s;
  }
  if (!best || best->gain <= 1e-9) return node;
  node.split = best;
  std::vector<size_t> below, above;
  for (size_t r : subset) {
    const double v = table.rows[r][best->feature];
    (std::isnan(v) || v <= best->threshold ? below : above).push_back(r);
  }
  node.children.push_back(Grow(table, failed, below, depth - 1, min_leaf));
  node.children.push_back(Grow(table, failed, above, depth - 1, min_leaf));
  return node;
}

std::string FormatNumber(double x) { return fmt::format("{:.4g}", x); }

// A path as a Markdown link's target: what would end or break one (spaces, brackets of every
// kind) or be read as a URL's fragment or query ('#', '?'), and '%' itself, percent-encoded, so
// "my runs/a (1).png" still links.
std::string FormatLinkTarget(const std::string& path) {
  std::string out;
  for (const char c : path) {
    if (c == ' ' || c == '(' || c == ')' || c == '<' || c == '>' || c == '%' || c == '[' ||
        c == ']' || c == '#' || c == '?') {
      out += fmt::format("%{:02X}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out;
}

// "k of n (x %, 95 % CI lo–hi %)" with the exact binomial interval: a subset's rate.
std::string FormatRate(int64_t k, int64_t n) {
  const RateInterval ci = CalcClopperPearsonInterval(double(k), double(n));
  return fmt::format("{} of {} ({:.1f} %, 95 % CI {:.1f}–{:.1f} %)", k, n, 100 * Rate(k, n),
                     100 * ci.low, 100 * ci.high);
}

std::string DescribeSide(const FeatureTable& table, const Split& s, bool failure_side) {
  const bool below = s.failures_below == failure_side;
  return fmt::format("{} {} {}", table.names[s.feature], below ? "≤" : ">",
                     FormatNumber(s.threshold));
}

void FormatTree(const FeatureTable& table, const TreeNode& node, int indent, std::string* out) {
  const std::string pad(2 * indent, ' ');
  if (!node.split) return;
  const Split& s = *node.split;
  for (int side = 0; side < 2; ++side) {
    const TreeNode& child = node.children[side];
    *out += fmt::format("{}- if {} {} {}: {} fail\n", pad, table.names[s.feature],
                        side == 0 ? "≤" : ">", FormatNumber(s.threshold),
                        FormatRate(child.failures, child.n));
    FormatTree(table, child, indent + 1, out);
  }
}

std::string FormatPercent(double p) { return fmt::format("{:#.3g} %", 100 * p); }

// The law of a file's records: importance when any record is weighted (an estimate's file, its
// adaptation beside), else the one law every record shares, else none (std::nullopt: mixed).
std::optional<RecordLaw> FindFileLaw(const std::vector<ReportRecord>& records) {
  std::set<RecordLaw> laws;
  for (const ReportRecord& r : records) laws.insert(DescribeLaw(r));
  if (laws.contains(RecordLaw::kSelected)) return RecordLaw::kSelected;
  if (laws.contains(RecordLaw::kImportance)) return RecordLaw::kImportance;
  if (laws.size() == 1) return *laws.begin();
  return std::nullopt;
}

// The outcome table: episodes and shares, with a 95 % interval when the shares estimate the
// program's rates (i.i.d.: exact binomial; a chain's: the same at its effective sample size).
std::string FormatOutcomeShares(const std::map<std::string, int64_t>& outcomes, int64_t n,
                                std::optional<double> effective_n) {
  std::string md = effective_n
                       ? "| outcome | episodes | share | 95 % interval |\n|---|---|---|---|\n"
                       : "| outcome | episodes | share |\n|---|---|---|\n";
  for (const auto& [name, count] : outcomes) {
    md += fmt::format("| {} | {} | {:.1f} % |", name, count, 100 * Rate(count, n));
    if (effective_n) {
      const double p = Rate(count, n);
      const RateInterval ci = CalcEffectiveCountInterval(p, p * (1 - p) / *effective_n,
                                                         *effective_n);
      md += fmt::format(" {} – {} |", FormatPercent(ci.low), FormatPercent(ci.high));
    }
    md += "\n";
  }
  return md;
}

// prs estimate's numbers from its records, as `prs estimate --from` prints them.
std::string FormatImportanceEstimate(const std::vector<ReportRecord>& records,
                                     const std::string& title) {
  const WeightedRecords weighted = SelectWeightedRecords(records, title, "");
  const Estimate e = CalcEstimate(weighted.records, weighted.outcomes_seen);
  std::string md = "## How often it fails (importance-sampling estimate)\n\n";
  if (!e.reliable) {
    std::string why = DescribeUnreliable(e);
    why[0] = char(std::toupper(static_cast<unsigned char>(why[0])));
    return md + why + " (`prs estimate`).\n\n";
  }
  if (e.outcomes.empty()) {
    return md + fmt::format(
                    "No failure in {} weighted episodes: the probability of failing is below {} "
                    "(a 95 % upper bound; a failure rarer than that may still exist).\n\n",
                    e.episodes, FormatPercent(e.upper_bound));
  }
  md +=
      "| outcome | probability | 95 % interval | failing episodes | i.i.d. episodes for as "
      "tight |\n|---|---|---|---|---|\n";
  for (const OutcomeEstimate& o : e.outcomes) {
    md += fmt::format("| {} | {} | {} – {} | {} | {:.0f} |\n", o.outcome, FormatPercent(o.p),
                      FormatPercent(o.ci_low), FormatPercent(o.ci_high), o.episodes,
                      o.iid_episodes);
  }
  return md + fmt::format(
                  "\nFrom the {} weighted episodes (effective sample size {:.0f}); `prs estimate "
                  "--from {}` gives the same numbers.\n\n",
                  e.episodes, e.ess, title);
}

// What the report says first: how often the controller fails under the program's law, as far
// as the records' law allows (DescribeLaw) — the importance-sampling estimate for weighted
// records, the shares with exact binomial intervals for i.i.d. ones (as `prs estimate --from`),
// a chain's shares at its effective sample size — then the outcome table.
std::string FormatHowOften(const std::vector<ReportRecord>& records, const std::string& title,
                           const std::map<std::string, int64_t>& outcomes) {
  const int64_t n = static_cast<int64_t>(records.size());
  const std::optional<RecordLaw> law = FindFileLaw(records);
  if (law == RecordLaw::kIid) {
    return "## How often it fails\n\nThe scenes were drawn independently from the program's law "
           "(i.i.d.), so each outcome's share estimates its probability, with the exact "
           "(Clopper–Pearson) 95 % interval that `prs estimate --from` gives too.\n\n" +
           FormatOutcomeShares(outcomes, n, double(n));
  }
  if (law == RecordLaw::kChain) {
    // The failure indicator in (seed, index) order: a chain's scenes follow each other there.
    std::vector<size_t> order(records.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return std::tie(records[a].seed, records[a].index) <
             std::tie(records[b].seed, records[b].index);
    });
    std::vector<double> failing;
    for (size_t i : order) failing.push_back(records[i].failed() ? 1.0 : 0.0);
    const double ess = CalcBatchMeansEss(failing);
    return fmt::format(
               "## How often it fails\n\nThe scenes come from Markov chains (--sampler gibbs): "
               "they follow the program's law but are correlated, so the {} episodes are worth "
               "about {:.0f} independent ones (the effective sample size of failing, by batch "
               "means in scene order). The intervals are exact binomial ones at that effective "
               "size, approximate as the effective size is estimated.\n\n",
               n, ess) +
           FormatOutcomeShares(outcomes, n, ess);
  }
  std::string md;
  if (law == RecordLaw::kImportance) {
    md = FormatImportanceEstimate(records, title) +
         "## The episodes run\n\nThe estimate drew its scenes toward failures, so the shares "
         "below are of the episodes run, not the program's rates.\n\n";
  } else {
    md = fmt::format(
        "## The episodes run\n\nThese are {}, so the shares below describe these episodes, not "
        "how often the controller fails under the program's law (`prs estimate` says "
        "that).\n\n",
        law ? DescribeLawInWords(*law) : "records of scenes chosen in more than one way");
  }
  return md + FormatOutcomeShares(outcomes, n, std::nullopt);
}

}  // namespace

std::vector<ReportRecord> ParseReportRecords(const std::vector<std::string>& lines,
                                             const std::string& path) {
  std::vector<ReportRecord> records;
  for (size_t n = 0; n < lines.size(); ++n) {
    if (lines[n].find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto j = nlohmann::json::parse(lines[n], nullptr, /*allow_exceptions=*/false);
    const std::string where = fmt::format("{}:{}", path, n + 1);
    if (!j.is_object() || !j.contains("outcome") || !j["outcome"].is_string() ||
        !j.contains("index") || !j["index"].is_number_unsigned()) {
      throw std::runtime_error(where +
                               ": not an episode record (a JSON object with \"index\" and "
                               "\"outcome\"); give the -o file of prs test or prs search");
    }
    ReportRecord r;
    r.line = static_cast<int64_t>(n + 1);
    r.index = j["index"].get<uint64_t>();
    r.outcome = j["outcome"].get<std::string>();
    const auto text = [&](const char* key) {
      return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
    };
    if (j.contains("seed") && j["seed"].is_number_unsigned()) r.seed = j["seed"].get<uint64_t>();
    r.detail = text("detail");
    r.regenerate = text("regenerate");
    r.spec = text("spec");
    if (j.contains("scene_options") && j["scene_options"].is_string()) {
      r.scene_options = j["scene_options"].get<std::string>();
    }
    if (j.contains("replay") && j["replay"].is_object()) {
      const nlohmann::json& replay = j["replay"];
      r.replay_of = replay.contains("of") && replay["of"].is_string()
                        ? replay["of"].get<std::string>()
                        : std::string("(unnamed)");
      r.replay_failed_only = replay.contains("failed_only") && replay["failed_only"] == true;
    }
    if (j.contains("score") && j["score"].is_number()) r.score = j["score"].get<double>();
    if (j.contains("coordinates") && j["coordinates"].is_array()) {
      for (const auto& x : j["coordinates"]) {
        if (x.is_number()) r.coordinates.push_back(x.get<double>());
      }
    }
    if (j.contains("features") && j["features"].is_object()) {
      for (const auto& [name, value] : j["features"].items()) {
        if (value.is_number() && std::isfinite(value.get<double>())) {
          r.features.emplace_back(name, value.get<double>());
        }
      }
    }
    r.saved_scene = text("saved_scene");
    if (j.contains("search") && j["search"].is_object()) {
      const nlohmann::json& search = j["search"];
      r.search_json = search.dump();
      const auto number = [&](const char* key) {
        return search.contains(key) && search[key].is_number() ? search[key].get<double>() : 0.0;
      };
      r.search_strategy = search.contains("strategy") && search["strategy"].is_string()
                              ? search["strategy"].get<std::string>()
                              : "search";
      if (r.search_strategy == "importance") {
        r.weight = number("weight");
        r.uniform_share = number("uniform_share");
        r.normalised = !search.contains("normalised") || search["normalised"] != false;
        if (search.contains("kernel_share") && search["kernel_share"].is_number()) {
          r.kernel_share = search["kernel_share"].get<double>();
        }
        if (!(r.weight > 0) || !(r.uniform_share > 0) || !std::isfinite(r.weight)) {
          throw std::runtime_error(where +
                                   ": an importance-sampling record without a positive "
                                   "\"weight\" and \"uniform_share\"");
        }
      }
    }
    records.push_back(std::move(r));
  }
  if (records.empty()) throw std::runtime_error(path + ": no episode records");
  return records;
}

RecordLaw DescribeLaw(const ReportRecord& record) {
  if (record.replay_failed_only) return RecordLaw::kSelected;
  if (record.search_strategy == "importance") return RecordLaw::kImportance;
  if (!record.search_strategy.empty()) return RecordLaw::kSearch;
  std::string options(1, ' ');  // appended, not " " + ...: GCC 12's false -Wrestrict
  options.append(record.scene_options.value_or("")).append(1, ' ');
  if (options.find(" --sampler gibbs ") != std::string::npos) return RecordLaw::kChain;
  if (options.find(" --design ") != std::string::npos) return RecordLaw::kDesign;
  return RecordLaw::kIid;
}

std::string DescribeLawInWords(RecordLaw law) {
  switch (law) {
    case RecordLaw::kIid:
      return "records of scenes drawn independently from the program's law";
    case RecordLaw::kImportance:
      return "prs estimate's weighted records";
    case RecordLaw::kSearch:
      return "records of a search, whose scenes are not drawn from the program's law";
    case RecordLaw::kChain:
      return "records of Markov chains (--sampler gibbs), whose scenes are correlated";
    case RecordLaw::kDesign:
      return "records of a design's points (--design), which are spread evenly, not drawn "
             "independently";
    case RecordLaw::kSelected:
      return "records of a replay of failures alone (--replay R --failed), chosen by their "
             "outcome";
  }
  return "";
}

FeatureTable BuildFeatureTable(const std::vector<ReportRecord>& records) {
  // Recorded features, in order of first appearance.
  std::vector<std::string> names;
  std::map<std::string, int> column;
  for (const auto& r : records) {
    for (const auto& [name, value] : r.features) {
      if (column.emplace(name, static_cast<int>(names.size())).second) names.push_back(name);
    }
  }
  std::vector<std::vector<double>> base(records.size(), std::vector<double>(names.size(), NAN));
  for (size_t i = 0; i < records.size(); ++i) {
    for (const auto& [name, value] : records[i].features) base[i][column[name]] = value;
  }
  auto varies = [&](const std::vector<std::vector<double>>& rows, size_t f) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& row : rows) {
      if (std::isnan(row[f])) continue;
      lo = std::min(lo, row[f]);
      hi = std::max(hi, row[f]);
    }
    return hi - lo > 1e-12;
  };
  FeatureTable table;
  table.rows.assign(records.size(), {});
  auto add = [&](const std::string& name, auto value_of) {
    std::vector<std::vector<double>> one(records.size(), std::vector<double>(1));
    for (size_t i = 0; i < records.size(); ++i) one[i][0] = value_of(i);
    if (!varies(one, 0)) return;
    table.names.push_back(name);
    for (size_t i = 0; i < records.size(); ++i) table.rows[i].push_back(one[i][0]);
  };
  for (size_t f = 0; f < names.size(); ++f) {
    add(names[f], [&](size_t i) { return base[i][f]; });
  }
  // Objects with recorded positions; pairs where at least one of the two moves.
  std::vector<std::string> objects;
  for (const auto& name : names) {
    if (name.size() > 2 && name.compare(name.size() - 2, 2, ".x") == 0) {
      objects.push_back(name.substr(0, name.size() - 2));
    }
  }
  auto value = [&](size_t i, const std::string& name) {
    const auto it = column.find(name);
    return it == column.end() ? NAN : base[i][it->second];
  };
  for (size_t a = 0; a < objects.size(); ++a) {
    for (size_t b = a + 1; b < objects.size(); ++b) {
      const std::string& A = objects[a];
      const std::string& B = objects[b];
      auto dx = [&](size_t i) { return value(i, A + ".x") - value(i, B + ".x"); };
      auto dy = [&](size_t i) { return value(i, A + ".y") - value(i, B + ".y"); };
      add("dist(" + A + ", " + B + ")", [&](size_t i) { return std::hypot(dx(i), dy(i)); });
      add(A + "-" + B + ".x", dx);
      add(A + "-" + B + ".y", dy);
    }
  }
  size_t d = 0;
  for (const auto& r : records) d = std::max(d, r.coordinates.size());
  for (size_t j = 0; j < d; ++j) {
    add("u[" + std::to_string(j) + "]", [&](size_t i) {
      return j < records[i].coordinates.size() ? records[i].coordinates[j] : NAN;
    });
  }
  return table;
}

std::vector<Split> RankSplits(const FeatureTable& table, const std::vector<bool>& failed) {
  std::vector<size_t> all(table.rows.size());
  std::iota(all.begin(), all.end(), 0);
  std::vector<Split> splits;
  const int64_t min_leaf = std::max<int64_t>(5, static_cast<int64_t>(table.rows.size()) / 100);
  for (int f = 0; f < static_cast<int>(table.names.size()); ++f) {
    if (auto s = BestSplit(table, failed, all, f, min_leaf)) splits.push_back(*s);
  }
  std::stable_sort(splits.begin(), splits.end(),
                   [](const Split& a, const Split& b) { return a.gain > b.gain; });
  return splits;
}

TreeNode GrowTree(const FeatureTable& table, const std::vector<bool>& failed, int depth,
                  int64_t min_leaf) {
  std::vector<size_t> all(table.rows.size());
  std::iota(all.begin(), all.end(), 0);
  return Grow(table, failed, all, depth, min_leaf);
}

std::vector<FailureMode> FindFailureModes(const FeatureTable& table,
                                          const std::vector<bool>& failed) {
  const int64_t n = static_cast<int64_t>(failed.size());
  const int64_t failures = std::count(failed.begin(), failed.end(), true);
  if (failures == 0) return {};
  std::vector<size_t> all(failed.size());
  std::iota(all.begin(), all.end(), 0);
  const TreeNode root = Grow(table, failed, all, 3, std::max<int64_t>(5, n / 50));
  std::vector<FailureMode> modes;
  // Walks the tree keeping each path's conditions and records.
  struct Step {
    const TreeNode* node;
    std::string description;
    std::vector<int> features;
    std::vector<size_t> records;
  };
  std::vector<Step> stack = {{&root, "", {}, all}};
  while (!stack.empty()) {
    Step step = std::move(stack.back());
    stack.pop_back();
    const TreeNode& node = *step.node;
    if (node.split) {
      const Split& s = *node.split;
      std::vector<size_t> side[2];
      for (size_t r : step.records) {
        const double v = table.rows[r][s.feature];
        side[std::isnan(v) || v <= s.threshold ? 0 : 1].push_back(r);
      }
      for (int k = 1; k >= 0; --k) {
        std::vector<int> features = step.features;
        features.push_back(s.feature);
        const std::string condition = fmt::format("{} {} {}", table.names[s.feature],
                                                  k == 0 ? "≤" : ">", FormatNumber(s.threshold));
        stack.push_back(
            {&node.children[k],
             step.description.empty() ? condition : step.description + " and " + condition,
             std::move(features), std::move(side[k])});
      }
      continue;
    }
    const bool rich = node.failures * n > failures * node.n;
    if (!rich || node.failures * 10 < failures) continue;
    FailureMode mode;
    mode.description = step.description.empty() ? "every episode" : step.description;
    mode.n = node.n;
    for (size_t r : step.records) {
      if (failed[r]) mode.members.push_back(r);
    }
    mode.mean.assign(table.names.size(), 0);
    for (size_t f = 0; f < table.names.size(); ++f) {
      double sum = 0;
      int64_t count = 0;
      for (size_t r : mode.members) {
        if (std::isnan(table.rows[r][f])) continue;
        sum += table.rows[r][f];
        ++count;
      }
      mode.mean[f] = count ? sum / count : NAN;
    }
    // The representative: nearest the members' mean in the path's features, each scaled by
    // its spread over the members.
    std::vector<double> spread(step.features.size(), 0);  // per path feature, over the members
    for (size_t i = 0; i < step.features.size(); ++i) {
      const int f = step.features[i];
      for (size_t m : mode.members) spread[i] += std::pow(table.rows[m][f] - mode.mean[f], 2);
      spread[i] = std::sqrt(spread[i] / static_cast<double>(mode.members.size()));
    }
    auto distance = [&](size_t r) {
      double d = 0;
      for (size_t i = 0; i < step.features.size(); ++i) {
        const int f = step.features[i];
        const double v = table.rows[r][f];
        if (!std::isnan(v) && spread[i] > 0) d += std::pow((v - mode.mean[f]) / spread[i], 2);
      }
      return d;
    };
    mode.representative = mode.members.front();
    double nearest = distance(mode.representative);
    for (size_t r : mode.members) {
      const double d = distance(r);
      if (d < nearest) {
        nearest = d;
        mode.representative = r;
      }
    }
    modes.push_back(std::move(mode));
  }
  std::stable_sort(modes.begin(), modes.end(), [](const FailureMode& a, const FailureMode& b) {
    return a.members.size() > b.members.size();
  });
  return modes;
}

std::string FormatFailureReport(const std::vector<ReportRecord>& records,
                                const ReportOptions& options, std::string* svg) {
  const FeatureTable table = BuildFeatureTable(records);
  std::vector<bool> failed(records.size());
  int64_t failures = 0;
  std::map<std::string, int64_t> outcomes;
  for (size_t i = 0; i < records.size(); ++i) {
    failed[i] = records[i].failed();
    failures += failed[i];
    ++outcomes[records[i].outcome];
  }
  const int64_t n = static_cast<int64_t>(records.size());
  std::string md = fmt::format("# Failure report: {}\n\n{} episodes; {} failed.\n\n",
                               options.title, n, failures);
  md += FormatHowOften(records, options.title, outcomes);
  if (failures == 0 || failures == n) {
    md += fmt::format("\nEvery episode {}: nothing separates failures from successes.\n",
                      failures == 0 ? "succeeded" : "failed");
    return md;
  }
  const std::vector<Split> splits = RankSplits(table, failed);
  md += "\n## What separates failures from successes\n\n";
  if (splits.empty()) {
    md += "No feature splits the episodes (the records carry no varying features).\n";
    return md;
  }
  const Split& top = splits.front();
  md += fmt::format("The strongest single split: **{}**. There, {} fail; elsewhere {}.\n\n",
                    DescribeSide(table, top, true), FormatRate(top.failures_side, top.n_side),
                    FormatRate(top.failures_other, top.n_other));
  md +=
      "| rank | feature | failure-rich side | fail there | fail elsewhere | gain (bits) |\n"
      "|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < splits.size() && i < 10; ++i) {
    const Split& s = splits[i];
    md += fmt::format("| {} | {} | {} | {} | {} | {:.3f} |\n", i + 1, table.names[s.feature],
                      DescribeSide(table, s, true), FormatRate(s.failures_side, s.n_side),
                      FormatRate(s.failures_other, s.n_other), s.gain);
  }
  md += "\n## A depth-2 decision tree\n\n";
  FormatTree(table, GrowTree(table, failed, 2, std::max<int64_t>(5, n / 50)), 0, &md);
  md += "\n## Failure modes\n\n";
  const std::vector<FailureMode> modes = FindFailureModes(table, failed);
  int64_t in_modes = 0;
  for (const FailureMode& mode : modes) in_modes += static_cast<int64_t>(mode.members.size());
  md += fmt::format(
      "The failures fall into {} (the failure-rich leaves of a depth-3 tree that "
      "hold at least 10 % of them); {} of {} failures are in one.\n\n",
      modes.size() == 1 ? std::string("one mode") : fmt::format("{} modes", modes.size()), in_modes,
      failures);
  md +=
      "| mode | where | fail there | mean of the top features | representative |\n"
      "|---|---|---|---|---|\n";
  for (size_t m = 0; m < modes.size(); ++m) {
    const FailureMode& mode = modes[m];
    std::string means;
    for (size_t i = 0; i < splits.size() && i < 3; ++i) {
      means += fmt::format("{}{} = {}", means.empty() ? "" : ", ", table.names[splits[i].feature],
                           FormatNumber(mode.mean[splits[i].feature]));
    }
    const ReportRecord& rep = records[mode.representative];
    std::string picture;  // the saved scene and its picture, linked as the caller gave them
    if (!rep.saved_scene.empty()) {
      const size_t slash = rep.saved_scene.rfind('/'), dot = rep.saved_scene.rfind('.');
      const bool has_extension =
          dot != std::string::npos && (slash == std::string::npos || dot > slash);
      const std::string stem = has_extension ? rep.saved_scene.substr(0, dot) : rep.saved_scene;
      picture = fmt::format(" [scene]({}) ![index {}]({})", FormatLinkTarget(rep.saved_scene),
                            rep.index, FormatLinkTarget(stem + ".png"));
    }
    md += fmt::format("| {} | {} | {} | {} | index {} (line {}, {}){} |\n", m + 1, mode.description,
                      FormatRate(static_cast<int64_t>(mode.members.size()), mode.n), means,
                      rep.index, rep.line, rep.outcome, picture);
  }
  md += "\n## Outcomes by feature (quantile bins)\n\n";
  for (size_t i = 0; i < splits.size() && i < 3; ++i) {
    const int f = splits[i].feature;
    std::vector<std::pair<double, bool>> values;
    for (size_t r = 0; r < records.size(); ++r) {
      if (!std::isnan(table.rows[r][f])) values.emplace_back(table.rows[r][f], failed[r]);
    }
    std::sort(values.begin(), values.end());
    md += fmt::format("**{}**\n\n| range | episodes | fail |\n|---|---|---|\n", table.names[f]);
    constexpr int kBins = 5;
    for (int b = 0; b < kBins; ++b) {
      const size_t lo = values.size() * b / kBins, hi = values.size() * (b + 1) / kBins;
      if (lo >= hi) continue;
      int64_t k = 0;
      for (size_t v = lo; v < hi; ++v) k += values[v].second;
      md += fmt::format("| {} … {} | {} | {} |\n", FormatNumber(values[lo].first),
                        FormatNumber(values[hi - 1].first), hi - lo,
                        FormatRate(k, static_cast<int64_t>(hi - lo)));
    }
    md += "\n";
  }
  // The error table by scene coordinate, for records drawn at coordinates.
  size_t d = 0;
  for (const auto& r : records) d = std::max(d, r.coordinates.size());
  if (d > 0) {
    md +=
        "## Outcomes by scene coordinate (failure rate in fifths of [0, 1))\n\n"
        "| coordinate | 0–0.2 | 0.2–0.4 | 0.4–0.6 | 0.6–0.8 | 0.8–1 |\n|---|---|---|---|---|---|\n";
    for (size_t j = 0; j < d; ++j) {
      int64_t k[5] = {0}, m[5] = {0};
      for (size_t r = 0; r < records.size(); ++r) {
        if (j >= records[r].coordinates.size()) continue;
        const int b = std::clamp(static_cast<int>(records[r].coordinates[j] * 5), 0, 4);
        ++m[b];
        k[b] += failed[r];
      }
      md += fmt::format("| u[{}] |", j);
      for (int b = 0; b < 5; ++b) {
        md += m[b] ? fmt::format(" {:.0f} % of {} |", 100 * Rate(k[b], m[b]), m[b]) : " – |";
      }
      md += "\n";
    }
    md += "\n(`prs check FILE --coordinates` names u[j].)\n";
  }
  if (svg && !options.svg_path.empty()) {
    // Against the strongest split's feature, one that is not a function of it (Cube-t.x is
    // Cube.x shifted when the table is fixed: a diagonal line) and that best splits its sides.
    const int second = ChooseSecondPlotFeature(table, failed, splits);
    if (second >= 0) {
      *svg = FormatScatterSvg(table, failed, top.feature, second, &top);
      // The plot lies beside the report, so its file name is the link.
      const std::string file = options.svg_path.substr(options.svg_path.rfind('/') + 1);
      md += fmt::format("\n## The two most separating features\n\n![{} against {}]({})\n",
                        table.names[second], table.names[top.feature], FormatLinkTarget(file));
    }
  }
  return md;
}

}  // namespace prs::search
