// The report's picture: ticks at round values inside the data's range, labels with the
// decimals their step needs, and a scatter plot whose split line sits where the axis says the
// threshold is, with a legend that counts the points.
#include "search/report_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "geometry/random.h"

namespace prs::search {
namespace {

// True when step is 1, 2 or 5 times a power of ten.
bool IsRoundStep(double step) {
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
  return std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 ||
         std::fabs(mantissa - 5) < 1e-9;
}

TEST(ReportPlotTest, TicksAreRoundEvenlySpacedAndInside) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {-0.927, 0.027}, {0, 1}, {1.3012, 1.3049}, {-1250, 18000}, {0.6, 0.61}, {-3, -2.2}}) {
    const std::vector<double> ticks = CalcAxisTicks(lo, hi);
    ASSERT_GE(ticks.size(), 3u) << lo << " " << hi;
    EXPECT_LE(ticks.size(), 11u) << lo << " " << hi;
    const double step = ticks[1] - ticks[0];
    EXPECT_TRUE(IsRoundStep(step)) << step;
    for (size_t k = 0; k < ticks.size(); ++k) {
      EXPECT_GE(ticks[k], lo);
      EXPECT_LE(ticks[k], hi);
      EXPECT_NEAR(ticks[k] / step, std::round(ticks[k] / step), 1e-6) << "a multiple of the step";
      if (k > 0) {
        EXPECT_NEAR(ticks[k] - ticks[k - 1], step, 1e-9 * std::fabs(hi - lo));
      }
    }
  }
  EXPECT_EQ(CalcAxisTicks(0.42, 1.45).size(), 5u) << "0.6, 0.8, …, 1.4; not 0.5 and 1.0 alone";
  EXPECT_EQ(CalcAxisTicks(2, 2), std::vector<double>{2});
  EXPECT_EQ(FormatTick(-0.2 + 0.2, 0.2), "0.0");  // never "-0.0"
  EXPECT_EQ(FormatTick(-0.75, 0.05), "-0.75");
  EXPECT_EQ(FormatTick(1200, 200), "1200");
  EXPECT_EQ(FormatTick(1.302, 0.001), "1.302");
}

TEST(ReportPlotTest, TheSplitLineSitsAtItsThresholdOnTheAxis) {
  // Failures where x <= -0.6; y is noise.
  geometry::Rng rng(3);
  FeatureTable table{{"Cube.x", "Cube.y"}, {}};
  std::vector<bool> failed;
  for (int i = 0; i < 400; ++i) {
    const double x = rng.Uniform(-0.9, 0), y = rng.Uniform(-0.4, 0.4);
    table.rows.push_back({x, y});
    failed.push_back(x <= -0.6);
  }
  const std::vector<Split> splits = RankSplits(table, failed);
  ASSERT_FALSE(splits.empty());
  ASSERT_EQ(splits[0].feature, 0);
  const std::string svg = FormatScatterSvg(table, failed, 0, 1, &splits[0]);

  // The x ticks' positions and values give the axis's map; the split line must be on it.
  std::vector<std::pair<double, double>> ticks;  // (pixel, value)
  const std::regex tick(R"re(class="x-tick" x="([-0-9.]+)" y="[-0-9.]+" [^>]*>([-0-9.]+)<)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tick); it != std::sregex_iterator();
       ++it) {
    ticks.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  }
  ASSERT_GE(ticks.size(), 3u) << svg;
  const double pixels_per_unit =
      (ticks.back().first - ticks.front().first) / (ticks.back().second - ticks.front().second);
  EXPECT_GT(pixels_per_unit, 0);
  std::smatch line;
  ASSERT_TRUE(std::regex_search(svg, line, std::regex(R"re(class="split" x1="([-0-9.]+)")re")));
  const double expected =
      ticks.front().first + (splits[0].threshold - ticks.front().second) * pixels_per_unit;
  EXPECT_NEAR(std::stod(line[1]), expected, 0.3) << "threshold " << splits[0].threshold;
  // The shaded side is the failing one (left of the line), and the label says the rule.
  std::smatch side;
  ASSERT_TRUE(std::regex_search(
      svg, side,
      std::regex(R"re(class="failure-side" x="([-0-9.]+)" y="[-0-9.]+" width="([-0-9.]+)")re")));
  EXPECT_NEAR(std::stod(side[1]) + std::stod(side[2]), std::stod(line[1]), 0.2);
  EXPECT_NE(svg.find("Cube.x ≤ -0.6"), std::string::npos) << svg;
  // The legend counts what is drawn.
  const int64_t failures = std::count(failed.begin(), failed.end(), true);
  EXPECT_NE(svg.find("failure (" + std::to_string(failures) + ")"), std::string::npos);
  EXPECT_NE(svg.find("success (" + std::to_string(400 - failures) + ")"), std::string::npos);
  size_t circles = 0;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) {
    ++circles;
  }
  EXPECT_EQ(circles, 400u + 2u) << "every point, and the legend's two";
  // Both axes are named.
  EXPECT_NE(svg.find("class=\"x-name\""), std::string::npos);
  EXPECT_NE(svg.find(">Cube.y (m)</text>"), std::string::npos) << "with its unit";
}

