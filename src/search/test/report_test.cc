// Failure reports on synthetic records with a planted cause: the top split names the planted
// feature and threshold, two separate causes give two failure modes, each outcome's interval is
// the exact binomial one, and a malformed results file is a located error.
#include "search/report.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/random.h"
#include "harness/harness.h"
#include "search/estimate.h"

namespace prs::search {
namespace {

// Records with a cube, a tray and a camera at random; the cube fails when it is far left
// (x <= -0.75) and, with `second_cause`, also when far back (y > 0.3).
std::vector<std::string> SyntheticRecords(int n, bool second_cause) {
  geometry::Rng rng(5);
  std::vector<std::string> lines;
  for (int i = 0; i < n; ++i) {
    harness::EpisodeRecord r;
    r.index = static_cast<uint64_t>(i);
    const double x = rng.Uniform(-0.9, 0), y = rng.Uniform(-0.4, 0.4);
    r.features = {{"t.x", 0.0},
                  {"t.y", 0.0},
                  {"Cube#5.x", x},
                  {"Cube#5.y", y},
                  {"Camera#6.z", rng.Uniform(1.9, 2.1)},
                  {"tr_1.x", rng.Uniform(-0.7, -0.2)},
                  {"tr_1.y", rng.Uniform(-0.1, 0.1)}};
    const bool fails = x <= -0.75 || (second_cause && y > 0.3);
    r.result.outcome = fails ? "no-path" : "success";
    r.coordinates = {rng.Uniform01(), (x + 0.9) / 0.9};
    lines.push_back(harness::FormatRecordJson(r));
  }
  return lines;
}

TEST(ReportTest, TheTopSplitNamesThePlantedFeature) {
  const auto records = ParseReportRecords(SyntheticRecords(2000, false), "r.jsonl");
  const FeatureTable table = BuildFeatureTable(records);
  // t.x and t.y never vary, so they are dropped; distances and offsets are added.
  EXPECT_EQ(std::count(table.names.begin(), table.names.end(), "t.x"), 0);
  EXPECT_EQ(std::count(table.names.begin(), table.names.end(), "dist(Cube#5, tr_1)"), 1);
  std::vector<bool> failed;
  for (const auto& r : records) failed.push_back(r.failed());
  const std::vector<Split> splits = RankSplits(table, failed);
  ASSERT_FALSE(splits.empty());
  // Cube#5.x, or a feature equal to it up to a fixed shift (the offset from the fixed table,
  // or the coordinate u[1] made from it).
  const std::string top = table.names[splits[0].feature];
  EXPECT_TRUE(top == "Cube#5.x" || top == "Cube#5-t.x" || top == "u[1]") << top;
  const Split& s = splits[0];
  EXPECT_TRUE(s.failures_below);
  EXPECT_EQ(s.failures_side, s.n_side);  // every episode on that side fails
  EXPECT_EQ(s.failures_other, 0);
  const std::string md = FormatFailureReport(records, {"r.jsonl", ""}, nullptr);
  EXPECT_NE(md.find("The strongest single split: **"), std::string::npos) << md;
  EXPECT_NE(md.find("≤ -0.74"), std::string::npos) << md;  // the threshold, -0.7498
  EXPECT_NE(md.find("one mode"), std::string::npos) << md;
  // Each outcome's row carries its exact binomial interval: each bound leaves 2.5 % in its
  // tail, found here by bisection on a binomial sum written in this test.
  int64_t failures = 0;
  for (const auto& r : records) failures += r.failed();
  const auto tail_at_least = [&](int64_t k, double p) {
    double sum = 0;
    for (int64_t i = k; i <= 2000; ++i) {
      sum += std::exp(std::lgamma(2001.0) - std::lgamma(i + 1.0) - std::lgamma(2001.0 - i) +
                      i * std::log(p) + (2000 - i) * std::log1p(-p));
    }
    return sum;
  };
  const auto bisect = [](auto increasing, double target) {
    double a = 0, b = 1;
    for (int i = 0; i < 100; ++i) (increasing((a + b) / 2) < target ? a : b) = (a + b) / 2;
    return (a + b) / 2;
  };
  const double lo = bisect([&](double p) { return tail_at_least(failures, p); }, 0.025);
  const double hi = bisect([&](double p) { return tail_at_least(failures + 1, p); }, 0.975);
  EXPECT_NE(md.find(fmt::format("| no-path | {} | {:.1f} % | {:#.3g} % – {:#.3g} % |", failures,
                                100.0 * failures / 2000, 100 * lo, 100 * hi)),
            std::string::npos)
      << md;
}

TEST(ReportTest, TwoCausesGiveTwoFailureModes) {
  const auto records = ParseReportRecords(SyntheticRecords(3000, true), "r.jsonl");
  const FeatureTable table = BuildFeatureTable(records);
  std::vector<bool> failed;
  for (const auto& r : records) failed.push_back(r.failed());
  const std::vector<FailureMode> modes = FindFailureModes(table, failed);
  ASSERT_EQ(modes.size(), 2u);
  // One mode is far left, the other far back: their representatives say so.
  int x_column = -1, y_column = -1;
  for (size_t f = 0; f < table.names.size(); ++f) {
    if (table.names[f] == "Cube#5.x") x_column = static_cast<int>(f);
    if (table.names[f] == "Cube#5.y") y_column = static_cast<int>(f);
  }
  ASSERT_GE(x_column, 0);
  ASSERT_GE(y_column, 0);
  int left = 0, back = 0;
  for (const FailureMode& mode : modes) {
    const auto& row = table.rows[mode.representative];
    EXPECT_TRUE(failed[mode.representative]);
    left += row[x_column] <= -0.75 && row[y_column] <= 0.3;
    back += row[y_column] > 0.3 && row[x_column] > -0.75;
  }
  EXPECT_EQ(left, 1);
  EXPECT_EQ(back, 1);
  std::string svg;
  const std::string md = FormatFailureReport(records, {"r.jsonl", "out/report.svg"}, &svg);
  EXPECT_NE(md.find("2 modes"), std::string::npos) << md;
  EXPECT_NE(md.find("![Cube#5"), std::string::npos) << md;
  EXPECT_NE(md.find("(report.svg)"), std::string::npos) << md;
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("#d62728"), std::string::npos);  // failures are drawn
}

TEST(ReportTest, BadInput) {
  try {
    ParseReportRecords({"{\"index\": 1, \"outcome\": \"success\"}", "oops"}, "r.jsonl");
    ADD_FAILURE() << "a malformed line was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("r.jsonl:2: not an episode record"), std::string::npos);
  }
  EXPECT_THROW(ParseReportRecords({"", "  "}, "r.jsonl"), std::runtime_error);
  const auto all_success = ParseReportRecords({"{\"index\": 0, \"outcome\": \"success\"}"}, "r");
  EXPECT_NE(FormatFailureReport(all_success, {"r", ""}, nullptr).find("Every episode succeeded"),
            std::string::npos);
}

// Records drawn from a known proposal over one coordinate u: half uniform, half uniform on
// [0, 0.02); failing when u < 0.01, so the probability under the program's law is 1 %.
std::vector<std::string> ImportanceRecords(int n) {
  geometry::Rng rng(8);
  std::vector<std::string> lines;
  for (int i = 0; i < n; ++i) {
    harness::EpisodeRecord r;
    r.index = static_cast<uint64_t>(i);
    const double u = rng.Uniform01() < 0.5 ? rng.Uniform01() : 0.02 * rng.Uniform01();
    const double density = 0.5 + (u < 0.02 ? 0.5 / 0.02 : 0.0);
    r.coordinates = {u};
    r.features = {{"Cube.x", u}, {"Cube.y", rng.Uniform01()}};
    r.result.outcome = u < 0.01 ? "planted-failure" : "success";
    r.search = {{"strategy", "importance"},
                {"phase", "sampling"},
                {"weight", 1 / density},
                {"uniform_share", 0.5},
                {"normalised", false}};
    lines.push_back(harness::FormatRecordJson(r));
  }
  return lines;
}

TEST(ReportTest, WeightedRecordsPutTheEstimateFirst) {
  const auto records = ParseReportRecords(ImportanceRecords(2000), "e.jsonl");
  const Estimate e = CalcEstimate(SelectWeightedRecords(records, "e.jsonl", "").records);
  ASSERT_EQ(e.outcomes.size(), 1u);
  EXPECT_LE(e.outcomes[0].ci_low, 0.01);
  EXPECT_GE(e.outcomes[0].ci_high, 0.01);
  const std::string md = FormatFailureReport(records, {"e.jsonl", ""}, nullptr);
  const size_t estimate = md.find("## How often it fails (importance-sampling estimate)");
  ASSERT_NE(estimate, std::string::npos) << md;
  const size_t row = md.find(fmt::format("| planted-failure | {:#.3g} % | {:#.3g} % – {:#.3g} % |",
                                         100 * e.outcomes[0].p, 100 * e.outcomes[0].ci_low,
                                         100 * e.outcomes[0].ci_high));
  EXPECT_NE(row, std::string::npos) << md;
  EXPECT_LT(row, md.find("| outcome | episodes |")) << "the estimate precedes the shares";
  // Nearly half the records fail, yet the probability is 1 %: the report says the shares are not
  // rates.
  EXPECT_NE(md.find("not the program's rates"), std::string::npos) << md;

  // A search's records: no estimate, and the report says why; i.i.d. records: the shares are.
  std::vector<std::string> searched = SyntheticRecords(200, false);
  for (std::string& line : searched) {
    line.insert(line.rfind('}'), ", \"search\": {\"strategy\": \"cross-entropy\"}");
  }
  const std::string search_md =
      FormatFailureReport(ParseReportRecords(searched, "s.jsonl"), {"s.jsonl", ""}, nullptr);
  EXPECT_EQ(search_md.find("How often it fails"), std::string::npos) << search_md;
  EXPECT_NE(search_md.find("These are records of a search"), std::string::npos) << search_md;
  const std::string iid_md = FormatFailureReport(
      ParseReportRecords(SyntheticRecords(200, false), "i.jsonl"), {"i.jsonl", ""}, nullptr);
  EXPECT_NE(iid_md.find("## How often it fails\n\nThe scenes were drawn independently from the "
                        "program's law"),
            std::string::npos)
      << iid_md;

  // A weighted record without its weight is a located error.
  std::vector<std::string> broken = ImportanceRecords(3);
  broken[1] =
      "{\"index\": 1, \"outcome\": \"success\", \"search\": {\"strategy\": "
      "\"importance\", \"weight\": \"heavy\"}}";
  try {
    ParseReportRecords(broken, "e.jsonl");
    ADD_FAILURE() << "a record without a weight was accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("e.jsonl:2: an importance-sampling record"),
              std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace prs::search
