// End-to-end tests of `prs campaign`: shards run in any order merge into one machine's run, bad
// shards and requests are named, the Slurm job script runs exactly the unfinished shards,
// submissions are recorded and resumed (with sbatch and squeue stand-ins), and a search
// campaign equals `prs search`.
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

// The records of a JSON Lines file without their wall-clock times (the one field that differs
// between a campaign and one machine's run).
std::vector<json> ReadRecordsWithoutTimes(const std::string& path) {
  std::vector<json> records = ReadRecords(path);
  for (json& record : records) record.erase("wall_s");
  return records;
}

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
  EXPECT_EQ(ReadRecordsWithoutTimes(merged), ReadRecordsWithoutTimes(single));
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

// --stable or --settle at init is kept in the spec, and each shard applies it: the merged
// scenes are `prs sample`'s with the same option. --stable: a cube drawn up to 1.5 cm above the
// table, the higher draws rejected; --settle: a cube dropped near the table's edge, the scenes
// where it falls off rejected.
TEST_F(PrsTest, CampaignShardsKeepStableAndSettle) {
  const auto expect_campaign_matches_sample =
      [&](const std::string& file, const std::string& option, const std::string& rejection) {
        const std::string dir = (dir_ / ("campaign" + option)).string();
        const std::vector<std::string> scenario = {file, "-I", Example(""), "-s", "4", option};
        std::vector<std::string> init = {"campaign", "init", dir, "-n", "12", "--shard-size", "5"};
        init.insert(init.end(), scenario.begin(), scenario.end());
        Result r = Run(init);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        for (const char* k : {"2", "0", "1"}) {
          r = Run({"campaign", "run-shard", dir, k, "--threads", "2"});
          ASSERT_EQ(r.exit_code, 0) << r.err;
        }
        const std::string merged = (dir_ / "merged.jsonl").string();
        r = Run({"campaign", "merge", dir, "-o", merged});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        std::vector<std::string> sample = {"sample", "-n", "12"};
        sample.insert(sample.end(), scenario.begin(), scenario.end());
        const Result single = Run(sample);
        ASSERT_EQ(single.exit_code, 0) << single.err;
        EXPECT_EQ(ReadText(merged), single.out);
        EXPECT_NE(single.out.find("\"" + rejection + "\""), std::string::npos) << "none rejected";
      };
  expect_campaign_matches_sample(Write("drop.prs",
                                       "from model import *\nt = Table on V3D(0, 0, 0)\n"
                                       "d = Cube at V3D((-0.8, -0.6), 0.3, (0.825, 0.84))\n"),
                                 "--stable=0.5", "unstable");
  expect_campaign_matches_sample(
      Write("fall.prs",
            "from model import *\nt = Table on V3D(0, 0, 0)\n"
            "c = Cube at V3D((0.85, 0.95), 0, 1.2)\nrequire settled c.z > 0.5\n"),
      "--settle", "unsettled");
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
  EXPECT_NE(r.out.find("/logs/slurm-%A_%a.out"), std::string::npos) << r.out;
  const std::string script = dir + "/slurm/submit-0.sh";
  ASSERT_TRUE(fs::exists(script));
  // What Slurm does with the script: run it once per array index, with the index set.
  for (const char* task : {"0", "2", "3", "4", "5"}) {
    const std::string command = std::string("SLURM_ARRAY_JOB_ID=7 SLURM_ARRAY_TASK_ID=") + task +
                                " bash " + Quote(script) + " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << task;
  }
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("6 of 6 done"), std::string::npos) << r.out;
  r = Run({"campaign", "slurm", dir, "--print"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("no shard to submit"), std::string::npos) << r.err;
  const std::string merged = (dir_ / "merged.jsonl").string();
  r = Run({"campaign", "merge", dir, "-o", merged});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Result single = Run({"sample", Example("table_cube.prs"), "-n", "30", "-s", "2"});
  EXPECT_EQ(ReadText(merged), single.out);
  // Without Slurm installed, submitting says so and where the script is.
  fs::remove(dir + "/shards/shard-00000.jsonl.done.json");
  r = Run({"campaign", "slurm", dir}, "PATH=/nonexistent");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("sbatch is not installed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/slurm/submit-1.sh yourself"), std::string::npos) << r.err;
}

