// Outcome names, the outcome table (the paper's Table III) and the JSON Lines records.
#include <algorithm>
#include <cmath>
#include <map>

#include "harness/harness.h"

namespace prs::harness {

bool IsOutcomeName(const std::string& name) {
  constexpr size_t kMaxLength = 64;
  if (name.empty() || name.size() > kMaxLength || name.front() == '-' || name.back() == '-') {
    return false;
  }
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    const bool ok =
        (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || (c == '-' && name[i - 1] != '-');
    if (!ok) return false;
  }
  return true;
}

std::vector<OutcomeRow> TabulateOutcomes(const std::vector<EpisodeRecord>& records) {
  std::map<std::string, int64_t> counts;
  for (const EpisodeRecord& record : records) ++counts[record.result.outcome];
  std::vector<OutcomeRow> rows;
  for (const auto& [outcome, count] : counts) {
    rows.push_back({outcome, count, double(count) / double(records.size())});
  }
  // std::map gave name order, so a stable sort leaves ties by name.
  std::stable_sort(rows.begin(), rows.end(), [](const OutcomeRow& a, const OutcomeRow& b) {
    const bool a_success = a.outcome == "success", b_success = b.outcome == "success";
    if (a_success != b_success) return a_success;
    return a.count > b.count;
  });
  return rows;
}

std::string FormatRecordJson(const EpisodeRecord& record) {
  nlohmann::ordered_json line;
  line["seed"] = record.seed;
  line["index"] = record.index;
  line["outcome"] = record.result.outcome;
  line["detail"] = record.result.detail;
  if (record.result.score) line["score"] = *record.result.score;
  line["wall_s"] = record.wall_s;
  line["extra"] = nlohmann::ordered_json::parse(
      record.result.extra.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  if (!record.coordinates.empty()) line["coordinates"] = record.coordinates;
  if (!record.spec.empty()) {
    line["spec"] = record.spec;
    line["scene_options"] = record.scene_options;
  }
  if (!record.search.is_null()) line["search"] = record.search;
  if (!record.replay.is_null()) line["replay"] = record.replay;
  if (!record.features.empty()) {
    nlohmann::ordered_json features = nlohmann::ordered_json::object();
    for (const auto& [name, value] : record.features) features[name] = value;
    line["features"] = std::move(features);
  }
  if (!record.regenerate.empty()) line["regenerate"] = record.regenerate;
  if (!record.saved_scene.empty()) line["saved_scene"] = record.saved_scene;
  // Controllers may send any bytes; invalid UTF-8 becomes U+FFFD instead of an exception.
  return line.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string SceneOptionsOf(const std::vector<std::string>& scenario_words) {
  std::string options;
  for (size_t i = 1; i < scenario_words.size(); ++i) {
    if (scenario_words[i] == "-I" || scenario_words[i] == "-p") {
      ++i;  // and its value: the fingerprint holds the program's files and parameters
      continue;
    }
    if (!options.empty()) options += ' ';
    options += scenario_words[i];
  }
  return options;
}

std::string QuoteForShell(const std::string& word) {
  constexpr char kPlain[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./+,=:@%";
  if (!word.empty() && word.find_first_not_of(kPlain) == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string FormatRegenerateCommand(const std::vector<std::string>& scenario_args, uint64_t seed,
                                    uint64_t index) {
  std::string command = "prs sample";
  for (const std::string& arg : scenario_args) {
    command += ' ';
    command += QuoteForShell(arg);
  }
  return command + " -s " + std::to_string(seed) + " --start " + std::to_string(index) + " -n 1";
}

}  // namespace prs::harness
