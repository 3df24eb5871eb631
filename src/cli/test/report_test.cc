// Unit tests of the pieces behind `prs check`, `prs stats` and `prs search`: text tables, the
// progress line, the stats report in both forms (the outline and variation are in
// src/analysis), and the search's note on idle threads.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/progress.h"
#include "cli/search_report.h"
#include "cli/stats_report.h"
#include "cli/text_table.h"

namespace prs::cli {
namespace {

TEST(TextTableTest, AlignsColumnsByCodePoints) {
  TextTable table({"name", "count", "kind"}, "lrl");
  table.AddRow({"a", "5", "plane ∩ half-spaces"});
  table.AddRow({"longer", "12345", ""});
  EXPECT_EQ(table.Format(),
            "  name    count  kind\n"
            "  a           5  plane ∩ half-spaces\n"
            "  longer  12345\n");
}

// 20 episodes on 16 threads: a wave of 16, then 4 with 12 threads idle (20 / 32 = 62.5 %).
TEST(BatchUseNoteTest, NamesTheIdleShareAndTheBatchThatFillsEveryThread) {
  const std::string note = FormatBatchUseNote(20, 16);
  EXPECT_NE(note.find("generations of 20 run on 16 threads in 2 waves, the last of 4 episodes"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("busy about 62% of the time"), std::string::npos) << note;
  EXPECT_NE(note.find("--batch 32 keeps them all busy"), std::string::npos) << note;
  EXPECT_NE(FormatBatchUseNote(100, 64).find("--batch 128"), std::string::npos);
  // Nothing to say: one thread, a multiple of the threads, or at least 90 % busy.
  for (const auto& [batch, threads] :
       {std::pair{20, 1}, {32, 16}, {20, 2}, {200, 16}, {19, 2}, {37, 4}}) {
    EXPECT_EQ(FormatBatchUseNote(batch, threads), "") << batch << " on " << threads;
  }
  EXPECT_NE(FormatBatchUseNote(17, 16), "") << "17 on 16: 53 % busy";
}

TEST(ProgressLineTest, FitsTheWidthAndShowsTheCounts) {
  const std::string line = FormatProgressLine(250, 1000, 2.0, 80);
  EXPECT_LE(CalcDisplayWidth(line), 79u);
  EXPECT_NE(line.find(" 25%"), std::string::npos) << line;
  EXPECT_NE(line.find("250/1000 scenes"), std::string::npos) << line;
  EXPECT_NE(line.find("125/s"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 6s"), std::string::npos) << line;
  EXPECT_LE(CalcDisplayWidth(FormatProgressLine(5, 10, 1.0, 20)), 19u);
}

TEST(ProgressLineTest, HardSceneLineShowsAttemptsAndRejections) {
  const std::string line = FormatHardSceneLine(3, 10, 1'200'000, 1'199'000, 12.0, 100);
  EXPECT_EQ(line, "prs: scene 4 of 10: 1200000 attempts in 12s, 100000/s, 99.9% rejected");
  EXPECT_LE(CalcDisplayWidth(FormatHardSceneLine(3, 10, 5, 5, 1.0, 30)), 29u);
}

SamplingStats MakeStats() {
  SamplingStats stats;
  stats.file = "x.prs";
  stats.seed = 4;
  stats.threads = 2;
  stats.summary.scenes = 10;
  stats.summary.attempts = 16;
  stats.max_attempts_per_scene = 3;
  stats.seconds = 0.5;
  lang::Rejection collision{lang::RejectionKind::kCollision, "a and b", {0, 3, 4}, "", false};
  for (int i = 0; i < 4; ++i) stats.summary.rejections.Add(collision);
  lang::Rejection requirement{
      lang::RejectionKind::kRequirement, "require at x.prs:2", {0, 0, 1}, "", false};
  for (int i = 0; i < 2; ++i) stats.summary.rejections.Add(requirement);
  return stats;
}

TEST(StatsReportTest, TableHasRatesAndLocatedCulprits) {
  lang::SourceManager sources;
  sources.AddFile("x.prs", "abc def\nrequire False\n");
  const std::string table = FormatStatsTable(MakeStats(), sources);
  for (const char* expected :
       {"acceptance rate  62.50%", "(10 scenes in 16 attempts)", "1.60 mean, 3 max",
        "50.0 ms  (20 scenes/s; 500.0 ms in all)", "collision        4       25.00%",
        "total            6       37.50%", "x.prs:1:4", "x.prs:1:1"}) {
    EXPECT_NE(table.find(expected), std::string::npos) << expected << "\n" << table;
  }
  EXPECT_LT(table.find("a and b"), table.find("require at"));  // most frequent first
}

TEST(StatsReportTest, JsonHasTheSameCounts) {
  lang::SourceManager sources;
  sources.AddFile("x.prs", "abc def\nrequire False\n");
  const nlohmann::json stats = nlohmann::json::parse(FormatStatsJson(MakeStats(), sources));
  EXPECT_EQ(stats["scenes"], 10);
  EXPECT_EQ(stats["attempts"], 16);
  EXPECT_EQ(stats["rejections"]["total"], 6);
  EXPECT_EQ(stats["rejections"]["by_reason"]["collision"], 4);
  EXPECT_EQ(stats["rejections"]["by_culprit"][0]["culprit"], "a and b");
  EXPECT_EQ(stats["rejections"]["by_culprit"][0]["column"], 4);
  EXPECT_DOUBLE_EQ(stats["acceptance_rate"].get<double>(), 10.0 / 16);
  EXPECT_DOUBLE_EQ(stats["seconds_per_scene"].get<double>(), 0.05);
}

}  // namespace
}  // namespace prs::cli
