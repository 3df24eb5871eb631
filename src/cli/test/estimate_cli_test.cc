// End-to-end tests of `prs estimate`: the table and --json of a planted failure, the same
// estimate again from the record file alone (--from), the bound when nothing fails, and bad
// requests (a budget too small, search records, another program's records).
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli/test/json_lines.h"
#include "cli/test/prs_test_fixture.h"

namespace prs::cli {
namespace {

using nlohmann::json;

TEST_F(PrsTest, EstimatePrintsAnIntervalAndTheRecordsGiveItAgain) {
  const std::string records = (dir_ / "estimate.jsonl").string();
  Result r = Run({"estimate", Example("table_cube.prs"), "--controller", "planted-1-percent",
                  "--budget", "1000", "-s", "2", "--json", "-o", records});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = json::parse(r.out);
  const json& e = out["estimates"]["planted-failure"];
  const double p = e["p"].get<double>();
  EXPECT_GT(p, 0.005);
  EXPECT_LT(p, 0.02) << "1.02 % by 2,000,000 i.i.d. episodes";
  EXPECT_LE(e["ci95"][0].get<double>(), p);
  EXPECT_GE(e["ci95"][1].get<double>(), p);
  EXPECT_GT(e["iid_episodes_for_same_precision"].get<double>(), 1000);
  EXPECT_TRUE(out["reliable"].get<bool>());
  const std::vector<json> lines = ReadRecords(records);
  ASSERT_EQ(lines.size(), 1000u);
  EXPECT_EQ(lines.back()["search"]["strategy"], "importance");
  EXPECT_GT(lines.back()["search"]["weight"].get<double>(), 0);

  r = Run({"estimate", "--from", records, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out), out) << "the record file alone gives the same estimate";
  r = Run({"estimate", Example("table_cube.prs"), "--from", records});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("planted-failure"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("95% interval"), std::string::npos) << r.out;
  r = Run({"estimate", Example("constructs.prs"), "--from", records});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("drawn from another program"), std::string::npos) << r.err;

  // prs report puts the same estimate at its top, and a picture with axes beside it.
  const std::string report = (dir_ / "report.md").string();
  r = Run({"report", records, "-o", report});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = ReadText(report);
  const size_t top = md.find("## How often it fails (importance-sampling estimate)");
  ASSERT_NE(top, std::string::npos) << md;
  EXPECT_LT(top, md.find("| outcome | episodes |")) << "the estimate comes first";
  EXPECT_NE(
      md.find(fmt::format("| planted-failure | {:#.3g} % | {:#.3g} % – {:#.3g} % |", 100 * p,
                          100 * e["ci95"][0].get<double>(), 100 * e["ci95"][1].get<double>())),
      std::string::npos)
      << md;
  const std::string svg = ReadText(dir_ / "report.svg");
  EXPECT_NE(svg.find("class=\"x-tick\""), std::string::npos);
  EXPECT_NE(svg.find("class=\"split\""), std::string::npos);
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
}

TEST_F(PrsTest, EstimateWithoutFailuresGivesABoundAndRefusesBadRequests) {
  Result r =
      Run({"estimate", Example("table_cube.prs"), "--exec", "true", "--budget", "200", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = json::parse(r.out);
  EXPECT_TRUE(out["estimates"].empty());
  const double n = out["episodes"].get<double>();
  EXPECT_NEAR(out["upper_bound_95"].get<double>(), 1 - std::pow(0.05, 1 / n), 1e-12)
      << "no failure found: the program's own law, and the rule of three";
  EXPECT_NE(r.err.find("reports no score"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("upper bound"), std::string::npos) << r.err;

  r = Run({"estimate", Example("table_cube.prs"), "--controller", "demo-reach", "--budget", "50"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(">= 200"), std::string::npos) << r.err;
  const std::string searched = (dir_ / "search.jsonl").string();
  ASSERT_EQ(Run({"search", Example("table_cube.prs"), "--controller", "demo-reach", "--budget",
                 "20", "-o", searched})
                .exit_code,
            0);
  r = Run({"estimate", "--from", searched});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not drawn from the program's law"), std::string::npos) << r.err;
  r = Run({"estimate", "--budget", "300"});
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace prs::cli
