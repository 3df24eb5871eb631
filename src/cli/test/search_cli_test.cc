// End-to-end tests of `prs search`, `--design`, `--near`, `prs report`, `prs compare` and `prs check
// --coordinates`: records with coordinates, scores and generations, the same for any thread
// count; designs change scenes but keep them valid and reproducible; reports name the cause;
// and bad requests exit with a message to act on.
#include <nlohmann/json.hpp>

#include <map>
#include <tuple>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

TEST_F(PrsTest, SearchWritesRecordsTheSameForAnyThreadCount) {
  const std::string one = (dir_ / "one.jsonl").string(), two = (dir_ / "two.jsonl").string();
  for (const auto& [out, threads] : {std::pair{one, "1"}, std::pair{two, "2"}}) {
    const Result r = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                          "--budget", "200", "-s", "4", "--threads", threads, "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("planted-failure"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("generation"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("ce found"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("waves"), std::string::npos) << "20 a generation fill 1 or 2 threads";
  }
  // 16 threads for generations of 20: the second wave leaves 12 of them idle, and prs says so.
  const Result wide = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                           "--budget", "40", "-s", "4", "--threads", "16"});
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.err.find("generations of 20 run on 16 threads in 2 waves"), std::string::npos)
      << wide.err;
  EXPECT_NE(wide.err.find("--batch 32 keeps them all busy"), std::string::npos) << wide.err;
  std::vector<json> a = ReadRecords(one), b = ReadRecords(two);
  ASSERT_EQ(a.size(), 200u);
  for (std::vector<json>* records : {&a, &b}) {
    for (json& record : *records) record.erase("wall_s");
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(a[0]["search"]["strategy"], "ce");
  EXPECT_EQ(a[199]["search"]["generation"], 9);
  EXPECT_EQ(a[0]["coordinates"].size(), 11u);
  EXPECT_TRUE(a[0]["score"].is_number());
}

