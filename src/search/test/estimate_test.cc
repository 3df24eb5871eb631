// prs estimate's statistics: the mixture's density is the one its points are drawn from, the
// estimator's hand computations, and coverage against known truths — a corner of a triangle
// that rejects half the attempts (exact in closed form), and Table-Cube's planted failures —
// with the intervals covering in at least 17 of 20 seeds and the error beating i.i.d. sampling.
#include "search/estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "harness/registry.h"
#include "sampling/test/scene_checks.h"
#include "search/intervals.h"

namespace prs::search {
namespace {

using sampling::testing_checks::CompileOrDie;

TEST(MixtureProposalTest, ItsPointsFollowItsDensity) {
  // E_q[1 / q] = 1 exactly when q is the density the points are drawn from; and a coordinate's
  // share in [0, 0.1) matches the density's integral there.
  MixtureProposal proposal;
  proposal.mean = {0.1, 0.7};
  proposal.std = {0.05, 0.2};
  proposal.uniform_share = 0.2;
  const MixturePoints points(proposal);
  const int n = 200'000;
  double sum_inverse = 0;
  int low = 0;
  for (int i = 0; i < n; ++i) {
    double u[2];
    ASSERT_TRUE(points.Point(3, uint64_t(i), 0, u));
    ASSERT_TRUE(u[0] >= 0 && u[0] < 1 && u[1] >= 0 && u[1] < 1);
    sum_inverse += 1 / proposal.CalcDensity(u);
    low += u[0] < 0.1;
  }
  EXPECT_NEAR(sum_inverse / n, 1.0, 0.01);
  // P(u0 < 0.1) = 0.2 * 0.1 + 0.8 * (Phi(0) - Phi(-2)) / (Phi(18) - Phi(-2)).
  const double phi_m2 = 0.5 * std::erfc(2 / std::sqrt(2.0));
  const double expected = 0.02 + 0.8 * (0.5 - phi_m2) / (1 - phi_m2);
  EXPECT_NEAR(double(low) / n, expected, 4 * std::sqrt(expected / n));
}

TEST(MixtureProposalTest, PerCentreSpreadsAndTheWideLayerFollowItsDensity) {
  // Two centres with their own spreads, a wide layer of 30 % three times wider, and a second
  // coordinate that stays uniform (std 0).
  MixtureProposal proposal{.mean = {0.5, 0.5},
                           .std = {1, 0},
                           .uniform_share = 0.2,
                           .centres = {{0.2, 0.5}, {0.8, 0.5}},
                           .centre_std = {{0.05, 0}, {0.02, 0}},
                           .wide_share = 0.3,
                           .wide_factor = 3};
  const MixturePoints points(proposal);
  const int n = 200'000;
  double sum_inverse = 0;
  int low = 0, second_low = 0;
  for (int i = 0; i < n; ++i) {
    double u[2];
    ASSERT_TRUE(points.Point(5, uint64_t(i), 0, u));
    sum_inverse += 1 / proposal.CalcDensity(u);
    low += u[0] < 0.3;
    second_low += u[1] < 0.3;
  }
  EXPECT_NEAR(sum_inverse / n, 1.0, 0.01);
  // P(u0 < 0.3), from the normal CDF truncated to [0, 1] per layer and centre.
  const auto phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  const auto cdf = [&](double x, double mean, double std) {
    return (phi((x - mean) / std) - phi(-mean / std)) / (phi((1 - mean) / std) - phi(-mean / std));
  };
  const auto layers = [&](double mean, double std) {
    return 0.7 * cdf(0.3, mean, std) + 0.3 * cdf(0.3, mean, 3 * std);
  };
  const double expected = 0.2 * 0.3 + 0.8 * 0.5 * (layers(0.2, 0.05) + layers(0.8, 0.02));
  EXPECT_NEAR(double(low) / n, expected, 4 * std::sqrt(expected / n));
  EXPECT_NEAR(double(second_low) / n, 0.3, 4 * std::sqrt(0.3 / n));
}

TEST(CalcEstimateTest, TheVarianceIsAtLeastWhatTheDrawsNearestToFailingSay) {
  // 10 failures of weight 0.1 in 1,000 plain-mean draws (p = 1 / 1000 whatever the successes
  // weigh). With successes of weight 1, the draws nearest to failing, 3 times the failures'
  // weight, are the 10 failures and the two successes of score 0.1: their mean weight,
  // sum w^2 / sum w = 2.1 / 3, is 7 times the failures' 0.01 / 0.1.
  const auto draws = [](double success_weight, double near_score, double far_score) {
    std::vector<WeightedOutcome> records(10, {"fell", 0.1, 0.2, false, -1, NAN});
    records.insert(records.end(), 2, {"success", success_weight, 0.2, false, near_score, NAN});
    records.insert(records.end(), 988, {"success", success_weight, 0.2, false, far_score, NAN});
    return records;
  };
  const double p = 1.0 / 1000;
  const double plain =
      (10 * std::pow(0.1 - p, 2) + 990 * p * p) / (1000.0 * 999);  // the sample variance
  const Estimate edged = CalcEstimate(draws(1, 0.1, 5));
  ASSERT_EQ(edged.outcomes.size(), 1u);
  EXPECT_DOUBLE_EQ(edged.outcomes[0].p, p);
  EXPECT_NEAR(edged.outcomes[0].iid_episodes, p * (1 - p) / (7 * plain), 1e-6);
  // Without scores there is nothing to compare with; with successes of weight 0.05 the near
  // draws (the failures and 40 successes) weigh 0.2 / 3 on average, less than the failures'
  // 0.1, and the failures' own variance stands: the factor is never below 1.
  EXPECT_NEAR(CalcEstimate(draws(1, NAN, NAN)).outcomes[0].iid_episodes, p * (1 - p) / plain, 1e-6);
  EXPECT_NEAR(CalcEstimate(draws(0.05, 0.1, 5)).outcomes[0].iid_episodes, p * (1 - p) / plain,
              1e-6);
}

TEST(CalcEstimateTest, WeightedSharesIntervalsAndTheBoundWithoutFailures) {
  std::vector<WeightedOutcome> records;
  for (int copy = 0; copy < 10; ++copy) {
    records.insert(
        records.end(),
        {{"success", 1, 0.2}, {"no-path", 1, 0.2}, {"success", 2, 0.2}, {"no-path", 4, 0.2}});
  }
  const Estimate e = CalcEstimate(records);
  ASSERT_EQ(e.outcomes.size(), 1u);
  EXPECT_EQ(e.outcomes[0].episodes, 20);
  EXPECT_DOUBLE_EQ(e.outcomes[0].p, 5.0 / 8);
  // Delta method: sum w^2 (f - p)^2 / (sum w)^2.
  const double p = 5.0 / 8;
  const double variance =
      10 * (1 * p * p + 1 * (1 - p) * (1 - p) + 4 * p * p + 16 * (1 - p) * (1 - p)) / 6400;
  // The interval: exact binomial at the effective counts n* = p (1 - p) / variance, k* = p n*
  // (intervals_test checks that interval against binomial sums).
  const double n_star = p * (1 - p) / variance;
  const RateInterval ci = CalcClopperPearsonInterval(p * n_star, n_star);
  EXPECT_NEAR(e.outcomes[0].ci_low, ci.low, 1e-12);
  EXPECT_NEAR(e.outcomes[0].ci_high, ci.high, 1e-12);
  EXPECT_LT(e.outcomes[0].ci_low, p);
  EXPECT_GT(e.outcomes[0].ci_high, p);
  EXPECT_FALSE(e.iid);
  EXPECT_NEAR(e.outcomes[0].iid_episodes, p * (1 - p) / variance, 1e-9);
  EXPECT_DOUBLE_EQ(e.ess, 6400.0 / 220);
  EXPECT_FALSE(e.reliable) << "an ESS of 29 is no estimate";
  // 100 i.i.d. successes: the rule of three, exactly 1 - 0.05^(1/100).
  const Estimate none = CalcEstimate(std::vector<WeightedOutcome>(100, {"success", 1, 1}));
  EXPECT_TRUE(none.outcomes.empty());
  EXPECT_NEAR(none.upper_bound, 1 - std::pow(0.05, 0.01), 1e-12);
  EXPECT_TRUE(none.iid);
  // A kind seen elsewhere only (an adaptation's) gets a row: no episode, [0, the bound].
  const Estimate seen =
      CalcEstimate(std::vector<WeightedOutcome>(100, {"success", 1, 1}), {"success", "no-path"});
  ASSERT_EQ(seen.outcomes.size(), 1u);
  EXPECT_EQ(seen.outcomes[0].outcome, "no-path");
  EXPECT_EQ(seen.outcomes[0].episodes, 0);
  EXPECT_EQ(seen.outcomes[0].ci_low, 0);
  EXPECT_NEAR(seen.outcomes[0].ci_high, 1 - std::pow(0.05, 0.01), 1e-12);
  EXPECT_THROW(CalcEstimate({{"success", 0, 1}}), std::invalid_argument);
  EXPECT_THROW(CalcEstimate({}), std::invalid_argument);
}

// Fails when the object's centre is in the corner [0, 0.04)^2; the score is how far it is.
class CornerController : public harness::Controller {
 public:
  harness::EpisodeResult RunEpisode(const sampling::SampledScene& s, const std::string&) override {
    const Eigen::Vector3d& p = s.scene.objects[0].p_WO;
    const double score = std::max(p.x() - 0.04, p.y() - 0.04);
    harness::EpisodeResult result{score <= 0 ? "corner" : "success", ""};
    result.score = score;
    return result;
  }
};

struct Coverage {
  int covered = 0;  // reliable runs whose interval holds the truth
  int flagged = 0;  // runs that said "unreliable" instead of giving an interval
  std::vector<double> errors, iid_errors;  // relative
};

// `seeds` estimates with `budget` episodes each, and i.i.d. runs of the same budget.
Coverage MeasureCoverage(const lang::CompiledProgram& program,
                         const harness::ControllerFactory& factory, double truth,
                         const std::string& outcome, int64_t budget, int seeds,
                         int first_seed = 1) {
  Coverage c;
  for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
    EstimateOptions options;
    options.budget = budget;
    options.run.seed = uint64_t(seed);
    options.run.threads = 2;
    const EstimateSummary summary = RunEstimate(program, factory, options);
    c.flagged += !summary.estimate.reliable;
    double p = 0, low = 0, high = 0;
    for (const OutcomeEstimate& o : summary.estimate.outcomes) {
      if (o.outcome == outcome) std::tie(p, low, high) = std::tuple(o.p, o.ci_low, o.ci_high);
    }
    c.covered += summary.estimate.reliable && low <= truth && truth <= high;
    c.errors.push_back(std::abs(p - truth) / truth);
    harness::RunOptions iid;
    iid.seed = uint64_t(seed);
    iid.count = budget;
    iid.threads = 2;
    int64_t failures = 0;
    for (const auto& r : harness::RunEpisodes(program, factory, iid).records) {
      failures += r.result.outcome == outcome;
    }
    c.iid_errors.push_back(std::abs(double(failures) / double(budget) - truth) / truth);
  }
  return c;
}

double Median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return (x[(x.size() - 1) / 2] + x[x.size() / 2]) / 2;
}

