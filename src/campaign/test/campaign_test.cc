// Campaigns: shards run in any order and on any thread count merge into exactly the lines of one
// machine's run; truncated, foreign and missing shards are found; an edited spec is refused.
#include "campaign/campaign.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "campaign/files.h"
#include "campaign/test/campaign_dir.h"
#include "harness/registry.h"
#include "output/scene_json.h"
#include "search/like.h"
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
  run.spec_hash = search::CalcSpecHash(*CompileTableCube());  // as prs test sets it
  run.scene_options = "";
  const harness::RunSummary single = harness::RunEpisodes(*CompileTableCube(), factory, run);
  const std::vector<std::string> merged = MergeShards(dir_, spec, false, nullptr);
  ASSERT_EQ(merged.size(), single.records.size());
  for (size_t i = 0; i < merged.size(); ++i) {
    auto a = nlohmann::json::parse(merged[i]);
    auto b = nlohmann::json::parse(harness::FormatRecordJson(single.records[i]));
    a.erase("wall_s");
    b.erase("wall_s");
    EXPECT_EQ(a, b) << i;
    EXPECT_EQ(a["spec"], spec.spec_hash) << "a campaign's records name their program";
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

// A three-joint arm (a turntable, a shoulder and an elbow) for a scenario of a campaign.
constexpr const char* kArmUrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="column"/><link name="upper"/><link name="lower"/><link name="tip"/>
  <joint name="turn" type="revolute"><parent link="base"/><child link="column"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="column"/><child link="upper"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="tip" type="fixed"><parent link="lower"/><child link="tip"/><origin xyz="0.25 0 0"/></joint>
</robot>
)";

constexpr const char* kArmScenario = R"(
class Table:
    width: 1.2
    length: 0.8
    height: 0.8
class Arm:
    width: 0.1
    length: 0.1
    height: 0.1
    arm: "robots/arm.urdf"
class Cube:
    width: 0.05
    length: 0.05
    height: 0.05
t = Table at V3D(0, 0, 0.4)
a = Arm on (top back t)
c = Cube on t, reachable by a with grasp "any"
)";

TEST_F(CampaignTest, TheUrdfFilesOfItsArmsTravelWithTheCampaign) {
  const fs::path scenario = fs::path(dir_ + "_scenario");
  fs::create_directories(scenario / "robots");
  std::ofstream(scenario / "robots" / "arm.urdf") << kArmUrdf;
  std::ofstream(scenario / "main.prs") << kArmScenario;
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile((scenario / "main.prs").string(), {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  CampaignSpec spec;
  spec.kind = "sample";
  spec.seed = 3;
  spec.count = 6;
  spec.shard_size = 3;
  spec.scenario_words = {"main.prs"};
  spec.version = "test";
  spec = InitCampaign(dir_, *program, spec);
  std::vector<std::string> single;
  sampling::BatchOptions batch;
  batch.seed = 3;
  batch.count = 6;
  sampling::SampleBatch(*program, batch, {.prepare = {}, .consume = [&](sampling::BatchScene&& s) {
                                            single.push_back(output::FormatSceneJson(s.sampled));
                                          }});
  fs::remove_all(scenario);  // the campaign must not need the original files
  EXPECT_TRUE(fs::exists(dir_ + "/spec/robots/arm.urdf"));
  const auto copy = CompileCampaign(dir_, spec);
  for (uint64_t k = 0; k < 2; ++k) RunShard(dir_, spec, *copy, k, nullptr, 1, nullptr);
  EXPECT_EQ(MergeShards(dir_, spec, false, nullptr), single);
  // A changed arm is a changed scenario.
  std::ofstream(dir_ + "/spec/robots/arm.urdf", std::ios::app) << "<!-- edited -->\n";
  EXPECT_THROW(CompileCampaign(dir_, spec), CampaignError);
}

TEST_F(CampaignTest, AFileWithoutAFinalNewlineIsCopiedWhole) {
  // The last line ends without a newline: the copy must keep its last character.
  const fs::path scenario = fs::path(dir_ + "_no_newline.prs");
  const std::string text = "b = Object at V3D(Range(0, 1), 0, 0.5)";
  std::ofstream(scenario) << text;
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile(scenario.string(), {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  CampaignSpec spec;
  spec.kind = "sample";
  spec.count = 2;
  spec.scenario_words = {scenario.string()};
  spec.version = "test";
  spec = InitCampaign(dir_, *program, spec);
  bool ok = false;
  EXPECT_EQ(ReadFileText(dir_ + "/" + spec.main_file, &ok), text);
  EXPECT_NO_THROW(CompileCampaign(dir_, spec));
  fs::remove(scenario);
}

TEST_F(CampaignTest, AnArmFileOutsideTheScenarioIsRefused) {
  const fs::path root = fs::path(dir_ + "_outside");
  fs::create_directories(root / "scenario");
  std::ofstream(root / "arm.urdf") << kArmUrdf;
  std::string text = kArmScenario;
  text.replace(text.find("robots/arm.urdf"), 15, "../arm.urdf");
  std::ofstream(root / "scenario" / "main.prs") << text;
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile((root / "scenario" / "main.prs").string(), {}, diagnostics);
  ASSERT_FALSE(diagnostics.has_errors());
  CampaignSpec spec;
  spec.kind = "sample";
  spec.count = 2;
  spec.shard_size = 1;
  spec.scenario_words = {"main.prs"};
  try {
    InitCampaign(dir_, *program, spec);
    ADD_FAILURE() << "an arm file above the scenario cannot be carried";
  } catch (const CampaignError& e) {
    EXPECT_NE(std::string(e.what()).find("'../arm.urdf' (an arm or a mesh) is not below the scenario's directory"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_)) << "a refused campaign leaves nothing behind";
  fs::remove_all(root);
}

}  // namespace
}  // namespace prs::campaign