TEST_F(PrsTest, SearchRefusesBadRequests) {
  Result r = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                  "--budget", "10", "--strategy", "cee"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'ce'"), std::string::npos) << r.err;
  r = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent", "--budget",
           "10", "--strategy", "bo"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("strategy=\"bo\""), std::string::npos) << r.err;
  r = Run(
      {"search", Example("table_cube.prs"), "--controller", "planted-1-percent", "--budget", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--budget"), std::string::npos) << r.err;
  const std::string fixed = Write("fixed.prs", "Object at Vector3D(0, 0, 0)\n");
  r = Run({"search", fixed, "--controller", "planted-1-percent", "--budget", "10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("draws nothing at random"), std::string::npos) << r.err;
  r = Run(
      {"search", Example("table_cube.prs"), "--controller", "planted-1-percnt", "--budget", "10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'planted-1-percent'"), std::string::npos) << r.err;
  // An --exec controller whose score is not a finite number: every episode says so.
  const std::string out = (dir_ / "nan.jsonl").string();
  r = Run({"search", Example("table_cube.prs"), "--exec",
           "echo '{\"outcome\": \"success\", \"score\": NaN}'", "--budget", "3", "-o", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const json& record : ReadRecords(out)) {
    EXPECT_EQ(record["outcome"], "bad-answer");
    EXPECT_NE(record["detail"].get<std::string>().find("finite number"), std::string::npos);
  }
}

TEST_F(PrsTest, DesignsGiveOtherValidScenesReproducibly) {
  const Result iid = Run({"sample", Example("table_cube.prs"), "-n", "50", "-s", "3"});
  ASSERT_EQ(iid.exit_code, 0) << iid.err;
  for (const std::string design : {"sobol", "halton", "lattice"}) {
    const Result a = Run({"sample", Example("table_cube.prs"), "-n", "50", "-s", "3", "--design",
                          design, "--threads", "1"});
    const Result b = Run({"sample", Example("table_cube.prs"), "-n", "50", "-s", "3", "--design",
                          design, "--threads", "2"});
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(a.out, b.out) << design;
    EXPECT_NE(a.out, iid.out) << design;
  }
  const Result r = Run({"sample", Example("table_cube.prs"), "--design", "sobel"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean 'sobol'"), std::string::npos) << r.err;
  const Result t = Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent",
                        "-n", "20", "--design", "halton", "-o", (dir_ / "t.jsonl").string()});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const std::vector<json> records = ReadRecords(dir_ / "t.jsonl");
  EXPECT_EQ(records[0]["coordinates"].size(), 11u);
  // A failure's regenerate command rewrites the scene the design gave it.
  const Result s = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                        "--budget", "300", "-s", "1", "-o", (dir_ / "s.jsonl").string()});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  for (const json& record : ReadRecords(dir_ / "s.jsonl")) {
    EXPECT_FALSE(record.contains("regenerate")) << "a searched scene is not (seed, index)'s";
  }
  const Result many =
      Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "-n", "600",
           "-s", "2", "--design", "sobol", "-o", (dir_ / "m.jsonl").string()});
  ASSERT_EQ(many.exit_code, 0) << many.err;
  int checked = 0;
  for (const json& record : ReadRecords(dir_ / "m.jsonl")) {
    if (!record.contains("regenerate")) continue;
    const std::string command = record["regenerate"];
    EXPECT_NE(command.find("--design sobol"), std::string::npos) << command;
    const Result again = Run({"sample", Example("table_cube.prs"), "-s", "2", "--design", "sobol",
                              "--index", std::to_string(record["index"].get<int>())});
    ASSERT_EQ(again.exit_code, 0);
    const json scene = json::parse(again.out);
    const Result planted = Run({"test", Example("table_cube.prs"), "--controller",
                                "planted-1-percent", "-s", "2", "--design", "sobol", "--start",
                                std::to_string(record["index"].get<int>()), "-n", "1"});
    EXPECT_NE(planted.out.find("planted-failure"), std::string::npos) << scene.dump();
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST_F(PrsTest, CheckListsTheSceneCoordinates) {
  const Result r = Run({"check", Example("table_cube.prs"), "--coordinates"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("11 scene coordinates"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Cube#5.position[1]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("table_cube.prs:17:1"), std::string::npos) << r.out;
  const std::string fixed = Write("fixed.prs", "Object at Vector3D(0, 0, 0)\n");
  const Result f = Run({"check", fixed, "--coordinates"});
  EXPECT_EQ(f.exit_code, 0);
  EXPECT_NE(f.out.find("no scene coordinates"), std::string::npos) << f.out;
}

TEST_F(PrsTest, NearDrawsSmallChangesOfOneEpisode) {
  const std::string results = (dir_ / "r.jsonl").string();
  Result r = Run({"search", Example("table_cube.prs"), "--controller", "planted-1-percent",
                  "--budget", "100", "-s", "2", "-o", results});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json episode = ReadRecords(results)[41];
  const double x = episode["features"]["Cube#5.x"], y = episode["features"]["Cube#5.y"];
  r = Run({"sample", Example("table_cube.prs"), "--near", results + ":42", "--scale", "0.01", "-n",
           "20", "-s", "5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::stringstream lines(r.out);
  int scenes = 0;
  for (std::string line; std::getline(lines, line); ++scenes) {
    const json scene = json::parse(line);  // kept alive: the loop reads into it
    for (const json& object : scene["objects"]) {
      if (object["class"] != "Cube") continue;
      // A 0.01 change of each coordinate moves the cube by centimetres, not across its tray.
      EXPECT_LT(std::hypot(object["position"][0].get<double>() - x,
                           object["position"][1].get<double>() - y),
                0.08);
    }
  }
  EXPECT_EQ(scenes, 20);
  r = Run({"sample", Example("table_cube.prs"), "--near", results + ":101"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("there is no line 101"), std::string::npos) << r.err;
  r = Run({"sample", Example("table_cube.prs"), "--near", results + ":99999999999999999999999"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no such line"), std::string::npos) << r.err;
  r = Run({"sample", Example("table_cube.prs"), "--near", results, "--like", results});
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(PrsTest, ReportNamesWhereTheControllerFails) {
  const std::string results = (dir_ / "r.jsonl").string();
  Result r = Run({"test", Example("table_cube.prs"), "--controller", "planted-1-percent", "-n",
                  "3000", "-s", "3", "-o", results});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"report", results});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The planted disk is the far corner of the cube's range: the report's strongest split is
  // about the cube (its position, or its distance or offset from another object).
  const size_t top = r.out.find("The strongest single split: **");
  ASSERT_NE(top, std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(top, 80).find("Cube#5"), std::string::npos) << r.out.substr(top, 200);
  EXPECT_NE(r.out.find("## Failure modes"), std::string::npos);
  const std::string md = (dir_ / "report.md").string();
  r = Run({"report", results, "-o", md});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "report.svg"));
  EXPECT_NE(ReadText(md).find("(report.svg)"), std::string::npos);
  // Bad input: a located message, exit 1.
  const std::string bad = Write("bad.jsonl", "{\"index\": 0, \"outcome\": \"success\"}\n[1, 2]\n");
  r = Run({"report", bad});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.jsonl:2: not an episode record"), std::string::npos) << r.err;
  r = Run({"report", (dir_ / "missing.jsonl").string()});
  EXPECT_EQ(r.exit_code, 1);
}

// prs compare: two controllers on the same scenes (the 1 % planted failure before, the 0.1 %
// one after), matched scene by scene; the counts are checked against the records themselves.
TEST_F(PrsTest, CompareMatchesTheScenesAndCountsFixedAndBroken) {
  const std::string before = (dir_ / "before.jsonl").string();
  const std::string after = (dir_ / "after.jsonl").string();
  const std::string other = (dir_ / "other.jsonl").string();
  for (const auto& [controller, out, seed] :
       {std::tuple{"planted-1-percent", before, "3"}, std::tuple{"planted-1-permille", after, "3"},
        std::tuple{"planted-1-permille", other, "4"}}) {
    const Result r = Run({"test", Example("table_cube.prs"), "--controller", controller, "-n",
                          "2000", "-s", seed, "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  int64_t fixed = 0, broke = 0;
  std::map<uint64_t, bool> failed_before;
  for (const nlohmann::json& j : ReadRecords(before)) {
    failed_before[j["index"].get<uint64_t>()] = j["outcome"] != "success";
  }
  for (const nlohmann::json& j : ReadRecords(after)) {
    const bool failed = j["outcome"] != "success";
    fixed += failed_before.at(j["index"].get<uint64_t>()) && !failed;
    broke += !failed_before.at(j["index"].get<uint64_t>()) && failed;
  }
  ASSERT_GT(fixed, 5);  // the 1 % disk fails about 20 of 2,000 scenes

  Result r = Run({"compare", before, after, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scenes"], 2000);
  EXPECT_EQ(j["mcnemar"]["fixed"], fixed);
  EXPECT_EQ(j["mcnemar"]["broke"], broke);
  EXPECT_EQ(j["fixed"].size(), static_cast<size_t>(fixed));
  EXPECT_LT(j["mcnemar"]["p"].get<double>(), 0.05);
  ASSERT_FALSE(j["fixed"].empty());
  // A fixed scene's regenerate command comes from the failing run's record.
  EXPECT_NE(j["fixed"][0]["regenerate"].get<std::string>().find("-s 3 --start "),
            std::string::npos);

  const std::string md = (dir_ / "compare.md").string();
  r = Run({"compare", before, after, "-o", md});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(ReadText(md).find("**" + std::to_string(fixed) + " fixed**"), std::string::npos);
  EXPECT_NE(r.err.find("2000 scenes compared"), std::string::npos) << r.err;

  // Bad input: other scenes, a file that is not records, a missing file.
  r = Run({"compare", before, other});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("before.jsonl:1: seed 3 index 0 is not in "), std::string::npos) << r.err;
  r = Run({"compare", before, Write("scenes.jsonl", "[1, 2]\n")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("scenes.jsonl:1: not an episode record"), std::string::npos) << r.err;
  r = Run({"compare", before, (dir_ / "missing.jsonl").string()});
  EXPECT_EQ(r.exit_code, 1);
}

}  // namespace
}  // namespace prs::cli