TEST(RunEstimateTest, ACornerOfATriangleThatRejectsHalfTheAttemptsIsCovered) {
  // Uniform in the unit square, kept below the diagonal (half the attempts are rejected): the
  // corner [0, 0.04)^2 holds 0.0016 / 0.5 = 0.32 % of the scenes, exactly.
  const auto program = CompileOrDie(
      "c = Object at V3D(Range(0, 1), Range(0, 1), 0), with width 0.01, with length 0.01, "
      "with height 0.01\nrequire c.position.x + c.position.y < 1\n");
  ASSERT_TRUE(program);
  const harness::ControllerFactory factory = [] { return std::make_unique<CornerController>(); };
  const Coverage c = MeasureCoverage(*program, factory, 0.0032, "corner", 1000, 20);
  EXPECT_GE(c.covered, 17) << "95 % intervals over 20 seeds";
  // Half the attempts are rejected, so the accepted set is smaller than the cube: every
  // weighted record says its estimate is self-normalised.
  EstimateOptions options;
  options.budget = 400;
  options.run.seed = 2;
  int weighted = 0;
  for (const harness::EpisodeRecord& r : RunEstimate(*program, factory, options).records) {
    if (r.search.value("strategy", "") != "importance") continue;
    ++weighted;
    EXPECT_TRUE(r.search["normalised"].get<bool>());
  }
  EXPECT_GT(weighted, 100);
  EXPECT_LE(Median(c.errors), 0.25);
  EXPECT_LT(Median(c.errors), Median(c.iid_errors) / 2) << "i.i.d. with the same budget";
}

