// End-to-end tests of `prs campaign`: shards run in any order merge into one machine's run, bad
// shards and requests are named, and the Slurm job script runs exactly the unfinished shards.
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

TEST_F(PrsTest, CampaignShardsMergeIntoOneMachinesRun) {
  const std::string dir = (dir_ / "campaign").string();
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "--controller", "demo-reach",
                  "-n", "40", "--shard-size", "7", "-s", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* k : {"5", "2", "0", "1", "4", "3"}) {
    r = Run({"campaign", "run-shard", dir, k, "--threads", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("6 of 6 done"), std::string::npos) << r.out;
  const std::string merged = (dir_ / "merged.jsonl").string(),
                    single = (dir_ / "single.jsonl").string();
  r = Run({"campaign", "merge", dir, "-o", merged});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"test", Example("table_cube.prs"), "--controller", "demo-reach", "-n", "40", "-s", "3",
           "-o", single});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<json> a = ReadRecords(merged), b = ReadRecords(single);
  for (std::vector<json>* records : {&a, &b}) {
    for (json& record : *records) record.erase("wall_s");
  }
  EXPECT_EQ(a, b);
  // A shard out of range, a truncated shard, and merge refusing an incomplete campaign.
  r = Run({"campaign", "run-shard", dir, "6"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("there is no shard 6"), std::string::npos) << r.err;
  fs::resize_file(dir + "/shards/shard-00002.jsonl", 5);
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("shard 2: bad"), std::string::npos) << r.out;
  r = Run({"campaign", "merge", dir, "-o", merged});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("shards not done: 2"), std::string::npos) << r.err;
  r = Run({"campaign", "status", (dir_ / "nothing").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("prs campaign init"), std::string::npos) << r.err;
}

TEST_F(PrsTest, CampaignSlurmScriptRunsTheUnfinishedShards) {
  const std::string dir = (dir_ / "campaign").string();
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "30", "--shard-size",
                  "5", "-s", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"campaign", "run-shard", dir, "1", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"campaign", "slurm", dir, "--print", "--max-running", "2", "--partition", "debug",
           "--cpus-per-task", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("#SBATCH --array=0,2-5%2\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("#SBATCH --partition=debug\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("/logs/shard-%a.out"), std::string::npos) << r.out;
  const std::string script = dir + "/slurm/submit-0.sh";
  ASSERT_TRUE(fs::exists(script));
  // What Slurm does with the script: run it once per array index, with the index set.
  for (const char* task : {"0", "2", "3", "4", "5"}) {
    const std::string command =
        std::string("SLURM_ARRAY_TASK_ID=") + task + " bash " + Quote(script) + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << task;
  }
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("6 of 6 done"), std::string::npos) << r.out;
  r = Run({"campaign", "slurm", dir, "--print"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("nothing to submit"), std::string::npos) << r.err;
  const std::string merged = (dir_ / "merged.jsonl").string();
  r = Run({"campaign", "merge", dir, "-o", merged});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Result single = Run({"sample", Example("table_cube.prs"), "-n", "30", "-s", "2"});
  EXPECT_EQ(ReadText(merged), single.out);
  // Without Slurm installed, submitting says so and where the script is.
  if (std::system("command -v sbatch >/dev/null 2>&1") != 0) {
    fs::remove(dir + "/shards/shard-00000.jsonl.done.json");
    r = Run({"campaign", "slurm", dir});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("sbatch is not installed"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace prs::cli
