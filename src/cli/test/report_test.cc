// Unit tests of the pieces behind `prs check` and `prs stats`: text tables, the progress
// line, the static outline (sites, names, region kinds), the observed variation, and the
// stats report in both forms.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "cli/progress.h"
#include "cli/property_variation.h"
#include "cli/scenario_outline.h"
#include "cli/stats_report.h"
#include "cli/text_table.h"
#include "sampling/sampler.h"

namespace prs::cli {
namespace {

std::string RepoPath(const std::string& relative) {
  const char* root = std::getenv("PRS_SOURCE_DIR");
  return std::string(root ? root : PRS_DEFAULT_SOURCE_DIR) + "/" + relative;
}

std::unique_ptr<lang::CompiledProgram> Compile(const std::string& text) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {RepoPath("examples")};
  auto program = lang::CompileText("scenario.prs", text, options, diagnostics);
  EXPECT_FALSE(diagnostics.has_errors());
  return diagnostics.has_errors() ? nullptr : std::move(program);
}

const CreationSite* FindSite(const ScenarioOutline& outline, const std::string& variable) {
  for (const CreationSite& site : outline.sites) {
    if (site.variable == variable) return &site;
  }
  return nullptr;
}

TEST(TextTableTest, AlignsColumnsByCodePoints) {
  TextTable table({"name", "count", "kind"}, "lrl");
  table.AddRow({"a", "5", "plane ∩ half-spaces"});
  table.AddRow({"longer", "12345", ""});
  EXPECT_EQ(table.Format(),
            "  name    count  kind\n"
            "  a           5  plane ∩ half-spaces\n"
            "  longer  12345\n");
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

TEST(ScenarioOutlineTest, ListsSitesWithNamesClassesAndRegionKinds) {
  auto program = Compile(
      "from model import *\n"
      "t = Table on V3D(0, 0, 0)\n"
      "tr = Tray completely on t, left of t\n"
      "for i in range(2):\n"
      "    Cube on tr\n"
      "c = Cube in Cuboid(V3D(0, 0, 1), V3D(0, 0, 0), 1, 1, 1)\n"
      "p = Cube at V3D(0, 0, 2), left of t\n"
      "d = Chair\n");
  ASSERT_NE(program, nullptr);
  const ScenarioOutline outline = OutlineScenario(*program);
  ASSERT_EQ(outline.sites.size(), 6u);
  EXPECT_EQ(outline.sites[0].class_name, "Table");
  EXPECT_EQ(FindSite(outline, "t")->position_region, "point");
  const CreationSite* tray = FindSite(outline, "tr");
  ASSERT_NE(tray, nullptr);
  EXPECT_EQ(tray->position_specifiers, (std::vector<std::string>{"completely on", "left of"}));
  EXPECT_EQ(tray->position_region.rfind("region (plane ∩ half-spaces", 0), 0u)
      << tray->position_region;
  EXPECT_FALSE(outline.sites[2].variable.has_value());  // the Cube in the loop
  EXPECT_EQ(outline.sites[2].class_name, "Cube");
  EXPECT_EQ(FindSite(outline, "c")->position_region, "region (Cuboid(...) ∩ workspace)");
  EXPECT_EQ(FindSite(outline, "p")->position_region, "point, checked against half-space");
  EXPECT_EQ(FindSite(outline, "d")->position_region, "class default");
  ASSERT_FALSE(outline.classes.empty());
  EXPECT_EQ(outline.classes.front().name, "Table");
  EXPECT_EQ(outline.classes.front().parent, "Object");
}

TEST(VariationObserverTest, FindsRandomPropertiesPerSiteAndOccurrence) {
  auto program = Compile(
      "from model import *\n"
      "t = Table on V3D(0, 0, 0)\n"
      "for i in range(2):\n"
      "    Cube at V3D(i - 0.5, 0, 1)\n"
      "b = Bowl on t\n");
  ASSERT_NE(program, nullptr);
  const ScenarioOutline outline = OutlineScenario(*program);
  sampling::SceneSampler sampler(*program);
  VariationObserver observer;
  for (uint64_t i = 0; i < 10; ++i) observer.Observe(sampler.Sample(1, i).scene);
  EXPECT_EQ(observer.scenes(), 10);
  const auto& sites = observer.sites();
  const SiteVariation& table = sites.at(FindSite(outline, "t")->key);
  EXPECT_TRUE(table.varied.empty());
  const SiteVariation& cubes = sites.at(outline.sites[1].key);
  EXPECT_EQ(cubes.min_objects, 2);
  EXPECT_EQ(cubes.max_objects, 2);
  EXPECT_TRUE(cubes.varied.empty()) << "the k-th cube is compared with the k-th cube";
  const SiteVariation& bowl = sites.at(FindSite(outline, "b")->key);
  for (const char* property : {"position", "width", "length"}) {
    EXPECT_NE(std::find(bowl.varied.begin(), bowl.varied.end(), property), bowl.varied.end())
        << property;
  }
  EXPECT_EQ(std::find(bowl.varied.begin(), bowl.varied.end(), "color"), bowl.varied.end());
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