TEST(RunEstimateTest, TheTableCubePlantedFailuresAreCovered) {
  const auto program = sampling::testing_checks::CompileExample("table_cube.prs");
  ASSERT_TRUE(program);
  // The truths, by i.i.d. sampling (docs/benchmarks.md: `prs test examples/table_cube.prs
  // --controller planted-1-... -n 2000000 -s 11`): 2,131 and 20,338 failures in 2,000,000; for
  // the 0.1 % disk also 10,199 in 10,000,000 with -s 21 (standard error 0.9 %).
  const struct {
    harness::PlantedFailure failure;
    double truth;
  } cases[] = {{harness::PlantedOnePermille(), (2131.0 + 10199) / 12e6},
               {harness::PlantedOnePercent(), 20338.0 / 2e6}};
  for (const auto& [failure, truth] : cases) {
    SCOPED_TRACE(truth);
    const harness::ControllerFactory factory = [failure] {
      return harness::MakePlantedController(failure);
    };
    const Coverage c = MeasureCoverage(*program, factory, truth, "planted-failure", 2000, 100);
    // An interval covers, or the run says it cannot give one (issue 43 asks for 93 % at
    // least); on these shapes it rarely has to.
    EXPECT_GE(c.covered + c.flagged, 90) << "95 % intervals over 100 seeds";
    EXPECT_LE(c.flagged, 10);
    EXPECT_LE(Median(c.errors), 0.25);
    EXPECT_LT(Median(c.errors), Median(c.iid_errors)) << "i.i.d. with the same budget";
  }
}

