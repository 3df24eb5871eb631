// Campaigns (docs/cluster.md): a test or sample run of N episodes or scenes cut into shards that
// any machine can run alone, from a self-describing directory: the spec and its imports copied
// in, the options, the shard plan. Shards are written atomically with a sidecar that ties them
// to their campaign, so status and merge can tell done from missing, truncated or foreign, and a
// merged campaign equals one machine's run of the same N and seed.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "dataset/dataset.h"
#include "harness/harness.h"
#include "lang/lang.h"

namespace prs::campaign {

/// DIR/campaign.json: everything a shard needs, written once by InitCampaign.
struct CampaignSpec {
  std::string id;         // unique per init: ties shards to this campaign
  std::string kind;       // "test" (episode records), "sample" (scene lines), "search" (records
                          // of a failure search, generation after generation: search_campaign.h),
                          // "estimate" (prs estimate's records, also in generations) or
                          // "dataset" (prs dataset's files: DatasetShardPath)
  std::string main_file;  // the scenario, relative to DIR ("spec/table_cube.prs")
  std::vector<std::string> scenario_words;                  // the FILE -I -p --naive given at init
  std::vector<std::pair<std::string, std::string>> params;  // -p NAME=VALUE
  bool naive = false;
  std::string sampler = "rejection";  // "partial-rejection" or "gibbs" (sampling/)
  int64_t max_attempts = 10'000;
  uint64_t seed = 0;
  uint64_t count = 0;
  uint64_t shard_size = 1000;
  std::string controller;  // test: a built-in controller, or
  std::string exec;        // test: an --exec command
  double timeout_s = 60;
  bool persistent = false;         // test, search: --exec started once per worker thread
  double startup_timeout_s = 120;  // its --startup-timeout
  std::string perception;          // test, search, estimate: table-cube's --perception CMD
  std::string spec_hash;           // search::CalcSpecHash of the copied program
  std::string version;             // the prs that made it
  // kind "search": the strategy ("ce", "anneal", "random") and the generation size; count is
  // the budget. Shards never straddle generations: each generation is cut on its own.
  std::string strategy;
  uint64_t batch = 0;
  // kind "estimate": the size of each generation (search::CalcEstimateLayout); count is the
  // budget. Its shards never straddle generations either.
  std::vector<uint64_t> generation_sizes;
  // --stable: the simulated seconds of the physics check (0: off), and its tolerances.
  double stable_s = 0;
  double stable_move_m = 0.01;
  double stable_turn_deg = 5;
  // --settle: the most simulated seconds scenes get to come to rest (0: off).
  double settle_s = 0;
  // kind "dataset": prs dataset's options (its dir unused), the cameras named at init (scene 0
  // of the seed's), so that every shard looks through the same ones.
  dataset::DatasetOptions dataset;

  uint64_t shards() const;
  /// The scenes (episodes) of shard k: [first, first + size).
  uint64_t first(uint64_t k) const;
  uint64_t size(uint64_t k) const;
  /// Search and estimate campaigns: the generation of shard k, and the shards of generation
  /// g (test and sample campaigns are one generation).
  uint64_t generation(uint64_t k) const;
  uint64_t generations() const;
  std::vector<uint64_t> generation_shards(uint64_t g) const;
  /// Whether each generation is planned from the records of the ones before (a search or an
  /// estimate), so that generation g's shards wait for generation g - 1's.
  bool planned() const { return kind == "search" || kind == "estimate"; }
  /// The episodes of each generation.
  std::vector<uint64_t> sizes() const;
};

/// Thrown with a message a user can act on (it names the file and what to do).
class CampaignError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Creates DIR (which must not exist or be empty): copies every source file of `program` into
/// DIR/spec/ (flat; two files of one name are an error), then writes DIR/campaign.json
/// atomically. Fills spec.id, spec.main_file, spec.spec_hash and, for a search with batch 0,
/// the batch `prs search` would pick. Throws CampaignError (also for a search of a program
/// that draws nothing at random, or an unknown strategy).
CampaignSpec InitCampaign(const std::string& dir, const lang::CompiledProgram& program,
                          CampaignSpec spec);

/// The sampling options the campaign's shards run with (max attempts, region or naive mode).
sampling::SampleOptions MakeSampleOptions(const CampaignSpec& spec);

/// Reads DIR/campaign.json. Throws CampaignError for a missing or malformed file.
CampaignSpec ReadCampaign(const std::string& dir);

/// Compiles DIR's copy of the scenario and checks it is the one init saw (the spec hash).
/// Throws CampaignError (with the rendered diagnostics on compile errors).
std::unique_ptr<lang::CompiledProgram> CompileCampaign(const std::string& dir,
                                                       const CampaignSpec& spec);

/// DIR/shards/shard-KKKKK.jsonl and its sidecar .done.json.
std::string ShardPath(const std::string& dir, uint64_t k);

/// A dataset campaign's shard k: DIR/shards/shard-KKKKK, a dataset (docs/dataset.md) of its
/// scenes, beside the shard's lines (their scene lines) and sidecar, written after it.
std::string DatasetShardPath(const std::string& dir, uint64_t k);

/// Where a shard stands, from its files alone.
struct ShardStatus {
  enum class State { kDone, kMissing, kRunning, kBad } state = State::kMissing;
  std::string why;  // for kBad: what is wrong; for kRunning: the partial file
};
ShardStatus CheckShard(const std::string& dir, const CampaignSpec& spec, uint64_t k);

/// Writes shard k's lines atomically (PATH.partial, fsync, rename) and then its sidecar
/// (campaign id, spec hash, version, lines, bytes, checksum). Re-running a shard rewrites both.
void WriteShard(const std::string& dir, const CampaignSpec& spec, uint64_t k,
                const std::vector<std::string>& lines);

/// Runs shard k: the episodes (kind "test", with `factory`), scenes (kind "sample") or searched
/// episodes (kind "search", from its generation's plan: search_campaign.h) of its range, on
/// `threads` threads, and writes it. Throws CampaignError for a shard index out of range or a
/// search generation that cannot start yet, and what harness::RunEpisodes /
/// sampling::SampleBatch throw; std::invalid_argument when the spec asks for --stable or --settle
/// and `hooks` has no scene test.
struct ShardHooks {
  /// Gets each distinct warning of the episodes once (harness::RunOptions::on_warning).
  std::function<void(const std::string&)> on_warning;
  /// The physics check the spec asks for (stable_s > 0 or settle_s > 0), made above this
  /// stage, which does not simulate: sim::MakeStabilityTest or sim::MakeSettleTest.
  sampling::SceneTest accept;
};
void RunShard(const std::string& dir, const CampaignSpec& spec,
              const lang::CompiledProgram& program, uint64_t k,
              const harness::ControllerFactory* factory, int threads,
              const std::atomic<bool>* cancel, const ShardHooks& hooks = {});

/// A dataset campaign's shards merged into the dataset `out` (dataset::MergeDatasets): the
/// files of one `prs dataset` run over the campaign's range. Throws CampaignError naming the
/// shards that are not done.
void MergeDatasetShards(const std::string& dir, const CampaignSpec& spec, const std::string& out);

/// The lines of every done shard in index order. Throws CampaignError naming the shards that
/// are not done, unless `partial` (then those are skipped and listed in *skipped).
std::vector<std::string> MergeShards(const std::string& dir, const CampaignSpec& spec, bool partial,
                                     std::vector<uint64_t>* skipped);

}  // namespace prs::campaign
