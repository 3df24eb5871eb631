// Campaigns on Slurm, the parts that need no cluster: the job-array script, squeue's lines, and
// each shard's state from its files, its submissions and the queue (a real single-node Slurm
// runs the whole thing in tests/slurm/campaign_test.sh).
#include "campaign/slurm.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "campaign/test/campaign_dir.h"
#include "sampling/test/scene_checks.h"

namespace prs::campaign {
namespace {

namespace fs = std::filesystem;

TEST(SqueueLinesTest, KeepTheCampaignsTasksAndTheLatestJobPerShard) {
  const std::string text =
      "14|4|COMPLETED|None\n"
      "9|8|PENDING|JobArrayTaskLimit\n"
      "16|6|RUNNING|None\n"
      "16|4|PENDING|Priority\n"  // shard 4 submitted again in job 16: the later job wins
      "77|1|RUNNING|None\n"      // another campaign's job of the same name
      "9|N/A|PENDING|None\n"     // not an array task
      "garbage\n"
      "  \n";
  const auto tasks = ParseSqueueLines(text, {{"9", 0}, {"14", 0}, {"16", 0}});
  ASSERT_EQ(tasks.size(), 3u);
  EXPECT_EQ(tasks.at(8).state, "PENDING");
  EXPECT_EQ(tasks.at(8).reason, "JobArrayTaskLimit");
  EXPECT_TRUE(tasks.at(8).active());
  EXPECT_EQ(tasks.at(6).job_id, "16");
  EXPECT_EQ(tasks.at(4).job_id, "16");
  EXPECT_EQ(tasks.at(4).state, "PENDING");
  EXPECT_FALSE(tasks.count(1));
}

TEST(SqueueLinesTest, JobIdsCompareAsNumbers) {
  const auto tasks =
      ParseSqueueLines("10|2|CANCELLED|None\n9|2|RUNNING|None\n", {{"9", 0}, {"10", 0}});
  ASSERT_EQ(tasks.count(2), 1u);
  EXPECT_EQ(tasks.at(2).job_id, "10");
  EXPECT_FALSE(tasks.at(2).active());
}

// Arrays past Slurm's MaxArraySize: indices are counted from each array's first shard.
TEST(SqueueLinesTest, IndicesAreShardsMinusTheArraysOffset) {
  const auto tasks = ParseSqueueLines("12|0|RUNNING|None\n12|7|PENDING|Priority\n", {{"12", 2000}});
  ASSERT_EQ(tasks.size(), 2u);
  EXPECT_EQ(tasks.at(2000).index, 0u);
  EXPECT_EQ(tasks.at(2007).state, "PENDING");
  EXPECT_EQ(tasks.at(2007).index, 7u);
}

TEST(SplitIntoArraysTest, EachArraysIndicesStayBelowMaxArraySize) {
  using Arrays = std::vector<std::vector<uint64_t>>;
  EXPECT_EQ(SplitIntoArrays({0, 1, 2, 5}, 1001), (Arrays{{0, 1, 2, 5}}));
  EXPECT_EQ(SplitIntoArrays({0, 1, 2, 3, 4}, 3), (Arrays{{0, 1, 2}, {3, 4}}));
  EXPECT_EQ(SplitIntoArrays({1000, 1001, 2500}, 1001), (Arrays{{1000, 1001}, {2500}}));
  EXPECT_EQ(SplitIntoArrays({}, 1001), Arrays{});
}

class SlurmCampaignTest : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = MakeTestCampaignDir();
    program_ = sampling::testing_checks::CompileExample("table_cube.prs");
    CampaignSpec spec;
    spec.kind = "sample";
    spec.seed = 3;
    spec.count = 50;
    spec.shard_size = 10;
    spec.version = "test";
    spec_ = InitCampaign(dir_, *program_, spec);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string dir_;
  std::unique_ptr<lang::CompiledProgram> program_;
  CampaignSpec spec_;
};

TEST_F(SlurmCampaignTest, ScriptIsAJobArrayOfTheGivenShards) {
  SlurmOptions options;
  options.prs = "/opt/prs it's/bin/prs";
  options.cpus_per_task = 2;
  options.max_running = 3;
  options.time = "00:10:00";
  const std::string script = FormatSlurmScript(dir_, spec_, {0, 1, 2, 4, 7, 8}, 0, options);
  EXPECT_NE(script.find("#SBATCH --array=0-2,4,7-8%3\n"), std::string::npos) << script;
  EXPECT_NE(script.find("shard=$((0 + SLURM_ARRAY_TASK_ID))\n"), std::string::npos) << script;
  EXPECT_NE(script.find("/logs/slurm-%A_%a.out\n"), std::string::npos) << script;
  const std::string later = FormatSlurmScript(dir_, spec_, {1500, 1501, 1503}, 1500, options);
  EXPECT_NE(later.find("#SBATCH --array=0-1,3%3\n"), std::string::npos) << later;
  EXPECT_NE(later.find("shard=$((1500 + SLURM_ARRAY_TASK_ID))\n"), std::string::npos) << later;
  EXPECT_NE(script.find("#SBATCH --job-name=" + SlurmJobName(spec_) + "\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=2\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --time=00:10:00\n"), std::string::npos);
  EXPECT_EQ(script.find("--partition"), std::string::npos);
  EXPECT_NE(script.find("exec '/opt/prs it'\\''s/bin/prs' campaign run-shard"), std::string::npos)
      << script;
}

TEST_F(SlurmCampaignTest, ShardStatesCombineFilesSubmissionsAndQueue) {
  // Shards 0 and 1 are written; 2..4 were submitted in job 40: 3 is running, 2 was cancelled
  // (its log says so), 4 is gone from the queue.
  for (uint64_t k : {0, 1}) RunShard(dir_, spec_, *program_, k, nullptr, 1, nullptr);
  SlurmSubmission submission;
  submission.number = FindNextSubmissionNumber(dir_);
  EXPECT_EQ(submission.number, 0);
  submission.job_id = "40";
  submission.shards = {2, 3, 4};
  submission.offset = 2;
  submission.options.time = "1:00:00";
  WriteSlurmScript(dir_, submission.number, "#!/bin/bash\n");
  WriteSubmission(dir_, submission);
  EXPECT_EQ(FindNextSubmissionNumber(dir_), 1);
  const auto read = ReadSubmissions(dir_);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].shards, submission.shards);
  EXPECT_EQ(read[0].options.time, "1:00:00");
  EXPECT_EQ(read[0].offset, 2u);
  // Slurm's own message about shard 2 (array index 0); its prs wrote nothing.
  std::ofstream(dir_ + "/logs/slurm-40_0.out") << "slurmstepd: error: *** CANCELLED ***\n\n";

  SlurmQueue queue;
  queue.available = true;
  queue.tasks = ParseSqueueLines("40|1|RUNNING|None\n40|0|CANCELLED|None\n", {{"40", 2}});
  const std::vector<ShardState> states = DescribeShards(dir_, spec_, queue);
  using Kind = ShardState::Kind;
  ASSERT_EQ(states.size(), 5u);
  EXPECT_EQ(states[0].kind, Kind::kDone);
  EXPECT_EQ(states[1].kind, Kind::kDone);
  EXPECT_EQ(states[2].kind, Kind::kFailed);
  EXPECT_NE(states[2].why.find("Slurm job 40_0 ended CANCELLED"), std::string::npos)
      << states[2].why;
  EXPECT_NE(states[3].why.find("Slurm job 40_1 is RUNNING"), std::string::npos) << states[3].why;
  EXPECT_NE(states[2].why.find("*** CANCELLED ***"), std::string::npos) << states[2].why;
  EXPECT_EQ(states[3].kind, Kind::kRunning);
  EXPECT_EQ(states[4].kind, Kind::kFailed);  // submitted, gone from the queue, not written
  EXPECT_EQ(FindShardsToResubmit(states), (std::vector<uint64_t>{2, 4}));

  // Without the queue, a submitted shard's fate is unknown: missing, and resubmitted.
  SlurmQueue unknown;
  unknown.why_not = "squeue is not installed here";
  const std::vector<ShardState> blind = DescribeShards(dir_, spec_, unknown);
  EXPECT_EQ(blind[3].kind, Kind::kMissing);
  EXPECT_NE(blind[3].why.find("squeue is not installed"), std::string::npos) << blind[3].why;
  EXPECT_EQ(FindShardsToResubmit(blind), (std::vector<uint64_t>{2, 3, 4}));

  // A truncated shard is bad and submitted again; a done one never is.
  fs::resize_file(ShardPath(dir_, 1), 10);
  const std::vector<ShardState> after = DescribeShards(dir_, spec_, queue);
  EXPECT_EQ(after[1].kind, Kind::kBad);
  EXPECT_EQ(FindShardsToResubmit(after), (std::vector<uint64_t>{1, 2, 4}));
}

}  // namespace
}  // namespace prs::campaign
