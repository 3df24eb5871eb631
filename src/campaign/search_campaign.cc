// Search and estimate campaigns: the search (estimate) replayed from the shards on disk,
// generation plans written for the shards, a shard's episodes run from its generation's plan,
// and an estimate's records given their weights at the merge.
#include "campaign/search_campaign.h"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "campaign/files.h"

namespace prs::campaign {
namespace fs = std::filesystem;

search::SearchOptions MakeSearchOptions(const CampaignSpec& spec) {
  search::SearchOptions options;
  if (!search::ParseStrategy(spec.strategy, &options.strategy)) {
    throw CampaignError("the campaign's search strategy '" + spec.strategy +
                        "' is not one prs runs (" +
                        fmt::format("{}", fmt::join(search::StrategyNames(), ", ")) + ")");
  }
  options.budget = static_cast<int64_t>(spec.count);
  options.batch = static_cast<int64_t>(spec.batch);
  options.run.sample = MakeSampleOptions(spec);
  options.run.seed = spec.seed;
  options.run.scene_options = harness::SceneOptionsOf(spec.scenario_words);
  return options;
}

search::EstimateOptions MakeEstimateOptions(const CampaignSpec& spec) {
  search::EstimateOptions options;
  options.budget = static_cast<int64_t>(spec.count);
  options.run.sample = MakeSampleOptions(spec);
  options.run.seed = spec.seed;
  options.run.scene_options = harness::SceneOptionsOf(spec.scenario_words);
  return options;
}

std::string GenerationPlanPath(const std::string& dir, uint64_t g) {
  return fmt::format("{}/search/generation-{:04d}.json", dir, g);
}

std::optional<search::GenerationPlan> ReadGenerationPlan(const std::string& dir, uint64_t g) {
  bool ok = false;
  const std::string path = GenerationPlanPath(dir, g);
  const std::string text = ReadFileText(path, &ok);
  if (!ok) return std::nullopt;
  const auto json = nlohmann::json::parse(text, nullptr, false);
  try {
    if (json.is_discarded()) throw std::runtime_error("not JSON");
    search::GenerationPlan plan = search::PlanFromJson(json);
    if (static_cast<uint64_t>(plan.generation) != g) throw std::runtime_error("another generation");
    return plan;
  } catch (const std::exception& error) {
    throw CampaignError(path + " is not generation " + std::to_string(g) + "'s plan (" +
                        error.what() + "); delete it and run prs campaign resume to plan it again");
  }
}

namespace {

// The records of generation g's shards, all done, in index order (and their lines, when
// `lines` is not null).
std::vector<harness::EpisodeRecord> ReadGenerationRecords(
    const std::string& dir, const CampaignSpec& spec, uint64_t g,
    std::vector<std::string>* lines = nullptr) {
  std::vector<harness::EpisodeRecord> records;
  for (uint64_t k : spec.generation_shards(g)) {
    bool ok = false;
    std::stringstream text(ReadFileText(ShardPath(dir, k), &ok));
    int line_number = 0;
    for (std::string line; std::getline(text, line);) {
      ++line_number;
      harness::EpisodeRecord record;
      if (!search::ParseRecordForSearch(line, &record) ||
          record.index != spec.first(k) + uint64_t(line_number - 1)) {
        throw CampaignError(fmt::format("{}:{}: not episode {}'s record; run shard {} again",
                                        ShardPath(dir, k), line_number,
                                        spec.first(k) + uint64_t(line_number - 1), k));
      }
      records.push_back(std::move(record));
      if (lines) lines->push_back(std::move(line));
    }
  }
  return records;
}

// A plan whose episodes are not the ones the campaign cut into shards at init.
void CheckLayout(const CampaignSpec& spec, const search::GenerationPlan& plan) {
  const std::vector<uint64_t> shards = spec.generation_shards(uint64_t(plan.generation));
  if (shards.empty() || spec.first(shards.front()) != plan.start ||
      spec.first(shards.back()) + spec.size(shards.back()) != plan.start + uint64_t(plan.count)) {
    throw CampaignError(fmt::format(
        "generation {} plans episodes {} to {}, which are not the campaign's shards of it: was "
        "the campaign made by another prs? Start a new campaign",
        plan.generation, plan.start, plan.start + uint64_t(plan.count)));
  }
}

// Generation g's plan on disk, or nullopt while it is not written; throws CampaignError when
// it is not the plan replayed from the shards before it (`replayed`) or not where the campaign
// cut generation g's shards.
std::optional<search::GenerationPlan> ReadReplayedPlan(const std::string& dir,
                                                       const CampaignSpec& spec, uint64_t g,
                                                       const search::GenerationPlan& replayed) {
  CheckLayout(spec, replayed);
  std::optional<search::GenerationPlan> written = ReadGenerationPlan(dir, g);
  if (written && search::PlanToJson(*written).dump() != search::PlanToJson(replayed).dump()) {
    throw CampaignError(fmt::format(
        "{} differs from the {} replayed from the shards before it: was it written by another "
        "prs? Start a new campaign",
        GenerationPlanPath(dir, g), spec.kind));
  }
  return written;
}

// The planner a search or estimate campaign replays.
std::unique_ptr<search::GenerationPlanner> MakePlanner(const CampaignSpec& spec,
                                                       const lang::CompiledProgram& program) {
  if (spec.kind == "estimate") {
    return std::make_unique<search::EstimatePlanner>(program, MakeEstimateOptions(spec));
  }
  return std::make_unique<search::SearchPlanner>(program, MakeSearchOptions(spec));
}

bool GenerationDone(const std::string& dir, const CampaignSpec& spec, uint64_t g,
                    std::vector<uint64_t>* unfinished) {
  for (uint64_t k : spec.generation_shards(g)) {
    if (CheckShard(dir, spec, k).state != ShardStatus::State::kDone) unfinished->push_back(k);
  }
  return unfinished->empty();
}

}  // namespace

SearchStep PlanSearchStep(const std::string& dir, const CampaignSpec& spec,
                          const lang::CompiledProgram& program) {
  const std::unique_ptr<search::GenerationPlanner> planner = MakePlanner(spec, program);
  SearchStep step;
  for (uint64_t g = 0; !planner->done(); ++g) {
    const search::GenerationPlan plan = planner->Next();
    const std::optional<search::GenerationPlan> written = ReadReplayedPlan(dir, spec, g, plan);
    std::vector<uint64_t> unfinished;
    if (!written || !GenerationDone(dir, spec, g, &unfinished)) {
      if (!written) {
        std::error_code error;
        fs::create_directories(dir + "/search", error);
        WriteFileAtomically(GenerationPlanPath(dir, g), search::PlanToJson(plan).dump() + "\n");
        unfinished.clear();
        GenerationDone(dir, spec, g, &unfinished);
      }
      step.generation = g;
      step.unfinished = unfinished;
      return step;
    }
    planner->Add(ReadGenerationRecords(dir, spec, g));
  }
  step.finished = true;
  step.generation = spec.generations();
  return step;
}

std::vector<std::string> RunSearchShard(const std::string& dir, const CampaignSpec& spec,
                                        const lang::CompiledProgram& program, uint64_t k,
                                        const harness::ControllerFactory& factory, int threads,
                                        const std::atomic<bool>* cancel, const ShardHooks& hooks) {
  const uint64_t g = spec.generation(k);
  std::optional<search::GenerationPlan> plan = ReadGenerationPlan(dir, g);
  if (!plan) {
    const SearchStep step = PlanSearchStep(dir, spec, program);
    if (step.generation < g) {
      throw CampaignError(fmt::format(
          "shard {} belongs to generation {}, which is planned from the records of generation "
          "{}: run that generation's shards first ({})",
          k, g, step.generation, fmt::join(step.unfinished, ", ")));
    }
    plan = ReadGenerationPlan(dir, g);
  }
  harness::RunOptions run =
      spec.kind == "estimate" ? MakeEstimateOptions(spec).run : MakeSearchOptions(spec).run;
  run.threads = threads;
  run.cancel = cancel;
  run.on_warning = hooks.on_warning;
  run.sample.accept = hooks.accept;
  std::vector<std::string> lines;
  run.on_record = [&](const harness::EpisodeRecord& record) {
    lines.push_back(harness::FormatRecordJson(record));
  };
  search::RunGeneration(program, factory, *plan, run, spec.first(k),
                        static_cast<int64_t>(spec.size(k)));
  return lines;
}

EstimateMerge MergeEstimate(const std::string& dir, const CampaignSpec& spec,
                            const lang::CompiledProgram& program) {
  search::EstimatePlanner planner(program, MakeEstimateOptions(spec));
  std::map<uint64_t, std::string> lines;  // by episode index
  for (uint64_t g = 0; !planner.done(); ++g) {
    const search::GenerationPlan plan = planner.Next();
    std::vector<uint64_t> unfinished;
    if (!GenerationDone(dir, spec, g, &unfinished)) {
      throw CampaignError(fmt::format(
          "the estimate needs every generation's records, and generation {}'s shards {} are not "
          "done: run them (prs campaign status {} says why)",
          g, fmt::join(unfinished, ", "), dir));
    }
    std::vector<std::string> text;
    std::vector<harness::EpisodeRecord> records = ReadGenerationRecords(dir, spec, g, &text);
    for (size_t i = 0; i < records.size(); ++i) lines[records[i].index] = std::move(text[i]);
    // The shards ran from the plan on disk, the weights come from the replay: they must agree.
    if (!ReadReplayedPlan(dir, spec, g, plan)) {
      throw CampaignError(fmt::format(
          "{} is missing, yet generation {}'s shards are done: the weights need the plan they "
          "ran from; start a new campaign",
          GenerationPlanPath(dir, g), g));
    }
    planner.Add(std::move(records));
  }
  EstimateMerge merge;
  merge.summary = planner.Finish();
  // Each record's line as its shard wrote it, with the weighted ones' "search" tag replaced:
  // ordered JSON keeps the fields where they were, so the lines equal one machine's.
  for (const harness::EpisodeRecord& record : merge.summary.records) {
    std::string& line = lines.at(record.index);
    if (record.search.is_object() && record.search.value("strategy", "") == "importance") {
      auto json = nlohmann::ordered_json::parse(line);
      json["search"] = nlohmann::ordered_json::parse(record.search.dump());
      line = json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
    }
    merge.lines.push_back(std::move(line));
  }
  return merge;
}

}  // namespace prs::campaign
