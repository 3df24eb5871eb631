// Estimate campaigns: prs estimate's generations cut into shards, run shard by shard in any
// order within a generation and on any thread count, merge into exactly one machine's records
// (weights included) and estimate; a merge before every generation is done is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "campaign/search_campaign.h"
#include "campaign/test/campaign_dir.h"
#include "harness/registry.h"
#include "sampling/test/scene_checks.h"

namespace prs::campaign {
namespace {

namespace fs = std::filesystem;

// A record's line without its wall-clock time, the one field two machines differ in.
std::string WithoutWallTime(const std::string& line) {
  return std::regex_replace(line, std::regex("\"wall_s\":[^,]*,"), "");
}

class EstimateCampaignTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = MakeTestCampaignDir();
    program_ = sampling::testing_checks::CompileExample("table_cube.prs");
  }
  void TearDown() override { fs::remove_all(dir_); }

  CampaignSpec Init(const std::string& controller, uint64_t budget) {
    fs::remove_all(dir_);
    CampaignSpec spec;
    spec.kind = "estimate";
    spec.seed = 7;
    spec.count = budget;
    spec.shard_size = 37;  // cuts most generations unevenly
    spec.controller = controller;
    spec.version = "test";
    return InitCampaign(dir_, *program_, spec);
  }

  std::string dir_;
  std::unique_ptr<lang::CompiledProgram> program_;
};

TEST(EstimateLayoutTest, TheBudgetSplitOfTheDocs) {
  // docs/search.md: of 2,000 episodes on Table-Cube (11 coordinates), the first search 400 (20
  // generations of 20), the probe 88 (8 per coordinate), the second search 200 (10 of 20), the
  // exploration 200, the walks 192 (12 rounds of 16 chains) and the sampling 920.
  const std::vector<int64_t> sizes = search::CalcEstimateLayout(2000, 11);
  std::vector<int64_t> expected(20, 20);
  expected.push_back(88);
  expected.insert(expected.end(), 10, 20);
  expected.push_back(200);
  expected.insert(expected.end(), 12, 16);
  expected.push_back(920);
  EXPECT_EQ(sizes, expected);
  // A budget too small to probe 11 coordinates with 4 failures each: no probe generation.
  const std::vector<int64_t> small = search::CalcEstimateLayout(400, 11);
  int64_t total = 0;
  for (int64_t s : small) total += s;
  EXPECT_EQ(total, 400);
  // The searches 80 (4 of 20) and 40 (2 of 20); the exploration 40; 2 rounds of 16; the rest.
  EXPECT_EQ(small.size(), 4u + 2 + 1 + 2 + 1);
  EXPECT_EQ(small.back(), 400 - 120 - 40 - 32);
}

TEST_F(EstimateCampaignTest, ShardsMergeIntoOneMachinesRecordsAndEstimate) {
  // 1 %: enough failures for every phase; 1 per mille at 600 episodes: few failures, so the
  // later phases draw the sampling proposal instead of exploring and walking.
  for (const char* controller : {"planted-1-percent", "planted-1-permille"}) {
    SCOPED_TRACE(controller);
    const CampaignSpec spec = Init(controller, 600);
    const CampaignSpec read = ReadCampaign(dir_);
    EXPECT_EQ(read.generation_sizes, spec.generation_sizes);
    const auto program = CompileCampaign(dir_, spec);
    const harness::ControllerFactory factory = [&] {
      return harness::MakePlantedController(std::string(controller) == "planted-1-percent"
                                                ? harness::PlantedOnePercent()
                                                : harness::PlantedOnePermille());
    };
    for (uint64_t g = 0; g < spec.generations(); ++g) {
      const std::vector<uint64_t> shards = spec.generation_shards(g);
      for (auto it = shards.rbegin(); it != shards.rend(); ++it) {
        RunShard(dir_, spec, *program, *it, &factory, 1 + int(*it % 2), nullptr);
      }
    }
    EXPECT_TRUE(PlanSearchStep(dir_, spec, *program).finished);
    const EstimateMerge merged = MergeEstimate(dir_, spec, *program);

    search::EstimateOptions options = MakeEstimateOptions(spec);
    options.run.threads = 2;
    std::vector<std::string> single;
    options.on_record = [&](const harness::EpisodeRecord& record) {
      single.push_back(harness::FormatRecordJson(record));
    };
    const search::EstimateSummary one = search::RunEstimate(*program_, factory, options);
    ASSERT_EQ(merged.lines.size(), single.size());
    for (size_t i = 0; i < single.size(); ++i) {
      ASSERT_EQ(WithoutWallTime(merged.lines[i]), WithoutWallTime(single[i])) << "line " << i;
    }
    ASSERT_EQ(merged.summary.estimate.outcomes.size(), one.estimate.outcomes.size());
    for (size_t i = 0; i < one.estimate.outcomes.size(); ++i) {
      EXPECT_EQ(merged.summary.estimate.outcomes[i].p, one.estimate.outcomes[i].p);
      EXPECT_EQ(merged.summary.estimate.outcomes[i].ci_high, one.estimate.outcomes[i].ci_high);
    }
    EXPECT_EQ(merged.summary.estimate.upper_bound, one.estimate.upper_bound);
    EXPECT_GT(merged.summary.estimate.episodes, 0);
  }
}

TEST_F(EstimateCampaignTest, AMergeNeedsEveryGeneration) {
  const CampaignSpec spec = Init("planted-1-percent", 400);
  const auto program = CompileCampaign(dir_, spec);
  const harness::ControllerFactory factory = [] {
    return harness::MakePlantedController(harness::PlantedOnePercent());
  };
  for (uint64_t k : spec.generation_shards(0))
    RunShard(dir_, spec, *program, k, &factory, 1, nullptr);
  try {
    MergeEstimate(dir_, spec, *program);
    ADD_FAILURE() << "merged an estimate with generations not run";
  } catch (const CampaignError& error) {
    EXPECT_NE(std::string(error.what()).find("generation 1's shards"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(MergeShards(dir_, spec, true, nullptr), CampaignError);
  // A plan on disk the replay contradicts: the shards ran from it, so no weights are given.
  for (uint64_t g = 1; g < spec.generations(); ++g) {
    for (uint64_t k : spec.generation_shards(g))
      RunShard(dir_, spec, *program, k, &factory, 1, nullptr);
  }
  auto plan = nlohmann::json::parse(std::ifstream(GenerationPlanPath(dir_, 2)));
  plan["mean"][0] = plan["mean"][0].get<double>() / 2;
  std::ofstream(GenerationPlanPath(dir_, 2)) << plan.dump() << "\n";
  try {
    MergeEstimate(dir_, spec, *program);
    ADD_FAILURE() << "merged an estimate whose plan on disk differs from the replay";
  } catch (const CampaignError& error) {
    EXPECT_NE(std::string(error.what()).find("generation-0002.json differs"), std::string::npos)
        << error.what();
  }
  // A budget too small to adapt and sample is refused at init, as by prs estimate.
  fs::remove_all(dir_);
  CampaignSpec tiny = spec;
  tiny.count = 100;
  EXPECT_THROW(InitCampaign(dir_, *program_, tiny), CampaignError);
}

}  // namespace
}  // namespace prs::campaign
