// End-to-end tests of --sampler gibbs: the same scenes for any thread count and index range,
// the notes and the stats that say the scenes are correlated, a test run's records that
// regenerate their scenes (and replay to the same records), and the commands that draw scenes at
// given points refusing it.
#include <nlohmann/json.hpp>

#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

// Ten 5 cm cubes at any yaw on a 0.5 x 0.4 m bin.
constexpr const char* kBin =
    "from model import *\n"
    "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
    "for i in range(10):\n"
    "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n";

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

TEST_F(PrsTest, GibbsScenesAreTheSameForAnyThreadsAndRange) {
  const std::string file = Write("bin.prs", kBin);
  const std::string include = (RepoRoot() / "examples").string();
  const auto sample = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"sample",    file,    "-I", include,
                                     "--sampler", "gibbs", "-s", "3"};
    args.insert(args.end(), extra.begin(), extra.end());
    return Run(args);
  };
  const Result one = sample({"-n", "40", "--threads", "1"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.err.find("correlated, not independent"), std::string::npos) << one.err;
  const Result two = sample({"-n", "40", "--threads", "2"});
  EXPECT_EQ(two.out, one.out);
  const Result tail = sample({"--start", "25", "-n", "15", "--threads", "2"});
  const auto all = Lines(one.out), part = Lines(tail.out);
  ASSERT_EQ(all.size(), 40u);
  ASSERT_EQ(part.size(), 15u);
  for (size_t i = 0; i < part.size(); ++i) EXPECT_EQ(part[i], all[25 + i]) << i;
  EXPECT_NE(all[0], all[1]);
}

TEST_F(PrsTest, GibbsStatsSayWhatTheScenesAreWorth) {
  const std::string file = Write("bin.prs", kBin);
  const Result r = Run({"stats", file, "-I", (RepoRoot() / "examples").string(), "--sampler",
                        "gibbs", "-n", "200", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json stats = json::parse(r.out);
  EXPECT_EQ(stats["sampler"], "gibbs");
  const double effective = stats["gibbs"]["effective_scenes"].get<double>();
  EXPECT_GT(effective, 0);
  EXPECT_LE(effective, 200);
  EXPECT_GE(stats["gibbs"]["autocorrelation_sweeps"].get<double>(), 1);
  EXPECT_EQ(stats["gibbs"]["blocks"], 10);
  const Result table = Run(
      {"stats", file, "-I", (RepoRoot() / "examples").string(), "--sampler", "gibbs", "-n", "50"});
  EXPECT_NE(table.out.find("correlated scenes"), std::string::npos) << table.out;
  const Result plain =
      Run({"stats", file, "-I", (RepoRoot() / "examples").string(), "-n", "5", "--json"});
  EXPECT_EQ(json::parse(plain.out)["sampler"], "rejection");
}

TEST_F(PrsTest, GibbsRecordsRegenerateTheirScenes) {
  const std::string file = Write("bin.prs", kBin);
  const std::string include = (RepoRoot() / "examples").string();
  const std::string records = (dir_ / "r.jsonl").string();
  Result r = Run({"test", file, "-I", include, "--sampler", "gibbs", "--exec", "false", "-n", "12",
                  "-s", "4", "-o", records});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(ReadText(records));
  ASSERT_EQ(lines.size(), 12u);
  const json record = json::parse(lines[9]);
  const std::string regenerate = record["regenerate"].get<std::string>();
  EXPECT_NE(regenerate.find("--sampler gibbs"), std::string::npos) << regenerate;
  const Result sampled = Run(
      {"sample", file, "-I", include, "--sampler", "gibbs", "-s", "4", "--start", "9", "-n", "1"});
  ASSERT_EQ(sampled.exit_code, 0) << sampled.err;
  const json scene = json::parse(sampled.out);
  EXPECT_EQ(scene["index"], 9);
  // The record's features are the scene's: the first cube's position.
  EXPECT_EQ(record["features"]["Cube#1.x"], scene["objects"][1]["position"][0]);
  // --replay regenerates every record's scene at its coordinates (a chain's scene is a point
  // like any other) and gives the same records.
  const std::string replayed = (dir_ / "replayed.jsonl").string();
  r = Run({"test", file, "-I", include, "--replay", records, "--exec", "false", "-o", replayed});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> again = Lines(ReadText(replayed));
  ASSERT_EQ(again.size(), lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    const json before = json::parse(lines[i]), after = json::parse(again[i]);
    EXPECT_EQ(after["index"], before["index"]) << i;
    EXPECT_EQ(after["coordinates"], before["coordinates"]) << i;
    EXPECT_EQ(after["features"], before["features"]) << i;
    EXPECT_EQ(after["outcome"], before["outcome"]) << i;
  }
}

TEST_F(PrsTest, GibbsIsRefusedWhereScenesAreDrawnAtGivenPoints) {
  const std::string file = Write("bin.prs", kBin);
  const Result r = Run({"sample", file, "-I", (RepoRoot() / "examples").string(), "--sampler",
                        "gibbs", "--design", "sobol", "-n", "4"});
  EXPECT_EQ(r.exit_code, 2) << "a usage error: " << r.err;
  EXPECT_EQ(r.err.rfind("prs: error: --sampler gibbs cannot be used with --design sobol: ", 0), 0u)
      << r.err;
  const Result bad = Run({"sample", file, "--sampler", "metropolis"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--sampler"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace prs::cli
