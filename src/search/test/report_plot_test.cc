// The report's picture: ticks at round values inside the data's range, labels with the
// decimals their step needs, and a scatter plot whose split line sits where the axis says the
// threshold is, with a legend that counts the points.
#include "search/report_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

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

}  // namespace
}  // namespace prs::search
