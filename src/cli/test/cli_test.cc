// End-to-end tests of the built `prs` binary: every exit code with its located message on
// stderr, JSON Lines on stdout and in -o files, byte-identical output for any thread count
// and any split of the index range, `prs check`'s outline, `prs stats --json`, and SIGTERM.
#include <nlohmann/json.hpp>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

// Every line is a complete JSON scene; returns their indices.
std::vector<uint64_t> ParseSceneIndices(const std::string& text) {
  EXPECT_TRUE(text.empty() || text.back() == '\n') << "the last line is incomplete";
  std::vector<uint64_t> indices;
  for (const std::string& line : SplitLines(text)) {
    const json scene = json::parse(line, nullptr, /*allow_exceptions=*/false);
    EXPECT_FALSE(scene.is_discarded()) << "not JSON: " << line;
    if (scene.is_discarded()) continue;
    EXPECT_EQ(scene["format"], "prs-scene/1");
    indices.push_back(scene["index"].get<uint64_t>());
  }
  return indices;
}

const char kRequirementProgram[] =
    "from model import *\n"
    "t = Table on floor\n"
    "c = Cube on t\n"
    "require c.position.x > 0\n";

TEST_F(PrsTest, SampleSucceedsWithOneJsonScenePerLine) {
  const Result r = Run({"sample", Example("table_cube.prs"), "-n", "5", "-s", "1"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ParseSceneIndices(r.out), (std::vector<uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_NE(r.err.find("prs: 5 scenes, 5 attempts, 0 rejections"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a progress bar on a non-terminal";
}

TEST_F(PrsTest, SampleIsByteIdenticalForAnyThreadCount) {
  const std::string file = Write("req.prs", kRequirementProgram);
  // 3,000 scenes: workers hand over runs of up to 64 scenes' text at once.
  const std::vector<std::string> args = {"sample", file,   "-I", Example(""),
                                         "-n",     "3000", "-s", "9"};
  auto run_with = [&](const char* threads) {
    std::vector<std::string> with = args;
    with.insert(with.end(), {"--threads", threads});
    return Run(with);
  };
  const Result one = run_with("1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(SplitLines(one.out).size(), 3000u);
  EXPECT_EQ(run_with("2").out, one.out);
  EXPECT_EQ(run_with("4").out, one.out);
  const std::string path = (dir_ / "scenes.jsonl").string();
  std::vector<std::string> to_file = args;
  to_file.insert(to_file.end(), {"--threads", "2", "-o", path});
  ASSERT_EQ(Run(to_file).exit_code, 0);
  EXPECT_EQ(ReadText(path), one.out);
}

TEST_F(PrsTest, SampleIsByteIdenticalForAnySplitOfTheRange) {
  const std::string file = Example("table_cube.prs");
  const Result whole = Run({"sample", file, "-n", "10", "-s", "3"});
  const Result first = Run({"sample", file, "-n", "4", "-s", "3", "--threads", "1"});
  const Result rest = Run({"sample", file, "-n", "6", "-s", "3", "--start", "4", "--threads", "3"});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(first.out + rest.out, whole.out);
}

TEST_F(PrsTest, ScenarioErrorExitsOneWithALocatedMessage) {
  const std::string file = Write("bad.prs", "from model import *\nt = Tabel on floor\n");
  const Result r = Run({"sample", file, "-I", Example("")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(file + ":2:5: error: unknown class 'Tabel'"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(Run({"check", file, "-I", Example("")}).exit_code, 1);
  EXPECT_EQ(Run({"stats", file, "-I", Example("")}).exit_code, 1);
}

TEST_F(PrsTest, MissingFileIsAScenarioError) {
  const Result r = Run({"sample", (dir_ / "missing.prs").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("error: cannot read"), std::string::npos) << r.err;
}

TEST_F(PrsTest, UsageErrorsExitTwo) {
  const std::string file = Example("table_cube.prs");
  const std::vector<std::vector<std::string>> bad_command_lines = {
      {},
      {"sampel", file},
      {"sample"},
      {"sample", file, "--bogus"},
      {"sample", file, "-p", "no_equals_sign"},
      {"sample", file, "-n", "-1"},
      {"sample", file, "-s", "-1"},
      {"sample", file, "--threads", "0"},
      {"sample", file, "--max-attempts", "0"},
      {"sample", file, "--start", "18446744073709551615", "-n", "2"},
      {"stats", file, "-n", "many"},
  };
  for (const auto& args : bad_command_lines) {
    const Result r = Run(args);
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(r.exit_code, 2) << joined << "\n" << r.err;
    EXPECT_NE(r.err.find("prs: error: "), std::string::npos) << joined << "\n" << r.err;
  }
  EXPECT_NE(Run({"sampel", file}).err.find("did you mean 'sample'?"), std::string::npos);
}

TEST_F(PrsTest, HelpExitsZero) {
  const Result r = Run({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* command : {"sample", "check", "stats"}) {
    EXPECT_NE(r.out.find(command), std::string::npos) << r.out;
  }
  EXPECT_EQ(Run({"sample", "--help"}).exit_code, 0);
}

TEST_F(PrsTest, SamplingFailureExitsThreeWithALocatedMessage) {
  const std::string file =
      Write("fail.prs", "from model import *\nt = Table on floor\nrequire t.z > 5\n");
  const Result r = Run({"sample", file, "-I", Example(""), "--max-attempts", "50"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find(file + ":3:1: error: "), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(Run({"stats", file, "-I", Example(""), "--max-attempts", "50"}).exit_code, 3);
}

TEST_F(PrsTest, OutputFileGetsCompleteLinesAndNoPartialFile) {
  const fs::path out = dir_ / "scenes.jsonl";
  const Result r = Run({"sample", Example("table_cube.prs"), "-n", "7", "-o", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_EQ(ParseSceneIndices(ReadText(out)), (std::vector<uint64_t>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_FALSE(fs::exists(out.string() + ".partial"));
}

// Scenes fail now and then within 2 attempts: the ones before the first failure are kept in
// OUT.partial, the same ones stdout gets, and OUT is not created.
TEST_F(PrsTest, OutputFileAfterAFailureKeepsTheEarlierScenesInPartial) {
  const std::string file = Write("flaky.prs", "x = Range(0, 1)\nrequire x > 0.8\n");
  const fs::path out = dir_ / "scenes.jsonl";
  const std::vector<std::string> args = {"sample", file, "-n", "100", "--max-attempts", "2"};
  const Result to_stdout = Run(args);
  std::vector<std::string> with_file = args;
  with_file.insert(with_file.end(), {"-o", out.string()});
  const Result to_file = Run(with_file);
  EXPECT_EQ(to_stdout.exit_code, 3);
  EXPECT_EQ(to_file.exit_code, 3);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(ReadText(out.string() + ".partial"), to_stdout.out);
  EXPECT_NE(to_file.err.find(".partial"), std::string::npos) << to_file.err;
}

TEST_F(PrsTest, UnwritableOutputIsAnError) {
  const Result r =
      Run({"sample", Example("table_cube.prs"), "-o", (dir_ / "no/such/dir/x").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("prs: error: cannot create"), std::string::npos) << r.err;
}

TEST_F(PrsTest, TerminationKeepsCompleteLinesAndSaysWhereToResume) {
  const fs::path out = dir_ / "scenes.jsonl";
  const std::string prs = Quote(PRS_BINARY);
  // Kill once lines have arrived, so the handlers are surely installed (at most ~10 s).
  const std::string partial = Quote(out.string() + ".partial");
  const std::string script = prs + " sample " + Quote(Example("table_cube.prs")) +
                             " -n 100000000 -o " + Quote(out.string()) + " 2>" +
                             Quote((dir_ / "err.txt").string()) + " & pid=$!; i=0; while [ ! -s " +
                             partial + " ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i+1)); done; " +
                             "kill -TERM $pid; wait $pid; echo $? >" +
                             Quote((dir_ / "rc.txt").string());
  ASSERT_EQ(std::system(("sh -c " + Quote(script)).c_str()), 0);
  EXPECT_EQ(ReadText(dir_ / "rc.txt"), "143\n");  // 128 + SIGTERM
  EXPECT_FALSE(fs::exists(out));
  const std::vector<uint64_t> indices = ParseSceneIndices(ReadText(out.string() + ".partial"));
  EXPECT_NE(
      ReadText(dir_ / "err.txt").find("resume with --start " + std::to_string(indices.size())),
      std::string::npos)
      << ReadText(dir_ / "err.txt");
}

TEST_F(PrsTest, CheckPrintsTheOutline) {
  const Result r = Run({"check", Example("table_cube.prs")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* expected :
       {"table_cube.prs: ok, 20 scenes sampled (2 modules", "7 creation sites", "tr_1", "Tray",
        "completely on, ahead of, left of", "region (plane ∩ half-spaces",
        "observed over 20 scenes", "Camera", "position", "classes", "model.prs:"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
  }
}

// A program that compiles but cannot be sampled is never called "ok", and -n 0 says that
// nothing was sampled.
TEST_F(PrsTest, CheckNeverSaysOkAboveAnError) {
  const std::string file = Write("nested.prs", "x = ()\nfor i in range(5000):\n    x = (x,)\n");
  const Result failed = Run({"check", file});
  EXPECT_EQ(failed.exit_code, 1);
  EXPECT_EQ(failed.out.find(": ok"), std::string::npos) << failed.out;
  EXPECT_NE(failed.out.find("nested.prs: compiles, but sampling fails"), std::string::npos)
      << failed.out;
  EXPECT_NE(failed.err.find("nested.prs:3:9: error: tuples, lists or dicts nested more than"),
            std::string::npos)
      << failed.err;
  const Result static_only = Run({"check", file, "-n", "0"});
  EXPECT_EQ(static_only.exit_code, 0) << static_only.err;
  EXPECT_NE(static_only.out.find("nested.prs: compiles (not sampled: -n 0)"), std::string::npos)
      << static_only.out;
}

TEST_F(PrsTest, StatsJsonHasCountsThatAddUp) {
  const std::string file = Write("req.prs", kRequirementProgram);
  const Result r = Run({"stats", file, "-I", Example(""), "-n", "200", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json stats = json::parse(r.out);
  EXPECT_EQ(stats["format"], "prs-stats/1");
  EXPECT_EQ(stats["scenes"], 200);
  const int64_t rejections = stats["rejections"]["total"];
  EXPECT_GT(rejections, 0);
  EXPECT_EQ(stats["attempts"].get<int64_t>(), 200 + rejections);
  int64_t by_reason = 0, by_culprit = 0;
  for (const auto& [reason, n] : stats["rejections"]["by_reason"].items())
    by_reason += n.get<int64_t>();
  for (const json& culprit : stats["rejections"]["by_culprit"])
    by_culprit += culprit["count"].get<int64_t>();
  EXPECT_EQ(by_reason, rejections);
  EXPECT_EQ(by_culprit, rejections);
  const json& top = stats["rejections"]["by_culprit"][0];
  EXPECT_EQ(top["reason"], "requirement");
  EXPECT_EQ(top["file"], file);
  EXPECT_EQ(top["line"], 4);
  EXPECT_NEAR(stats["acceptance_rate"].get<double>(), 200.0 / (200 + rejections), 1e-12);
}

// `d` is drawn 0 to 1.5 cm above the table: --stable rejects the scenes where its fall, with the
// 2-3 mm it sinks into the table on impact, exceeds 1 cm (draws above about 7 mm), the same
// scenes for any thread count; prs stats counts them as "unstable" with `d` as the culprit; the
// tolerance is an option; bad values are usage errors.
const char kDropProgram[] =
    "from model import *\n"
    "t = Table on V3D(0, 0, 0)\n"
    "c = Cube on t\n"
    "d = Cube at V3D((-0.8, -0.6), 0.3, (0.825, 0.84))\n";

TEST_F(PrsTest, StableKeepsTheScenesAtRestForAnyThreadCount) {
  const std::string file = Write("drop.prs", kDropProgram);
  const std::vector<std::string> args = {"sample", file, "-I", Example(""), "-n",
                                         "20",     "-s", "4",  "--stable"};
  const std::string output = RunOnOneAndTwoThreads(args);
  int rejected = 0;
  for (const std::string& line : SplitLines(output)) {
    const json scene = json::parse(line);
    EXPECT_LE(scene["objects"][2]["position"][2].get<double>(), 0.825 + 0.0105);  // d
    if (scene["rejections"].contains("unstable")) {
      rejected += scene["rejections"]["unstable"].get<int>();
    }
  }
  EXPECT_GT(rejected, 0);
  const Result stats =
      Run({"stats", file, "-I", Example(""), "-n", "20", "-s", "4", "--stable", "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const json counts = json::parse(stats.out);
  EXPECT_EQ(counts["rejections"]["by_reason"]["unstable"], rejected);
  EXPECT_EQ(counts["rejections"]["by_culprit"][0]["culprit"], "d");
  // A 2 cm tolerance accepts every draw (at most 1.5 cm of fall and 3 mm of sinking).
  const Result loose = Run({"stats", file, "-I", Example(""), "-n", "20", "-s", "4", "--stable",
                            "--stable-move", "0.02", "--json"});
  ASSERT_EQ(loose.exit_code, 0) << loose.err;
  EXPECT_FALSE(json::parse(loose.out)["rejections"]["by_reason"].contains("unstable"));
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--stable=0"},
                                              {"--stable=abc"},
                                              {"--stable-move", "-1"},
                                              {"--stable-turn", "0"}}) {
    std::vector<std::string> with = {"sample", file, "-I", Example("")};
    with.insert(with.end(), bad.begin(), bad.end());
    const Result r = Run(with);
    EXPECT_EQ(r.exit_code, 2) << bad[0];
    EXPECT_NE(r.err.find("expects a number of"), std::string::npos) << r.err;
  }
}

// A failing scene's regenerate command keeps --stable: without it, it would be another scene.
TEST_F(PrsTest, StableIsInTheRegenerateCommand) {
  const std::string file = Write("drop.prs", kDropProgram);
  const Result r = Run({"test", file, "-I", Example(""), "--exec", "exit 3", "-n", "1", "-s", "4",
                        "--stable=0.5", "-o", (dir_ / "r.jsonl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json record = json::parse(ReadText(dir_ / "r.jsonl"));
  const std::string command = record["regenerate"];
  EXPECT_NE(command.find(" --stable=0.5 "), std::string::npos) << command;
}

// --settle: cubes drawn in the air above the table's edge come to rest; those that fall off
// (below 0.5 m) break the `require settled` and are drawn again, counted as "unsettled". The
// scenes carry "settled_s", are the same for any thread count, and the regenerate command
// keeps --settle; --settle with --stable is a usage error.
const char kFallProgram[] =
    "from model import *\n"
    "t = Table on V3D(0, 0, 0)\n"
    "c = Cube at V3D((0.85, 0.95), 0, 1.2)\n"
    "require settled c.z > 0.5\n";

TEST_F(PrsTest, SettleWritesTheScenesAtRestForAnyThreadCount) {
  const std::string file = Write("fall.prs", kFallProgram);
  const std::string output =
      RunOnOneAndTwoThreads({"sample", file, "-I", Example(""), "-n", "8", "-s", "3", "--settle"});
  int rejected = 0;
  for (const std::string& line : SplitLines(output)) {
    const json scene = json::parse(line);
    EXPECT_GT(scene["settled_s"].get<double>(), 0.3);
    const json& c = scene["objects"][1];
    EXPECT_NEAR(c["position"][2].get<double>(), 0.825, 0.004);  // on the table top
    if (scene["rejections"].contains("unsettled")) {
      rejected += scene["rejections"]["unsettled"].get<int>();
    }
  }
  EXPECT_GT(rejected, 0);
  const Result stats =
      Run({"stats", file, "-I", Example(""), "-n", "8", "-s", "3", "--settle", "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_EQ(json::parse(stats.out)["rejections"]["by_reason"]["unsettled"], rejected);
  const Result both = Run({"sample", file, "-I", Example(""), "--settle", "--stable"});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
  const Result bad = Run({"sample", file, "-I", Example(""), "--settle=-1"});
  EXPECT_EQ(bad.exit_code, 2);
  const Result record = Run({"test", file, "-I", Example(""), "--exec", "exit 3", "-n", "1", "-s",
                             "3", "--settle=1.5", "-o", (dir_ / "r.jsonl").string()});
  ASSERT_EQ(record.exit_code, 0) << record.err;
  const std::string command = json::parse(ReadText(dir_ / "r.jsonl"))["regenerate"];
  EXPECT_NE(command.find(" --settle=1.5 "), std::string::npos) << command;
}

TEST_F(PrsTest, StatsTableLocatesTheCulprit) {
  const std::string file = Write("req.prs", kRequirementProgram);
  const Result r = Run({"stats", file, "-I", Example(""), "-n", "50"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& expected :
       {std::string("acceptance rate"), std::string("rejections by reason"),
        std::string("per scene"), std::string("rejections by culprit"), file + ":4:1"}) {
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << "\n" << r.out;
  }
}

}  // namespace
}  // namespace prs::cli
