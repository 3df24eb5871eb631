// Tests of the scenario analysis behind `prs check` and Scenario.check(): the static outline
// (sites, names, region kinds) and the properties observed to vary between scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "analysis/property_variation.h"
#include "analysis/scenario_outline.h"
#include "sampling/sampler.h"

namespace prs::analysis {
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

}  // namespace
}  // namespace prs::analysis
