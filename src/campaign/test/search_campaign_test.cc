// Search campaigns: generations cut into shards, run shard by shard in any order within a
// generation and on any thread count, give exactly one machine's search; a later generation
// waits for the one before it; a plan on disk that the replay contradicts is refused.
#include "campaign/search_campaign.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "campaign/slurm.h"
#include "campaign/test/campaign_dir.h"
#include "harness/registry.h"
#include "sampling/test/scene_checks.h"

namespace prs::campaign {
namespace {

namespace fs = std::filesystem;

TEST(SearchShardPlanTest, GenerationsAreCutOneByOne) {
  CampaignSpec spec;
  spec.kind = "search";
  spec.count = 50;
  spec.batch = 20;      // generations of 20, 20, 10
  spec.shard_size = 8;  // 3 shards per full generation: 8, 8, 4
  EXPECT_EQ(spec.generations(), 3u);
  ASSERT_EQ(spec.shards(), 8u);
  const std::vector<uint64_t> firsts = {0, 8, 16, 20, 28, 36, 40, 48};
  const std::vector<uint64_t> sizes = {8, 8, 4, 8, 8, 4, 8, 2};
  for (uint64_t k = 0; k < spec.shards(); ++k) {
    EXPECT_EQ(spec.first(k), firsts[k]) << k;
    EXPECT_EQ(spec.size(k), sizes[k]) << k;
  }
  EXPECT_EQ(spec.generation(5), 1u);
  EXPECT_EQ(spec.generation(7), 2u);
  EXPECT_EQ(spec.generation_shards(2), (std::vector<uint64_t>{6, 7}));
  EXPECT_EQ(spec.generation_shards(1), (std::vector<uint64_t>{3, 4, 5}));
}

class SearchCampaignTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = MakeTestCampaignDir();
    program_ = sampling::testing_checks::CompileExample("table_cube.prs");
    factory_ = [] { return harness::MakePlantedController(harness::PlantedOnePercent()); };
  }
  void TearDown() override { fs::remove_all(dir_); }

  CampaignSpec Init(const std::string& strategy) {
    CampaignSpec spec;
    spec.kind = "search";
    spec.strategy = strategy;
    spec.seed = 11;
    spec.count = 90;
    spec.batch = 30;
    spec.shard_size = 12;  // 3 generations of 3 shards (12, 12, 6)
    spec.controller = "planted-1-percent";
    spec.version = "test";
    return InitCampaign(dir_, *program_, spec);
  }

  std::string dir_;
  std::unique_ptr<lang::CompiledProgram> program_;
  harness::ControllerFactory factory_;
};

TEST_F(SearchCampaignTest, ShardsMergeIntoOneMachinesSearch) {
  for (const char* strategy : {"ce", "anneal", "random"}) {
    fs::remove_all(dir_);
    const CampaignSpec spec = Init(strategy);
    const auto program = CompileCampaign(dir_, spec);
    // Within a generation, any order and any thread count.
    for (uint64_t g = 0; g < spec.generations(); ++g) {
      const std::vector<uint64_t> shards = spec.generation_shards(g);
      for (auto it = shards.rbegin(); it != shards.rend(); ++it) {
        RunShard(dir_, spec, *program, *it, &factory_, 1 + static_cast<int>(*it % 2), nullptr);
      }
    }
    EXPECT_TRUE(PlanSearchStep(dir_, spec, *program).finished);
    const std::vector<std::string> merged = MergeShards(dir_, spec, false, nullptr);

    search::SearchOptions options = MakeSearchOptions(spec);
    options.run.threads = 2;
    const search::SearchSummary single = search::RunSearch(*program_, factory_, options);
    ASSERT_EQ(merged.size(), single.records.size()) << strategy;
    for (size_t i = 0; i < merged.size(); ++i) {
      auto a = nlohmann::json::parse(merged[i]);
      auto b = nlohmann::json::parse(harness::FormatRecordJson(single.records[i]));
      a.erase("wall_s");
      b.erase("wall_s");
      ASSERT_EQ(a, b) << strategy << " record " << i;
    }
  }
}

TEST_F(SearchCampaignTest, ALaterGenerationWaitsForTheOneBefore) {
  const CampaignSpec spec = Init("ce");
  const auto program = CompileCampaign(dir_, spec);
  SlurmQueue no_queue;
  no_queue.available = true;
  std::vector<ShardState> states = DescribeShards(dir_, spec, no_queue);
  EXPECT_EQ(states[0].kind, ShardState::Kind::kMissing);  // generation 0 can run now
  EXPECT_EQ(states[3].kind, ShardState::Kind::kWaiting);
  EXPECT_EQ(FindShardsToResubmit(states), (std::vector<uint64_t>{0, 1, 2}));
  try {
    RunShard(dir_, spec, *program, 4, &factory_, 1, nullptr);
    ADD_FAILURE() << "a shard of generation 1 ran before generation 0";
  } catch (const CampaignError& error) {
    EXPECT_NE(std::string(error.what()).find("run that generation's shards first (0, 1, 2)"),
              std::string::npos)
        << error.what();
  }
  for (uint64_t k : {0, 1}) RunShard(dir_, spec, *program, k, &factory_, 1, nullptr);
  SearchStep step = PlanSearchStep(dir_, spec, *program);
  EXPECT_FALSE(step.finished);
  EXPECT_EQ(step.generation, 0u);
  EXPECT_EQ(step.unfinished, (std::vector<uint64_t>{2}));
  RunShard(dir_, spec, *program, 2, &factory_, 1, nullptr);
  step = PlanSearchStep(dir_, spec, *program);
  EXPECT_EQ(step.generation, 1u);
  EXPECT_EQ(step.unfinished, (std::vector<uint64_t>{3, 4, 5}));
  EXPECT_TRUE(fs::exists(GenerationPlanPath(dir_, 1)));
  states = DescribeShards(dir_, spec, no_queue);
  EXPECT_EQ(states[4].kind, ShardState::Kind::kMissing);
  EXPECT_EQ(states[6].kind, ShardState::Kind::kWaiting);

  // A plan on disk that the replay contradicts, and one that is not a plan.
  auto plan = nlohmann::json::parse(std::ifstream(GenerationPlanPath(dir_, 1)));
  plan["mean"][0] = 0.123;
  std::ofstream(GenerationPlanPath(dir_, 1)) << plan.dump() << "\n";
  EXPECT_THROW(PlanSearchStep(dir_, spec, *program), CampaignError);
  std::ofstream(GenerationPlanPath(dir_, 1)) << "{\"generation\": 1}\n";
  try {
    RunShard(dir_, spec, *program, 3, &factory_, 1, nullptr);
    ADD_FAILURE();
  } catch (const CampaignError& error) {
    EXPECT_NE(std::string(error.what()).find("is not generation 1's plan"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace prs::campaign
