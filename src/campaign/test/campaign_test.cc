// Campaigns: shards run in any order and on any thread count merge into exactly the lines of one
// machine's run; truncated, foreign and missing shards are found; an edited spec is refused.
#include "campaign/campaign.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "campaign/test/campaign_dir.h"
#include "harness/registry.h"
#include "output/scene_json.h"
#include "sampling/batch.h"
#include "sampling/test/scene_checks.h"

namespace prs::campaign {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<lang::CompiledProgram> CompileTableCube() {
  return sampling::testing_checks::CompileExample("table_cube.prs");
}

class CampaignTest : public testing::Test {
 protected:
  void SetUp() override { dir_ = MakeTestCampaignDir(); }
  void TearDown() override { fs::remove_all(dir_); }

  CampaignSpec Init(const std::string& kind, uint64_t count, uint64_t shard_size) {
    CampaignSpec spec;
    spec.kind = kind;
    spec.seed = 5;
    spec.count = count;
    spec.shard_size = shard_size;
    spec.controller = kind == "test" ? "demo-reach" : "";
    spec.scenario_words = {"examples/table_cube.prs"};
    spec.version = "test";
    return InitCampaign(dir_, *CompileTableCube(), spec);
  }

  std::string dir_;
};

TEST_F(CampaignTest, ShardsInAnyOrderMergeIntoOneMachinesScenes) {
  const CampaignSpec spec = Init("sample", 20, 3);
  ASSERT_EQ(spec.shards(), 7u);
  EXPECT_EQ(spec.size(6), 2u);
  const CampaignSpec read = ReadCampaign(dir_);
  EXPECT_EQ(read.id, spec.id);
  const auto program = CompileCampaign(dir_, read);
  for (uint64_t k = 7; k-- > 0;) RunShard(dir_, read, *program, k, nullptr, 1 + k % 2, nullptr);
  RunShard(dir_, read, *program, 3, nullptr, 2, nullptr);  // a re-run changes nothing
  const std::vector<std::string> merged = MergeShards(dir_, read, false, nullptr);
  sampling::BatchOptions batch;
  batch.seed = 5;
  batch.count = 20;
  std::vector<std::string> single;
  sampling::SampleBatch(*CompileTableCube(), batch,
                        {.prepare = {}, .consume = [&](sampling::BatchScene&& s) {
                           single.push_back(output::FormatSceneJson(s.sampled));
                         }});
  EXPECT_EQ(merged, single);
}

TEST_F(CampaignTest, EpisodeRecordsEqualOneMachinesButTheirTimes) {
  const CampaignSpec spec = Init("test", 10, 4);
  const auto program = CompileCampaign(dir_, spec);
  const harness::ControllerFactory factory = harness::MakeDemoReachController;
  for (uint64_t k : {2, 0, 1}) RunShard(dir_, spec, *program, k, &factory, 2, nullptr);
  harness::RunOptions run;
  run.seed = 5;
  run.count = 10;
  run.scenario_args = {"examples/table_cube.prs"};
  const harness::RunSummary single = harness::RunEpisodes(*CompileTableCube(), factory, run);
  const std::vector<std::string> merged = MergeShards(dir_, spec, false, nullptr);
  ASSERT_EQ(merged.size(), single.records.size());
  for (size_t i = 0; i < merged.size(); ++i) {
    auto a = nlohmann::json::parse(merged[i]);
    auto b = nlohmann::json::parse(harness::FormatRecordJson(single.records[i]));
    a.erase("wall_s");
    b.erase("wall_s");
    EXPECT_EQ(a, b) << i;
  }
}

TEST_F(CampaignTest, BadShardsAndAnEditedSpecAreFound) {
  const CampaignSpec spec = Init("sample", 9, 3);
  const auto program = CompileCampaign(dir_, spec);
  for (uint64_t k = 0; k < 3; ++k) RunShard(dir_, spec, *program, k, nullptr, 1, nullptr);
  EXPECT_EQ(CheckShard(dir_, spec, 0).state, ShardStatus::State::kDone);
  // Truncated after it was written.
  fs::resize_file(ShardPath(dir_, 1), fs::file_size(ShardPath(dir_, 1)) / 2);
  EXPECT_EQ(CheckShard(dir_, spec, 1).state, ShardStatus::State::kBad);
  EXPECT_NE(CheckShard(dir_, spec, 1).why.find("truncated"), std::string::npos);
  // From another campaign.
  CampaignSpec other = spec;
  other.id = "another";
  EXPECT_NE(CheckShard(dir_, other, 2).why.find("another campaign"), std::string::npos);
  // Missing, and merging around it.
  fs::remove(ShardPath(dir_, 2));
  fs::remove(ShardPath(dir_, 2) + ".done.json");
  EXPECT_EQ(CheckShard(dir_, spec, 2).state, ShardStatus::State::kMissing);
  EXPECT_THROW(MergeShards(dir_, spec, false, nullptr), CampaignError);
  std::vector<uint64_t> skipped;
  EXPECT_EQ(MergeShards(dir_, spec, true, &skipped).size(), 3u);
  EXPECT_EQ(skipped, (std::vector<uint64_t>{1, 2}));
  EXPECT_THROW(RunShard(dir_, spec, *program, 3, nullptr, 1, nullptr), CampaignError);
  // The spec edited after init.
  std::ofstream(dir_ + "/" + spec.main_file, std::ios::app) << "\n# edited\n";
  EXPECT_THROW(CompileCampaign(dir_, spec), CampaignError);
  // Init refuses a non-empty directory; reading a non-campaign is a clear error.
  EXPECT_THROW(Init("sample", 9, 3), CampaignError);
  try {
    ReadCampaign(dir_ + "/spec");
    ADD_FAILURE();
  } catch (const CampaignError& e) {
    EXPECT_NE(std::string(e.what()).find("prs campaign init"), std::string::npos);
  }
}

}  // namespace
}  // namespace prs::campaign
