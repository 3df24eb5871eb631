// End-to-end tests of `prs test` on saved scenes and with persistent workers: a scenes file and
// a --save-failures directory run as they are and give the records of the sampled run (the
// case study's MuJoCo controller included); --replay regenerates an earlier run's scenes and
// refuses other programs and options; --persistent gives the records of one process per
// episode; bad files and workers exit with a located message and run nothing.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

// The records without their wall times (and, for comparing runs that name their scenes
// differently, without saved_scene and regenerate).
// The records without what says how each run was made: its time, files, program (a scenes file
// has none) and replay tag.
std::vector<json> Comparable(std::vector<json> records) {
  for (json& record : records) {
    for (const char* key :
         {"wall_s", "saved_scene", "regenerate", "spec", "scene_options", "replay"}) {
      record.erase(key);
    }
  }
  return records;
}

TEST_F(PrsTest, SavedFailuresReplayToTheSameOutcomesInTheCaseStudy) {
  const std::string failures = (dir_ / "failures").string();
  Result r =
      Run({"test", Example("table_cube.prs"), "--controller", "table-cube", "-n", "10", "-s", "1",
           "--threads", "2", "--save-failures", failures, "-o", (dir_ / "run.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<json> failed;
  for (const json& record : ReadRecords(dir_ / "run.jsonl")) {
    if (record["outcome"] != "success") failed.push_back(record);
  }
  ASSERT_GE(failed.size(), 2u) << "seed 1 has perception faults among its first 10 scenes";
  r = Run({"test", failures, "--controller", "table-cube", "--threads", "2", "-o",
           (dir_ / "replay.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Comparable(ReadRecords(dir_ / "replay.jsonl")), Comparable(failed))
      << "the same scenes in index order, with the same outcomes, details and measurements";
}

TEST_F(PrsTest, AScenesFileGivesTheRecordsOfTheSampledRun) {
  const std::string scenes = (dir_ / "scenes.jsonl").string();
  Result r = Run({"sample", Example("table_cube.prs"), "-n", "40", "-s", "3", "-o", scenes});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"test", Example("table_cube.prs"), "--controller", "demo-reach", "-n", "40", "-s", "3",
           "-o", (dir_ / "sampled.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"test", scenes, "--controller", "demo-reach", "--threads", "2", "-o",
           (dir_ / "saved.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Comparable(ReadRecords(dir_ / "saved.jsonl")),
            Comparable(ReadRecords(dir_ / "sampled.jsonl")));
  // -n and --start pick among the saved scenes.
  r = Run({"test", scenes, "--controller", "demo-reach", "--start", "5", "-n", "3", "-o",
           (dir_ / "some.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> some = ReadRecords(dir_ / "some.jsonl");
  ASSERT_EQ(some.size(), 3u);
  EXPECT_EQ(some[0]["index"], 5);
}

TEST_F(PrsTest, ReplayRegeneratesSearchAndTestRecordsAndRefusesOtherScenes) {
  const std::string searched = (dir_ / "search.jsonl").string();
  Result r = Run({"search", Example("table_cube.prs"), "--controller", "demo-reach", "--budget",
                  "40", "-s", "2", "-o", searched});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<json> failed;
  for (const json& record : ReadRecords(searched)) {
    if (record["outcome"] != "success") failed.push_back(record);
  }
  ASSERT_FALSE(failed.empty());
  r = Run({"test", Example("table_cube.prs"), "--replay", searched, "--failed", "--controller",
           "demo-reach", "-o", (dir_ / "again.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<json> replayed = ReadRecords(dir_ / "again.jsonl");
  EXPECT_EQ(Comparable(replayed), Comparable(failed))
      << "each at its coordinates, with its outcome and its search tag";
  for (const json& record : replayed) {
    EXPECT_EQ(record["replay"], json({{"of", searched}, {"failed_only", true}}));
    EXPECT_EQ(record["spec"], failed.front()["spec"]);
  }

  // The same records under other sampling options, or against another program: refused.
  r = Run({"test", Example("table_cube.prs"), "--replay", searched, "--naive", "--controller",
           "demo-reach", "-o", (dir_ / "naive.jsonl").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("search.jsonl:1: the record's scenes were made with the options '', this "
                       "replay's are '--naive'"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "naive.jsonl")) << "no records for a failed run";
  // Records that do not name their options (an older prs) are checked by their features.
  std::string unnamed;
  for (json record : ReadRecords(searched)) {
    record.erase("scene_options");
    unnamed += record.dump() + "\n";
  }
  r = Run({"test", Example("table_cube.prs"), "--replay", Write("old.jsonl", unnamed), "--naive",
           "--controller", "demo-reach"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("old.jsonl:1: scene 0 of seed 2 is not the scene this record ran in"),
            std::string::npos)
      << r.err;
  r = Run({"test", Example("constructs.prs"), "--replay", searched, "--controller", "demo-reach"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("drawn from another program"), std::string::npos) << r.err;
  // A records file given as scenes says how to replay it.
  r = Run({"test", searched, "--controller", "demo-reach"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("search.jsonl:1: not a scene"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--replay"), std::string::npos) << r.err;
}

TEST_F(PrsTest, ABadSceneLineIsLocatedAndNothingRuns) {
  const std::string scenes = (dir_ / "scenes.jsonl").string();
  ASSERT_EQ(Run({"sample", Example("table_cube.prs"), "-n", "2", "-o", scenes}).exit_code, 0);
  std::string text;
  for (const json& scene : ReadRecords(scenes)) text += scene.dump() + "\n";
  const std::string broken = Write("broken.jsonl", text + "\n{\"format\":\"prs-scene/1\"\n");
  const std::string marker = (dir_ / "ran.txt").string();
  const Result r = Run({"test", broken, "--exec", "touch '" + marker + "'"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("broken.jsonl:4: not valid JSON"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(marker)) << "nothing runs before every line is read";
  const Result empty =
      Run({"test", (dir_ / "nothing").string() + "/", "--controller", "demo-reach"});
  EXPECT_NE(empty.exit_code, 0);
}

// A controller in POSIX sh for both modes: odd scenes fail with their index as the score.
constexpr char kShellController[] = R"(#!/bin/sh
[ -n "$LOG" ] && echo "start $$" >> "$LOG"
[ "$PRS_PERSISTENT" = 1 ] && echo '{"ready": true}'
while IFS= read -r line; do
  rest=${line#*\"seed\":}; seed=${rest%%[!0-9]*}
  rest=${line#*\"index\":}; index=${rest%%[!0-9]*}
  if [ $((index % 2)) = 1 ]; then outcome=no-path; else outcome=success; fi
  echo "{\"outcome\":\"$outcome\",\"score\":$index,\"seed\":$seed,\"index\":$index}"
done
)";

TEST_F(PrsTest, PersistentWorkersGiveTheRecordsOfOneProcessPerEpisode) {
  const std::string command = "sh '" + Write("controller.sh", kShellController) + "'";
  std::vector<std::vector<json>> runs;
  for (const auto& [persistent, threads] : {std::pair{false, "2"}, {true, "2"}, {true, "1"}}) {
    std::vector<std::string> args = {"test",      Example("table_cube.prs"),
                                     "--exec",    command,
                                     "-n",        "16",
                                     "-s",        "7",
                                     "--threads", threads,
                                     "-o",        (dir_ / "r.jsonl").string()};
    if (persistent) args.push_back("--persistent");
    const Result r = Run(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("no-path"), std::string::npos) << r.out;
    runs.push_back(Comparable(ReadRecords(dir_ / "r.jsonl")));
  }
  EXPECT_EQ(runs[1], runs[0]);
  EXPECT_EQ(runs[2], runs[0]);
}

TEST_F(PrsTest, PersistentWorkersServeEveryGenerationOfASearchAndACampaignShard) {
  const std::string log = (dir_ / "starts.txt").string();
  const std::string command =
      "LOG='" + log + "' exec sh '" + Write("controller.sh", kShellController) + "'";
  Result r =
      Run({"search", Example("table_cube.prs"), "--exec", command, "--persistent", "--budget", "60",
           "--batch", "20", "--threads", "2", "-o", (dir_ / "search.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadRecords(dir_ / "search.jsonl").size(), 60u);
  const auto count_starts = [&] {
    std::ifstream in(log);
    int n = 0;
    for (std::string line; std::getline(in, line);) n += line.starts_with("start ");
    return n;
  };
  // Workers start when a thread first needs one, so a thread that finds the queue empty starts
  // none: the counts are bounds (one process per episode would start 60 here), not exact.
  const int search_starts = count_starts();
  EXPECT_GE(search_starts, 1);
  EXPECT_LE(search_starts, 2) << "at most two workers (one per thread) for three generations";

  const std::string dir = (dir_ / "campaign").string();
  r = Run({"campaign", "init", dir, Example("table_cube.prs"), "--exec", command, "--persistent",
           "-n", "12", "--shard-size", "6", "-s", "7"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* k : {"1", "0"}) {
    const int before = count_starts();
    r = Run({"campaign", "run-shard", dir, k, "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GE(count_starts() - before, 1) << "shard " << k;
    EXPECT_LE(count_starts() - before, 2) << "at most two workers for shard " << k;
  }
  r = Run({"campaign", "merge", dir, "-o", (dir_ / "merged.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"test", Example("table_cube.prs"), "--exec", command, "-n", "12", "-s", "7", "-o",
           (dir_ / "single.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Comparable(ReadRecords(dir_ / "merged.jsonl")),
            Comparable(ReadRecords(dir_ / "single.jsonl")));
}

TEST_F(PrsTest, APersistentWorkerThatCannotStartStopsTheRun) {
  Result r = Run({"test", Example("table_cube.prs"), "--persistent", "--controller", "demo-reach"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--persistent requires --exec"), std::string::npos) << r.err;
  r = Run({"test", Example("table_cube.prs"), "-n", "4", "--persistent", "--exec",
           "echo 'cannot open display' >&2; exit 1", "-o", (dir_ / "r.jsonl").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("exited with code 1 before its handshake; its last error line: cannot "
                       "open display"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("docs/harness.md"), std::string::npos) << r.err;
  r = Run({"test", Example("table_cube.prs"), "-n", "4", "--persistent", "--startup-timeout", "0.2",
           "--exec", "sleep 5"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("sent no handshake within 0.2 s"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prs::cli