// The name on an SVG axis ("x-name" or "y-name"), without its unit.
std::string AxisName(const std::string& svg, const std::string& axis) {
  std::smatch name;
  if (!std::regex_search(svg, name,
                         std::regex("class=\"" + axis + "-name\"[^>]*>([^<]*)</text>"))) {
    return "";
  }
  const std::string text = name[1];
  return text.substr(0, text.rfind(" ("));
}

int Column(const FeatureTable& table, const std::string& name) {
  const auto it = std::find(table.names.begin(), table.names.end(), name);
  return it == table.names.end() ? -1 : static_cast<int>(it - table.names.begin());
}

// A cube c on a fixed table t, failing when x > 0.8 and y > 0.3: c-t.x is c.x less a constant,
// as good a split as c.x, and plotting one against the other draws a diagonal line that hides
// the corner where the failures are. The plot is c.x (or c-t.x) against c.y (or c-t.y).
TEST(ReportPlotTest, TheSecondFeatureIsNotAFunctionOfTheFirst) {
  geometry::Rng rng(11);
  std::vector<ReportRecord> records;
  for (int i = 0; i < 1500; ++i) {
    ReportRecord r;
    r.index = static_cast<uint64_t>(i);
    const double x = rng.Uniform01(), y = rng.Uniform01();
    r.features = {{"c.x", x}, {"c.y", y}, {"c.z", 0.8}, {"t.x", 0.4}, {"t.y", -0.25}};
    r.outcome = x > 0.8 && y > 0.3 ? "no-path" : "success";
    records.push_back(r);
  }
  const FeatureTable table = BuildFeatureTable(records);
  std::vector<bool> failed;
  for (const ReportRecord& r : records) failed.push_back(r.failed());
  const std::vector<Split> splits = RankSplits(table, failed);
  ASSERT_GE(splits.size(), 2u);
  const std::string first = table.names[splits[0].feature];
  ASSERT_TRUE(first == "c.x" || first == "c-t.x") << first;
  // The next ranked split is the same feature shifted: the old plot's choice.
  EXPECT_TRUE(AreRedundant(table, Column(table, "c.x"), Column(table, "c-t.x")));
  const int second = ChooseSecondPlotFeature(table, failed, splits);
  ASSERT_GE(second, 0);
  EXPECT_TRUE(table.names[second] == "c.y" || table.names[second] == "c-t.y")
      << table.names[second];

  // The report's picture says so on its axes.
  std::string svg;
  const std::string md = FormatFailureReport(records, {"r.jsonl", "out/r.svg"}, &svg);
  const std::string x_name = AxisName(svg, "x"), y_name = AxisName(svg, "y");
  EXPECT_TRUE(x_name == "c.x" || x_name == "c-t.x") << x_name;
  EXPECT_TRUE(y_name == "c.y" || y_name == "c-t.y") << y_name;
  EXPECT_NE(svg.find(">" + x_name + " (m)</text>"), std::string::npos) << "with its unit";
  EXPECT_NE(md.find("![" + y_name + " against " + x_name + "](r.svg)"), std::string::npos) << md;
  // The strongest split is the horizontal axis's, so its line is drawn.
  EXPECT_NE(svg.find("class=\"split\""), std::string::npos);
}