// sbatch and squeue stand-ins on PATH: what is submitted, recorded and resubmitted, and how the
// queue's words show in `status` (tests/slurm/campaign_test.sh does the same on real Slurm).
TEST_F(PrsTest, CampaignSlurmRecordsSubmissionsAndResumesWhatTheQueueLost) {
  const std::string dir = (dir_ / "campaign").string();
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  const auto write_program = [&](const std::string& name, const std::string& text) {
    Write("bin/" + name, "#!/bin/sh\n" + text);
    fs::permissions(bin / name, fs::perms::owner_all);
  };
  // sbatch prints job ids 41, 42, ... and keeps its arguments; squeue knows job 41's tasks.
  write_program("sbatch", "n=$(cat " + Quote((dir_ / "jobs").string()) +
                              " 2>/dev/null || echo 40); n=$((n + 1)); echo $n > " +
                              Quote((dir_ / "jobs").string()) + "; echo \"$@\" >> " +
                              Quote((dir_ / "sbatch_args").string()) + "; echo $n\n");
  write_program("squeue",
                "printf '41|0|RUNNING|None\\n41|1|CANCELLED|None\\n41|2|PENDING|Priority\\n'\n");
  const std::string env = "PATH=" + Quote(bin.string()) + ":/usr/bin:/bin";
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "25", "--shard-size",
                  "5", "-s", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"campaign", "resume", dir}, env);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("submit it first with prs campaign slurm"), std::string::npos) << r.err;

  r = Run({"campaign", "slurm", dir, "--time", "00:05:00", "--max-running", "2", "--extra",
           "--qos=low"},
          env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "41\n");
  EXPECT_NE(ReadText(dir_ / "sbatch_args").find("--parsable --qos=low"), std::string::npos);
  EXPECT_NE(ReadText(dir + "/slurm/submit-0.sh").find("#SBATCH --array=0-4%2\n"),
            std::string::npos);
  r = Run({"campaign", "run-shard", dir, "3", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;

  r = Run({"campaign", "status", dir}, env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("shard 0: running: Slurm job 41_0 is RUNNING"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shard 1: failed: Slurm job 41_1 ended CANCELLED"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("shard 4: failed: Slurm job 41_4 ended without writing it"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("1 of 5 done, 1 queued, 1 running, 2 failed, 0 missing, 0 bad"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.err.find("resume " + dir + " submits the 2 shards"), std::string::npos) << r.err;

  // Resume: only shards 1 and 4, with the first submission's options unless given again.
  r = Run({"campaign", "resume", dir, "--time", "00:09:00"}, env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "42\n");
  const std::string script = ReadText(dir + "/slurm/submit-1.sh");
  EXPECT_NE(script.find("#SBATCH --array=1,4%2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --time=00:09:00\n"), std::string::npos) << script;
  EXPECT_NE(ReadText(dir_ / "sbatch_args").find("--parsable --qos=low"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/slurm/submit-1.json"));

  // Without squeue, status says the queue was not asked; resume warns it may submit twice.
  r = Run({"campaign", "status", dir}, "PATH=/nonexistent");
  EXPECT_NE(r.err.find("the Slurm queue was not asked: squeue is not installed"), std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("1 of 5 done, 0 queued, 0 running, 0 failed, 4 missing"), std::string::npos)
      << r.out;
}

// Past Slurm's MaxArraySize (here 3, from an scontrol stand-in) the shards go in several
// arrays, each indexed from its first shard; squeue's indices map back to the shards.
TEST_F(PrsTest, CampaignSlurmSplitsArraysAtMaxArraySize) {
  const std::string dir = (dir_ / "campaign").string();
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"scontrol", "echo 'MaxArraySize            = 3'\n"},
           {"sbatch", "n=$(cat " + Quote((dir_ / "jobs").string()) +
                          " 2>/dev/null || echo 40); n=$((n + 1)); echo $n > " +
                          Quote((dir_ / "jobs").string()) + "; echo $n\n"},
           {"squeue", "printf '42|1|RUNNING|None\\n41|0|PENDING|None\\n'\n"}}) {
    Write("bin/" + name, "#!/bin/sh\n" + text);
    fs::permissions(bin / name, fs::perms::owner_all);
  }
  const std::string env = "PATH=" + Quote(bin.string()) + ":/usr/bin:/bin";
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "25", "--shard-size",
                  "5", "-s", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"campaign", "slurm", dir}, env);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "41\n42\n");
  const std::string first = ReadText(dir + "/slurm/submit-0.sh");
  const std::string second = ReadText(dir + "/slurm/submit-1.sh");
  EXPECT_NE(first.find("#SBATCH --array=0-2\n"), std::string::npos) << first;
  EXPECT_NE(second.find("#SBATCH --array=0-1\n"), std::string::npos) << second;
  EXPECT_NE(second.find("shard=$((3 + SLURM_ARRAY_TASK_ID))"), std::string::npos) << second;
  r = Run({"campaign", "status", dir}, env);
  EXPECT_NE(r.out.find("shard 4: running: Slurm job 42_1 is RUNNING"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 of 5 done, 1 queued, 1 running, 3 failed"), std::string::npos) << r.out;
  // The second array's task 1 is shard 4, with its output in logs/shard-4.42.*.
  ASSERT_EQ(std::system(("SLURM_ARRAY_JOB_ID=42 SLURM_ARRAY_TASK_ID=1 bash " +
                         Quote(dir + "/slurm/submit-1.sh") + " >/dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_TRUE(fs::exists(dir + "/shards/shard-00004.jsonl"));
  EXPECT_TRUE(fs::exists(dir + "/logs/shard-4.42.err"));
}

// A search campaign from the command line: generation after generation with run-shard, merged
// into exactly `prs search -o`; its options checked at init.
TEST_F(PrsTest, CampaignSearchRunsGenerationAfterGenerationAsPrsSearch) {
  const std::string dir = (dir_ / "search").string();
  Result r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "50", "--batch", "20"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("give --search too"), std::string::npos) << r.err;
  r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "50", "--search", "ce"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--search needs a controller"), std::string::npos) << r.err;
  r = Run({"campaign", "init", dir, Example("table_cube.prs"), "-n", "50", "--search", "bo",
           "--controller", "planted-1-percent"});
  EXPECT_EQ(r.exit_code, 2);
  // A program that fails when it runs (the search's trial attempts): located, nothing made.
  const std::string broken = Write("broken.prs", "from model import *\nt = Table at (0, 0, 0.5)\n");
  r = Run({"campaign", "init", dir, broken, "-I", (RepoRoot() / "examples").string(), "-n", "10",
           "--search", "ce", "--controller", "demo-reach"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.prs:2:14: error: the position must be a vector"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("^~~"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  r = Run({"campaign", "init", dir, Example("table_cube.prs"), "--controller", "planted-1-percent",
           "-n", "50", "--search", "anneal", "--batch", "20", "--shard-size", "8", "-s", "6"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("3 generations of 20"), std::string::npos) << r.err;
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("0 of 8 done, 0 queued, 0 running, 0 failed, 3 missing, 0 bad, 5 waiting; "
                       "search generation 1 of 3"),
            std::string::npos)
      << r.out;
  r = Run({"campaign", "run-shard", dir, "3"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run that generation's shards first (0, 1, 2)"), std::string::npos) << r.err;
  for (int k = 0; k < 8; ++k) {
    r = Run({"campaign", "run-shard", dir, std::to_string(k), "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << k << r.err;
  }
  const std::string merged = (dir_ / "merged.jsonl").string();
  r = Run({"campaign", "merge", dir, "-o", merged});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string single = (dir_ / "single.jsonl").string();
  r = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent", "--budget",
           "50", "--batch", "20", "--strategy", "anneal", "-s", "6", "-q", "-o", single});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> a = ReadRecordsWithoutTimes(merged);
  EXPECT_EQ(a.size(), 50u);
  EXPECT_EQ(a, ReadRecordsWithoutTimes(single));
  r = Run({"campaign", "slurm", dir, "--print"});
  EXPECT_NE(r.err.find("the search is complete"), std::string::npos) << r.err;
}

TEST_F(PrsTest, CampaignEstimateMergesIntoPrsEstimate) {
  const std::string dir = (dir_ / "estimate").string(), file = Example("table_cube.prs");
  Result r = Run({"campaign", "init", dir, file, "-n", "600", "--estimate"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--estimate needs a controller"), std::string::npos) << r.err;
  r = Run({"campaign", "init", dir, file, "--controller", "planted-1-percent", "-n", "100",
           "--estimate"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("too small to adapt a proposal and then sample: give at least 200"),
            std::string::npos)
      << r.err;
  r = Run({"campaign", "init", dir, file, "--controller", "planted-1-percent", "-n", "600",
           "--estimate", "--search", "ce"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("two kinds of campaign: give one"), std::string::npos) << r.err;
  r = Run({"campaign", "init", dir, file, "--controller", "planted-1-percent", "-n", "600",
           "--estimate", "--sampler", "gibbs"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("leave out --sampler"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  // 600 episodes over Table-Cube's 11 coordinates: the first search's 6 generations of 20, the
  // probe's 55, the second search's 3 of 20, the exploration's 60, 3 rounds of 16
  // walks and the sampling's 257 (in shards of 100: 3).
  r = Run({"campaign", "init", dir, file, "--controller", "planted-1-percent", "-n", "600",
           "--estimate", "--shard-size", "100", "-s", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("an estimate in 15 generations"), std::string::npos) << r.err;
  r = Run({"campaign", "status", dir});
  EXPECT_NE(r.out.find("0 of 17 done"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("estimate generation 1 of 15"), std::string::npos) << r.out;
  r = Run({"campaign", "run-shard", dir, "16"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("run that generation's shards first (0)"), std::string::npos) << r.err;
  const std::string merged = (dir_ / "merged.jsonl").string();
  r = Run({"campaign", "merge", dir, "-o", merged});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("generation 0's shards 0 are not done"), std::string::npos) << r.err;
  for (int k = 0; k < 17; ++k) {
    r = Run({"campaign", "run-shard", dir, std::to_string(k), "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << k << r.err;
  }
  r = Run({"campaign", "merge", dir, "-o", merged, "--partial"});
  EXPECT_EQ(r.exit_code, 2);
  r = Run({"campaign", "merge", dir, "-o", merged});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string table = r.out;
  const std::string single = (dir_ / "single.jsonl").string();
  r = Run({"estimate", file, "--controller", "planted-1-percent", "--budget", "600", "-s", "3",
           "-q", "-o", single});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(table, r.out) << "the merged estimate prints as prs estimate does";
  EXPECT_NE(table.find("planted-failure"), std::string::npos) << table;
  const std::vector<json> a = ReadRecordsWithoutTimes(merged);
  EXPECT_EQ(a.size(), 600u);
  EXPECT_EQ(a, ReadRecordsWithoutTimes(single));
  r = Run({"estimate", "--from", merged, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Result from_single = Run({"estimate", "--from", single, "--json"});
  EXPECT_EQ(r.out, from_single.out);
  EXPECT_NE(r.out.find("\"planted-failure\":{\"p\":"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace prs::cli
