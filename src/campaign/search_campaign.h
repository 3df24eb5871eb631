// Search and estimate campaigns (docs/cluster.md): a failure search or a failure-probability
// estimate (docs/search.md) whose generations run as campaign shards, each generation one job
// array. Generation g's plan (search::GenerationPlan) is a pure function of the earlier
// generations' records, so it is computed by replaying the search (the estimate) from the
// shards on disk once they are all done, and written to DIR/search/generation-G.json for the
// shards to read; the merged records equal one machine's `prs search` (`prs estimate -o`) of
// the same budget and seed.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "campaign/campaign.h"
#include "search/estimate.h"
#include "search/search.h"

namespace prs::campaign {

/// The search a search campaign stands for: its strategy, budget (count), batch, seed and
/// sampling options; no regenerate commands (searched scenes carry their coordinates).
search::SearchOptions MakeSearchOptions(const CampaignSpec& spec);

/// The estimate an estimate campaign stands for: its budget (count), seed and sampling options.
search::EstimateOptions MakeEstimateOptions(const CampaignSpec& spec);

/// DIR/search/generation-G.json.
std::string GenerationPlanPath(const std::string& dir, uint64_t g);

/// Generation g's plan, or nullopt while it is not written. Throws CampaignError for a file that
/// is not a plan.
std::optional<search::GenerationPlan> ReadGenerationPlan(const std::string& dir, uint64_t g);

/// Where a search or estimate campaign stands: the first generation that is not done and its shards
/// that are not done (its plan now written), or finished.
struct SearchStep {
  bool finished = false;
  uint64_t generation = 0;
  std::vector<uint64_t> unfinished;
};

/// Replays the search (estimate) over the generations whose shards are all done (checking each
/// written plan against the replay), writes the plan of the first generation that is not, and
/// returns it. Throws CampaignError for a plan on disk that the replay contradicts or a done shard
/// that does not read back as records.
SearchStep PlanSearchStep(const std::string& dir, const CampaignSpec& spec,
                          const lang::CompiledProgram& program);

/// The records of search or estimate shard k (its generation planned first when the earlier
/// generations are done), as JSON lines. Throws CampaignError when an earlier generation is not
/// done.
std::vector<std::string> RunSearchShard(const std::string& dir, const CampaignSpec& spec,
                                        const lang::CompiledProgram& program, uint64_t k,
                                        const harness::ControllerFactory& factory, int threads,
                                        const std::atomic<bool>* cancel, const ShardHooks& hooks);

/// An estimate campaign's merged records, as `prs estimate -o` writes them (the adaptation's in
/// index order, then the weighted ones with their weights), and the estimate.
struct EstimateMerge {
  std::vector<std::string> lines;
  search::EstimateSummary summary;
};

/// Replays the estimate over every generation's shards and gives the weighted records their
/// weights. Throws CampaignError naming the generations not done (or a shard that does not read
/// back as records).
EstimateMerge MergeEstimate(const std::string& dir, const CampaignSpec& spec,
                            const lang::CompiledProgram& program);

}  // namespace prs::campaign
