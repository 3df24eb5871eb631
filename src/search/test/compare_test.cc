// Paired comparison: McNemar's exact test against values worked by hand, its size under the
// null hypothesis by simulation, scenes matched by (seed, index) in any order, and the runs
// that cannot be compared refused with the file, line and scene.
#include "search/compare.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <random>

namespace prs::search {
namespace {

ReportRecord Record(uint64_t seed, uint64_t index, const std::string& outcome, int64_t line) {
  ReportRecord r;
  r.seed = seed;
  r.index = index;
  r.outcome = outcome;
  r.line = line;
  r.features = {{"c.x", 0.1 * static_cast<double>(index)}};
  return r;
}

TEST(CompareTest, McNemarExactPMatchesHandWorkedValues) {
  EXPECT_DOUBLE_EQ(CalcMcNemarExactP(0, 0), 1);
  EXPECT_DOUBLE_EQ(CalcMcNemarExactP(5, 5), 1);
  EXPECT_NEAR(CalcMcNemarExactP(7, 0), 2.0 / 128, 1e-12);                // 2 · (1/2)^7
  EXPECT_NEAR(CalcMcNemarExactP(10, 2), 2.0 * (1 + 12 + 66) / 4096, 1e-12);  // n = 12, k ≤ 2
  EXPECT_NEAR(CalcMcNemarExactP(2, 10), CalcMcNemarExactP(10, 2), 1e-15);  // two-sided
  EXPECT_DOUBLE_EQ(CalcMcNemarExactP(1, 0), 1);  // 2 · 1/2
  // Thousands of discordant scenes: no overflow, and a 55/45 split of 2,000 is significant.
  EXPECT_LT(CalcMcNemarExactP(1100, 900), 1e-5);
  EXPECT_GT(CalcMcNemarExactP(1010, 990), 0.5);
}

// Under "no difference" (each discordant scene fixed or broke by a fair coin) the test rejects
// at 5 % in at most 5 % of runs: it is exact, so conservative. 2,000 runs of 30 discordant
// scenes, a fixed seed; the exact size for n = 30 is 4.28 %.
TEST(CompareTest, McNemarRejectsAtMostFivePercentUnderTheNull) {
  std::mt19937_64 rng(7);
  std::bernoulli_distribution coin(0.5);
  int rejected = 0;
  const int runs = 2000;
  for (int run = 0; run < runs; ++run) {
    int fixed = 0;
    for (int k = 0; k < 30; ++k) fixed += coin(rng);
    rejected += CalcMcNemarExactP(fixed, 30 - fixed) < 0.05;
  }
  // Binomial(2000, 0.0428): mean 85.6, sd 9.0; 5 % would be 100.
  EXPECT_GT(rejected, 55);
  EXPECT_LT(rejected, 115);
}

TEST(CompareTest, MatchesScenesBySeedAndIndexInAnyOrder) {
  std::vector<ReportRecord> before = {Record(1, 0, "success", 1), Record(1, 1, "poor-grip", 2),
                                      Record(1, 2, "perception-fault", 3),
                                      Record(1, 3, "success", 4), Record(1, 4, "poor-grip", 5)};
  before[1].regenerate = "prs sample x.prs -s 1 --start 1 -n 1";
  // After: written in another order (more threads); 1 fixed, 0 broken, 3 → other failure.
  std::vector<ReportRecord> after = {Record(1, 4, "poor-grip", 1), Record(1, 3, "success", 2),
                                     Record(1, 2, "poor-grip", 3), Record(1, 1, "success", 4),
                                     Record(1, 0, "success", 5)};
  const PairedComparison c = ComparePairedRuns(before, "before.jsonl", after, "after.jsonl");
  ASSERT_EQ(c.scenes.size(), 5u);
  ASSERT_EQ(c.fixed.size(), 1u);
  EXPECT_EQ(c.before[c.fixed[0].before].index, 1u);
  EXPECT_EQ(c.after[c.fixed[0].after].index, 1u);
  EXPECT_TRUE(c.broke.empty());
  EXPECT_EQ(c.both_succeed, 2);
  EXPECT_EQ(c.both_fail, 2);
  ASSERT_EQ(c.changed_failure.size(), 1u);
  EXPECT_EQ(c.before[c.changed_failure[0].before].index, 2u);
  EXPECT_DOUBLE_EQ(c.mcnemar_p, 1);
  EXPECT_EQ(c.outcomes.front(), "success");

  const std::string md = FormatComparisonMarkdown(c);
  EXPECT_NE(md.find("| success | 2 (40.0 %) | 3 (60.0 %) | +1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("**1 fixed**"), std::string::npos) << md;
  EXPECT_NE(md.find("`prs sample x.prs -s 1 --start 1 -n 1`"), std::string::npos) << md;
  EXPECT_NE(md.find("No evidence at the 5 % level"), std::string::npos) << md;

  const nlohmann::json j = nlohmann::json::parse(FormatComparisonJson(c));
  EXPECT_EQ(j["scenes"], 5);
  EXPECT_EQ(j["outcomes"]["poor-grip"]["before"], 2);
  EXPECT_EQ(j["outcomes"]["poor-grip"]["after"], 2);
  EXPECT_EQ(j["fixed"][0]["index"], 1);
  EXPECT_EQ(j["fixed"][0]["regenerate"], "prs sample x.prs -s 1 --start 1 -n 1");
  EXPECT_EQ(j["mcnemar"]["fixed"], 1);
  EXPECT_EQ(j["mcnemar"]["broke"], 0);
}

TEST(CompareTest, ASignificantChangeIsSaidSo) {
  std::vector<ReportRecord> before, after;
  for (uint64_t i = 0; i < 40; ++i) {
    before.push_back(Record(2, i, i < 12 ? "timeout" : "success", static_cast<int64_t>(i + 1)));
    after.push_back(Record(2, i, i == 39 ? "timeout" : "success", static_cast<int64_t>(i + 1)));
  }
  const PairedComparison c = ComparePairedRuns(before, "b", after, "a");
  EXPECT_EQ(c.fixed.size(), 12u);
  EXPECT_EQ(c.broke.size(), 1u);
  EXPECT_NEAR(c.mcnemar_p, 2.0 * (1 + 13) / 8192, 1e-12);
  EXPECT_NE(FormatComparisonMarkdown(c).find("made a difference for the better"),
            std::string::npos);
}

TEST(CompareTest, RunsThatAreNotOfTheSameScenesAreRefused) {
  const std::vector<ReportRecord> run = {Record(1, 0, "success", 1), Record(1, 1, "success", 2)};
  const auto refused = [](std::vector<ReportRecord> b, std::vector<ReportRecord> a) {
    try {
      ComparePairedRuns(std::move(b), "before.jsonl", std::move(a), "after.jsonl");
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  // Another seed.
  std::vector<ReportRecord> other_seed = {Record(2, 0, "success", 1), Record(2, 1, "success", 2)};
  EXPECT_NE(refused(run, other_seed).find("before.jsonl:1: seed 1 index 0 is not in after.jsonl"),
            std::string::npos)
      << refused(run, other_seed);
  // Fewer scenes after.
  EXPECT_NE(refused(run, {run[0]}).find("before.jsonl:2: seed 1 index 1 is not in after.jsonl "
                                        "(2 scenes against 1)"),
            std::string::npos)
      << refused(run, {run[0]});
  // The same (seed, index), another scene (another program, or --settle on one side only).
  std::vector<ReportRecord> moved = run;
  moved[1].features = {{"c.x", 0.7}};
  EXPECT_NE(refused(run, moved).find("seed 1 index 1 is not the same scene in both runs: c.x is "
                                     "0.1 before and 0.7 after"),
            std::string::npos)
      << refused(run, moved);
  // Runs of two programs, or of other scene options, are refused as wholes, naming both sides.
  std::vector<ReportRecord> other_spec = run, spec = run;
  for (ReportRecord& r : spec) r.spec = "aaaa", r.scene_options = "";
  for (ReportRecord& r : other_spec) r.spec = "bbbb", r.scene_options = "";
  EXPECT_NE(refused(spec, other_spec)
                .find("the runs are not of the same scenes: before.jsonl has the program "
                      "fingerprint aaaa, scene options '', after.jsonl has the program "
                      "fingerprint bbbb"),
            std::string::npos)
      << refused(spec, other_spec);
  std::vector<ReportRecord> settled = spec;
  for (ReportRecord& r : settled) r.scene_options = "--settle=3";
  EXPECT_NE(refused(spec, settled).find("scene options '--settle=3'"), std::string::npos)
      << refused(spec, settled);
  std::vector<ReportRecord> mixed = spec;
  mixed[1].spec = "bbbb";
  EXPECT_NE(refused(mixed, spec).find("before.jsonl:2: the record has the program fingerprint "
                                      "bbbb"),
            std::string::npos)
      << refused(mixed, spec);
  // Without fingerprints, other objects are other scenes, not a vacuous match.
  std::vector<ReportRecord> other_objects = run;
  for (ReportRecord& r : other_objects) r.features = {{"d.x", 0.5}};
  EXPECT_NE(refused(run, other_objects).find("not the same scene in both runs: before.jsonl has c"),
            std::string::npos)
      << refused(run, other_objects);
  // A replay of the failures alone is refused with what to do instead.
  std::vector<ReportRecord> replayed = {run[0]};
  replayed[0].replay_of = "before.jsonl";
  replayed[0].replay_failed_only = true;
  EXPECT_NE(refused(run, replayed).find("after.jsonl:1: the run replays only the failures of "
                                        "before.jsonl"),
            std::string::npos)
      << refused(run, replayed);
  // A scene twice, a record without a seed.
  EXPECT_NE(refused({run[0], run[0]}, run).find("before.jsonl:1: seed 1 index 0 is also on line 1"),
            std::string::npos)
      << refused({run[0], run[0]}, run);
  std::vector<ReportRecord> no_seed = run;
  no_seed[1].seed.reset();
  EXPECT_NE(refused(run, no_seed).find("after.jsonl:2: the record has no \"seed\""),
            std::string::npos);
}

}  // namespace
}  // namespace prs::search
