// End-to-end tests of `prs test`: the example Python controller over --exec agrees with the
// built-in demo-reach, the table adds up, records are the same for 1 and 2 threads (also for the
// simulated table-cube), failures are saved with pictures and regenerate, timeouts, SIGTERM,
// and bad flags (exit 2) or scenarios (exit 1, 3).
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"
#include "harness/test/process_checks.h"

namespace prs::cli {
namespace {

using nlohmann::json;

// The records without their wall-clock times, which are the only part allowed to differ.
std::vector<json> WithoutTimes(std::vector<json> records) {
  for (json& record : records) record.erase("wall_s");
  return records;
}

// outcome -> count from the table on stdout; the "total" row under the key "total".
std::map<std::string, int64_t> ParseTable(const std::string& out) {
  std::map<std::string, int64_t> counts;
  std::stringstream lines(out);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header.rfind("outcome", 0), 0u) << out;
  for (std::string outcome, share; lines >> outcome;) {
    lines >> counts[outcome] >> share;
  }
  return counts;
}

std::map<std::string, int64_t> CountOutcomes(const std::vector<json>& records) {
  std::map<std::string, int64_t> counts;
  for (const json& record : records) ++counts[record["outcome"].get<std::string>()];
  return counts;
}

class PrsTestCommandTest : public PrsTest {
 protected:
  std::vector<std::string> TableCube(std::vector<std::string> more) {
    std::vector<std::string> args = {"test", Example("table_cube.prs")};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
};

// Seed 1, scenes 15..22 hold one cube too close to its robot (scene 17).
TEST_F(PrsTestCommandTest, PythonControllerOverExecAgreesWithDemoReach) {
  const std::string python = "/usr/bin/python3 " + Quote(Example("controllers/reach_check.py"));
  const Result by_exec = Run(TableCube(
      {"--exec", python, "-n", "8", "--start", "15", "-s", "1", "-o", Path("exec.jsonl")}));
  ASSERT_EQ(by_exec.exit_code, 0) << by_exec.err;
  const Result built_in = Run(TableCube({"--controller", "demo-reach", "-n", "8", "--start", "15",
                                         "-s", "1", "-o", Path("demo.jsonl")}));
  ASSERT_EQ(built_in.exit_code, 0) << built_in.err;
  const std::vector<json> exec = ReadRecords(Path("exec.jsonl"));
  const std::vector<json> demo = ReadRecords(Path("demo.jsonl"));
  ASSERT_EQ(exec.size(), 8u);
  ASSERT_EQ(demo.size(), 8u);
  for (size_t i = 0; i < exec.size(); ++i) {
    EXPECT_EQ(exec[i]["index"], 15 + i);
    EXPECT_EQ(exec[i]["outcome"], demo[i]["outcome"]) << exec[i].dump() << "\n" << demo[i].dump();
  }
  EXPECT_EQ(CountOutcomes(exec), (std::map<std::string, int64_t>{{"no-path", 1}, {"success", 7}}));
  EXPECT_EQ(by_exec.out, built_in.out) << "the same outcomes make the same table";
  EXPECT_NE(by_exec.err.find("prs: 8 episodes, 7 successes, 1 failure;"), std::string::npos)
      << by_exec.err;
}

TEST_F(PrsTestCommandTest, TableCountsAddUpToTheRecords) {
  const Result r =
      Run(TableCube({"--controller", "demo-reach", "-n", "100", "-s", "1", "-o", Path("r.jsonl")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, int64_t> table = ParseTable(r.out);
  EXPECT_EQ(table["total"], 100);
  table.erase("total");
  EXPECT_EQ(table, CountOutcomes(ReadRecords(Path("r.jsonl"))));
  EXPECT_EQ(r.out.substr(r.out.find('\n') + 1, 7), "success") << "success comes first";
}

TEST_F(PrsTestCommandTest, RecordsAreTheSameForOneAndTwoThreads) {
  // A shell controller whose answer depends on the scene it reads (its checksum), in all
  // three answer forms.
  const std::string controller =
      "c=$(cksum < \"$PRS_SCENE_FILE\" | cut -d' ' -f1); case $((c % 3)) in 0) exit 0;; "
      "1) exit 3;; *) echo '{\"outcome\": \"poor-grip\", \"sum\": '$c'}';; esac";
  std::vector<json> runs[2];
  for (const int threads : {1, 2}) {
    const std::string out = Path("t" + std::to_string(threads) + ".jsonl");
    const Result r = Run(TableCube({"--exec", controller, "-n", "12", "-s", "4", "--threads",
                                    std::to_string(threads), "-o", out}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[threads - 1] = WithoutTimes(ReadRecords(out));
  }
  ASSERT_EQ(runs[0].size(), 12u);
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_GE(CountOutcomes(runs[0]).size(), 2u) << "the checksums should give several outcomes";
  std::vector<json> demo[2];
  for (const int threads : {1, 2}) {
    const std::string out = Path("d" + std::to_string(threads) + ".jsonl");
    ASSERT_EQ(Run(TableCube({"--controller", "demo-reach", "-n", "100", "-s", "1", "--threads",
                             std::to_string(threads), "-o", out}))
                  .exit_code,
              0);
    demo[threads - 1] = WithoutTimes(ReadRecords(out));
  }
  EXPECT_EQ(demo[0], demo[1]);
}

// The simulated case study through the harness: a short run, the same records on 1 and 2
// threads (each thread with its own simulation and rendering context).
TEST_F(PrsTestCommandTest, TableCubeControllerRunsTheSameOnOneAndTwoThreads) {
  std::vector<json> runs[2];
  for (const int threads : {1, 2}) {
    const std::string out = Path("tc" + std::to_string(threads) + ".jsonl");
    const Result r = Run(TableCube({"--controller", "table-cube", "-n", "4", "-s", "1", "--threads",
                                    std::to_string(threads), "-o", out}));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[threads - 1] = WithoutTimes(ReadRecords(out));
  }
  ASSERT_EQ(runs[0].size(), 4u);
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_GE(CountOutcomes(runs[0])["success"], 1) << json(runs[0]).dump();
}

size_t CountOccurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The original tool's object model has a Cube without a mass. The case-study controllers give
// it one and say so once per run, whatever the thread count; the records carry the mass.
TEST_F(PrsTestCommandTest, AMasslessPickTargetIsWarnedAboutOnceAndPicked) {
  const Result r = Run({"test", Example("table_cube_paper_model.prs"), "--controller",
                        "table-cube-paper", "-n", "4", "-s", "1", "--threads", "2", "-o",
                        Path("r.jsonl")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(CountOccurrences(r.err, "prs: warning: Cube_5 (a Cube) has no mass"), 1u) << r.err;
  const std::vector<json> records = ReadRecords(Path("r.jsonl"));
  ASSERT_EQ(records.size(), 4u);
  for (const json& record : records) {
    EXPECT_EQ(record["extra"]["cube_mass_assumed"], true);
    EXPECT_NEAR(record["extra"]["cube_mass_kg"].get<double>(), 0.064, 1e-12);
  }
  EXPECT_GE(CountOutcomes(records)["success"], 2) << json(records).dump();
}

// A user's own controller reads the scene as prs export writes it: once per run, prs test
// warns when a scene has nothing movable (the original model's massless cube), and not when
// it has (examples/model.prs's cube has a mass).
TEST_F(PrsTestCommandTest, ExecControllersAreWarnedOfScenesWithoutAFreeBody) {
  const std::string controller = "echo '{\"outcome\": \"success\"}'";
  const Result massless = Run({"test", Example("table_cube_paper_model.prs"), "--exec", controller,
                               "-n", "3", "-s", "1"});
  ASSERT_EQ(massless.exit_code, 0) << massless.err;
  EXPECT_EQ(CountOccurrences(massless.err, "prs: warning: a scene has no free body"), 1u)
      << massless.err;
  const Result with_mass = Run(TableCube({"--exec", controller, "-n", "3", "-s", "1"}));
  ASSERT_EQ(with_mass.exit_code, 0) << with_mass.err;
  EXPECT_EQ(with_mass.err.find("warning"), std::string::npos) << with_mass.err;
}

TEST_F(PrsTestCommandTest, FailingScenesAreSavedAndTheirCommandRegeneratesThem) {
  const Result r = Run(TableCube({"--controller", "demo-reach", "-n", "20", "-s", "1",
                                  "--save-failures", Path("failures"), "-o", Path("r.jsonl")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int failures = 0;
  for (const json& record : ReadRecords(Path("r.jsonl"))) {
    const std::string index = std::to_string(record["index"].get<uint64_t>());
    const fs::path saved = dir_ / "failures" / ("seed-1-index-" + index + ".json");
    if (record["outcome"] == "success") {
      EXPECT_FALSE(fs::exists(saved));
      EXPECT_FALSE(record.contains("regenerate"));
      continue;
    }
    ++failures;
    EXPECT_EQ(record["saved_scene"], saved.string());
    EXPECT_EQ(record["regenerate"],
              "prs sample " + Example("table_cube.prs") + " -s 1 --start " + index + " -n 1");
    const fs::path png = fs::path(saved).replace_extension(".png");
    EXPECT_EQ(ReadText(png).substr(0, 8), "\x89PNG\r\n\x1a\n") << "no picture " << png;
    const Result again = Run({"sample", Example("table_cube.prs"), "-s", "1", "--index", index});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(again.out, ReadText(saved)) << "the saved scene is not scene " << index;
  }
  EXPECT_EQ(failures, 1);  // scene 17
  EXPECT_NE(r.err.find("prs: 1 failing scene saved in " + Path("failures")), std::string::npos)
      << r.err;
}

TEST_F(PrsTestCommandTest, HangingAndKilledControllersAreOutcomes) {
  const Result r = Run(TableCube({"--exec", "case $PRS_INDEX in 0) sleep 20;; *) kill -9 $$;; esac",
                                  "-n", "3", "--timeout", "0.3", "-o", Path("r.jsonl")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(CountOutcomes(ReadRecords(Path("r.jsonl"))),
            (std::map<std::string, int64_t>{{"signal-9", 2}, {"timeout", 1}}));
  EXPECT_NE(r.out.find("timeout"), std::string::npos) << r.out;
}

TEST_F(PrsTestCommandTest, TerminationKillsRunningControllersAndSaysWhereToResume) {
  // Controllers that note their pid and hang; prs gets SIGTERM once one has started.
  const std::string controller = "echo $$ > " + Quote(Path("pid")) + ".$PRS_INDEX; exec sleep 30";
  const std::string script =
      Quote(PRS_BINARY) + " test " + Quote(Example("table_cube.prs")) + " --exec " +
      Quote(controller) + " -n 4 --threads 2 -o " + Quote(Path("r.jsonl")) + " 2>" +
      Quote(Path("err.txt")) + " & pid=$!; i=0; while [ ! -s " + Quote(Path("pid")) +
      ".0 ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i+1)); done; kill -TERM $pid; wait $pid; " +
      "echo $? > " + Quote(Path("rc.txt"));
  const auto begin = std::chrono::steady_clock::now();
  ASSERT_EQ(std::system(("sh -c " + Quote(script)).c_str()), 0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count(), 15);
  EXPECT_EQ(ReadText(Path("rc.txt")), "143\n");  // 128 + SIGTERM
  EXPECT_NE(ReadText(Path("err.txt")).find("interrupted after 0 episodes (resume with --start 0"),
            std::string::npos)
      << ReadText(Path("err.txt"));
  // No episode finished, so no empty r.jsonl.partial is left behind.
  EXPECT_FALSE(fs::exists(Path("r.jsonl.partial")));
  EXPECT_FALSE(fs::exists(Path("r.jsonl")));
  for (const char* index : {"0", "1"}) {
    const std::string pid = ReadText(Path("pid") + "." + index);
    if (pid.empty()) continue;  // that episode had not started
    EXPECT_TRUE(harness::testing_checks::IsGone(std::stoi(pid))) << "controller " << index;
  }
}

TEST_F(PrsTestCommandTest, SampleIndexIsOneSceneAtThatIndex) {
  const Result by_index = Run({"sample", Example("table_cube.prs"), "-s", "2", "--index", "9"});
  const Result by_start =
      Run({"sample", Example("table_cube.prs"), "-s", "2", "--start", "9", "-n", "1"});
  ASSERT_EQ(by_index.exit_code, 0) << by_index.err;
  EXPECT_EQ(by_index.out, by_start.out);
  EXPECT_NE(by_index.out.find("\"index\":9"), std::string::npos);
  const Result both = Run({"sample", Example("table_cube.prs"), "--index", "9", "-n", "2"});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--index"), std::string::npos) << both.err;
}

TEST_F(PrsTestCommandTest, BadFlagsAreUsageErrorsNamingTheFlag) {
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{}, "no controller: give --controller NAME"},
      {{"--controller", "demo-rech"},
       "--controller: unknown controller 'demo-rech'; did you mean 'demo-reach'?"},
      {{"--controller", "demo-reach", "--exec", "true"}, "--exec"},
      {{"--exec", "true", "--timeout", "0"}, "--timeout"},
      {{"--exec", "true", "--timeout", "soon"}, "expects a number of seconds"},
      {{"--controller", "demo-reach", "--threads", "0"}, "--threads"},
      {{"--controller", "demo-reach", "-n", "-1"}, "--count"},
  };
  for (const auto& c : cases) {
    const Result r = Run(TableCube(c.args));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

TEST_F(PrsTestCommandTest, ScenarioErrorsExitOneAndSamplingFailuresThree) {
  const std::string file = Write("bad.prs", "from model import *\nc = Cube on nowhere\n");
  const Result r = Run({"test", file, "-I", Example(""), "--controller", "demo-reach", "-n", "2"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.prs:2:"), std::string::npos) << r.err;
  const std::string impossible =
      Write("impossible.prs", "from model import *\nc = Cube on floor\nrequire c.position.z > 5\n");
  const Result never = Run({"test", impossible, "-I", Example(""), "--controller", "demo-reach",
                            "-n", "2", "--max-attempts", "20"});
  EXPECT_EQ(never.exit_code, 3) << never.err;
  EXPECT_NE(never.err.find("impossible.prs:3:"), std::string::npos) << never.err;
  const Result missing = Run({"test", Path("none.prs"), "--controller", "demo-reach"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("none.prs"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace prs::cli