// One cause (x > 0.8), nothing else: the plot still has a second axis, and not c-t.x or the
// distance to the fixed table (a function of x when y barely varies).
TEST(ReportPlotTest, AOneFeatureFailureIsPlottedAgainstAnotherFeature) {
  geometry::Rng rng(12);
  FeatureTable table{{"c.x", "c-t.x", "dist(c, t)", "c.y", "u[0]"}, {}};
  std::vector<bool> failed;
  for (int i = 0; i < 800; ++i) {
    const double x = rng.Uniform01(), y = rng.Uniform(-0.01, 0.01);
    table.rows.push_back({x, x - 0.4, std::hypot(x + 1, y), y, rng.Uniform01()});
    failed.push_back(x > 0.8);
  }
  const std::vector<Split> splits = RankSplits(table, failed);
  ASSERT_FALSE(splits.empty());
  ASSERT_EQ(splits[0].feature, 0);
  const int second = ChooseSecondPlotFeature(table, failed, splits);
  EXPECT_TRUE(second == 3 || second == 4) << (second >= 0 ? table.names[second] : "none");
  // Nothing to plot against: every feature is the first one in disguise.
  const FeatureTable alike{{"c.x", "c-t.x"}, {{0.1, -0.3}, {0.5, 0.1}, {0.9, 0.5}, {0.2, -0.2}}};
  const std::vector<bool> alike_failed = {false, false, true, false};
  EXPECT_EQ(ChooseSecondPlotFeature(alike, alike_failed, {Split{0, 0.7}}), -1);
  EXPECT_EQ(ChooseSecondPlotFeature(alike, alike_failed, {}), -1);
}

TEST(ReportPlotTest, RedundantFeaturesAreFunctionsOfEachOtherOrNearlySo) {
  geometry::Rng rng(13);
  FeatureTable table{{"x", "affine", "noisy", "square", "distance", "other", "coarse"}, {}};
  for (int i = 0; i < 500; ++i) {
    const double x = rng.Uniform(-1, 1), other = rng.Uniform(-1, 1);
    table.rows.push_back({x, 3 - 2 * x, x + rng.Uniform(-0.05, 0.05), x * x,
                          std::hypot(x - 0.2, 0.05), other, std::floor(4 * other)});
  }
  EXPECT_TRUE(AreRedundant(table, 0, 0));
  EXPECT_TRUE(AreRedundant(table, 0, 1)) << "an affine function: r = -1";
  EXPECT_TRUE(AreRedundant(table, 0, 2)) << "|r| > 0.99";
  EXPECT_TRUE(AreRedundant(table, 0, 3)) << "x² is a function of x, though r is near 0";
  EXPECT_TRUE(AreRedundant(table, 4, 0)) << "either way round";
  EXPECT_FALSE(AreRedundant(table, 0, 5));
  EXPECT_FALSE(AreRedundant(table, 5, 0));
  EXPECT_FALSE(AreRedundant(table, 0, 6)) << "few values, each with every x";
  EXPECT_FALSE(AreRedundant(table, 6, 0));
  EXPECT_TRUE(AreRedundant(table, 5, 6)) << "coarse is floor(4 · other)";
  // Too few points in common, or a constant: nothing to draw.
  FeatureTable sparse{{"a", "b"}, {{0.1, NAN}, {0.2, 0.5}, {NAN, 0.7}, {0.4, 0.9}}};
  EXPECT_TRUE(AreRedundant(sparse, 0, 1));
}

}  // namespace
}  // namespace prs::search
