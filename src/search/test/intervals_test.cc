// The intervals of intervals.h against what defines them, computed here from the binomial law
// itself: each Clopper–Pearson bound puts 2.5 % in its tail, and the interval's exact coverage
// (a sum over every outcome k) is at least 95 % at rates near 0, in the middle and near 1,
// where the delta method's interval is not. Batch means against sequences of known
// correlation.
#include "search/intervals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace prs::search {
namespace {

// P(X = k) for X ~ Binomial(n, p), in logs.
double BinomialPmf(int k, int n, double p) {
  if (p <= 0) return k == 0 ? 1 : 0;
  if (p >= 1) return k == n ? 1 : 0;
  return std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
                  k * std::log(p) + (n - k) * std::log1p(-p));
}

double BinomialAtMost(int k, int n, double p) {
  double sum = 0;
  for (int i = 0; i <= k; ++i) sum += BinomialPmf(i, n, p);
  return sum;
}

TEST(ClopperPearsonTest, EachBoundLeavesTwoAndAHalfPercentInItsTail) {
  for (const auto& [k, n] : {std::pair{2, 500}, {3, 700}, {1, 10}, {50, 100}, {699, 700}}) {
    const RateInterval ci = CalcClopperPearsonInterval(k, n);
    EXPECT_NEAR(1 - BinomialAtMost(k - 1, n, ci.low), 0.025, 1e-9) << k << " of " << n;
    EXPECT_NEAR(BinomialAtMost(k, n, ci.high), 0.025, 1e-9) << k << " of " << n;
    EXPECT_LT(ci.low, double(k) / n);
    EXPECT_GT(ci.high, double(k) / n);
  }
  // The few-failure cases are not clamped at 0: 2 in 500 and 3 in 700.
  EXPECT_GT(CalcClopperPearsonInterval(2, 500).low, 0.0004);
  EXPECT_GT(CalcClopperPearsonInterval(3, 700).low, 0.0008);
}

TEST(ClopperPearsonTest, TheEdgesAreOneSided) {
  const RateInterval none = CalcClopperPearsonInterval(0, 300);
  EXPECT_EQ(none.low, 0);
  EXPECT_NEAR(none.high, 1 - std::pow(0.025, 1.0 / 300), 1e-12);
  const RateInterval all = CalcClopperPearsonInterval(300, 300);
  EXPECT_NEAR(all.low, std::pow(0.025, 1.0 / 300), 1e-12);
  EXPECT_EQ(all.high, 1);
  EXPECT_LT(all.low, 1) << "everything failing is not 100 % - 100 %";
  const RateInterval empty = CalcClopperPearsonInterval(0, 0);
  EXPECT_EQ(empty.low, 0);
  EXPECT_EQ(empty.high, 1);
}

TEST(ClopperPearsonTest, CoversAtLeastNinetyFivePercentAtEveryRate) {
  // Exact coverage: the probability of the k whose interval holds p.
  for (const int n : {30, 500}) {
    for (const double p : {0.0005, 0.002, 0.01, 0.1, 0.5, 0.9, 0.99, 0.999}) {
      double coverage = 0;
      for (int k = 0; k <= n; ++k) {
        const RateInterval ci = CalcClopperPearsonInterval(k, n);
        if (ci.low <= p && p <= ci.high) coverage += BinomialPmf(k, n, p);
      }
      EXPECT_GE(coverage, 0.95) << "p " << p << " n " << n;
    }
  }
}

TEST(EffectiveCountIntervalTest, IsTheBinomialIntervalForIidEpisodes) {
  // An i.i.d. mean's variance is p (1 - p) / n: the effective counts are k and n.
  const double p = 7.0 / 400;
  const RateInterval a = CalcEffectiveCountInterval(p, p * (1 - p) / 400, 400);
  const RateInterval b = CalcClopperPearsonInterval(7, 400);
  EXPECT_NEAR(a.low, b.low, 1e-12);
  EXPECT_NEAR(a.high, b.high, 1e-12);
  // A quarter of the variance is four times the episodes: a narrower interval around p.
  const RateInterval tight = CalcEffectiveCountInterval(p, p * (1 - p) / 1600, 400);
  EXPECT_GT(tight.low, a.low);
  EXPECT_LT(tight.high, a.high);
  EXPECT_GT(tight.low, 0);
  // No variance at p = 1: the effective sample size decides, and the interval is not a point.
  const RateInterval all = CalcEffectiveCountInterval(1, 0, 50);
  EXPECT_NEAR(all.low, std::pow(0.025, 1.0 / 50), 1e-12);
  EXPECT_EQ(all.high, 1);
}

TEST(BatchMeansTest, FindsTheEffectiveSizeOfCorrelatedSequences) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const int n = 40'000;
  std::vector<double> iid(n), ar(n);
  double x = 0;
  const double rho = 0.9;
  for (int i = 0; i < n; ++i) {
    iid[i] = normal(rng);
    x = rho * x + std::sqrt(1 - rho * rho) * normal(rng);
    ar[i] = x;
  }
  // i.i.d.: n; AR(1): n (1 - rho) / (1 + rho) = n / 19.
  EXPECT_GT(CalcBatchMeansEss(iid), 0.7 * n);
  EXPECT_LE(CalcBatchMeansEss(iid), n);
  const double ess = CalcBatchMeansEss(ar);
  EXPECT_GT(ess, n / 19.0 / 1.5);
  EXPECT_LT(ess, n / 19.0 * 1.5);
  EXPECT_EQ(CalcBatchMeansEss(std::vector<double>(100, 1.0)), 100);
}

}  // namespace
}  // namespace prs::search