TEST(RunEstimateTest, RecordsAreTheSameForAnyThreadCountAndCarryTheirWeights) {
  const auto program = sampling::testing_checks::CompileExample("table_cube.prs");
  const harness::ControllerFactory factory = [] {
    return harness::MakePlantedController(harness::PlantedOnePercent());
  };
  std::vector<std::vector<harness::EpisodeRecord>> runs;
  for (const int threads : {1, 2}) {
    EstimateOptions options;
    options.budget = 400;
    options.run.seed = 5;
    options.run.threads = threads;
    runs.push_back(RunEstimate(*program, factory, options).records);
  }
  ASSERT_EQ(runs[0].size(), 400u);
  for (size_t i = 0; i < runs[0].size(); ++i) {
    EXPECT_EQ(runs[0][i].result.outcome, runs[1][i].result.outcome);
    EXPECT_EQ(runs[0][i].coordinates, runs[1][i].coordinates);
    EXPECT_EQ(runs[0][i].search, runs[1][i].search);
  }
  EXPECT_EQ(runs[0].back().search["strategy"], "importance");
  EXPECT_FALSE(runs[0].back().search["normalised"].get<bool>()) << "Table-Cube rejects nothing";
  EXPECT_GT(runs[0].back().search["weight"].get<double>(), 0);
  EXPECT_LE(runs[0].back().search["weight"].get<double>(), 1 / 0.2);
  EstimateOptions tiny;
  tiny.budget = 50;
  EXPECT_THROW(RunEstimate(*program, factory, tiny), std::invalid_argument);
}

}  // namespace
}  // namespace prs::search
