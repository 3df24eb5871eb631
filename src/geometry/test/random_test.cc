// Tests of the deterministic RNG: fixed outputs, ranges, and basic statistics.
#include "geometry/random.h"

#include <cmath>
#include <algorithm>
#include <concepts>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

namespace prs::geometry {
namespace {

static_assert(std::uniform_random_bit_generator<Rng>);

TEST(RngTest, FixedFirstOutputs) {
  Rng rng(42);
  // Recorded once from this implementation; any change breaks reproducibility of scenes.
  const uint64_t expected[4] = {0x72e2930cff9266b8ULL, 0xd28bfa05a8189590ULL,
                                 0xe910b52381eeb9d2ULL, 0x0739ae2d2e67fbdaULL};
  for (uint64_t e : expected) EXPECT_EQ(rng.NextU64(), e);
}

TEST(RngTest, SameSeedSameStream) {
  Rng a(7, 3), b(7, 3);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.NextU64(), b.NextU64());
}

TEST(RngTest, DistinctStreamsDiffer) {
  Rng a(7, 0), b(7, 1), c(8, 0);
  int same_ab = 0, same_ac = 0;
  for (int i = 0; i < 100; ++i) {
    const uint64_t x = a.NextU64();
    same_ab += x == b.NextU64();
    same_ac += x == c.NextU64();
  }
  EXPECT_EQ(same_ab, 0);
  EXPECT_EQ(same_ac, 0);
}

TEST(RngTest, BitsAreBalanced) {
  // Each of the 64 bits is set about half the time: |count - n/2| < 5 sigma.
  Rng rng(1);
  const int n = 20000;
  std::vector<int> ones(64, 0);
  for (int i = 0; i < n; ++i) {
    const uint64_t x = rng.NextU64();
    for (int b = 0; b < 64; ++b) ones[b] += (x >> b) & 1;
  }
  const double sigma = std::sqrt(n * 0.25);
  for (int b = 0; b < 64; ++b) EXPECT_LT(std::abs(ones[b] - n / 2.0), 5 * sigma) << "bit " << b;
}

TEST(RngTest, Uniform01RangeAndMean) {
  Rng rng(2);
  const int n = 100000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.Uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
}

TEST(RngTest, UniformBounds) {
  Rng rng(3);
  for (int i = 0; i < 1000; ++i) {
    const double x = rng.Uniform(-2.5, 1.5);
    EXPECT_GE(x, -2.5);
    EXPECT_LT(x, 1.5);
  }
  EXPECT_EQ(rng.Uniform(4.0, 4.0), 4.0);
  EXPECT_THROW(rng.Uniform(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(rng.Uniform(0.0, INFINITY), std::invalid_argument);
}

TEST(RngTest, UniformIntBoundsAndCoverage) {
  Rng rng(4);
  std::vector<int> counts(7, 0);
  const int n = 70000;
  for (int i = 0; i < n; ++i) {
    const int64_t x = rng.UniformInt(-3, 3);
    ASSERT_GE(x, -3);
    ASSERT_LE(x, 3);
    ++counts[x + 3];
  }
  // Chi-square with 6 degrees of freedom; 0.999 quantile is 22.46.
  double chi2 = 0;
  for (int c : counts) chi2 += (c - n / 7.0) * (c - n / 7.0) / (n / 7.0);
  EXPECT_LT(chi2, 22.46);
  EXPECT_EQ(rng.UniformInt(5, 5), 5);
  EXPECT_THROW(rng.UniformInt(2, 1), std::invalid_argument);
  const int64_t lo = std::numeric_limits<int64_t>::min(), hi = std::numeric_limits<int64_t>::max();
  for (int i = 0; i < 10; ++i) (void)rng.UniformInt(lo, hi);  // full range must not hang
  for (int i = 0; i < 1000; ++i) {
    const int64_t x = rng.UniformInt(hi - 2, hi);
    EXPECT_GE(x, hi - 2);
  }
}

TEST(RngTest, NormalMeanAndVariance) {
  Rng rng(5);
  const int n = 100000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Normal();
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  EXPECT_NEAR(mean, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(var, 1.0, 5 * std::sqrt(2.0 / n));
}

TEST(RngTest, WorksWithStdShuffle) {
  Rng a(9), b(9);
  std::vector<int> x = {1, 2, 3, 4, 5, 6, 7, 8}, y = x;
  std::shuffle(x.begin(), x.end(), a);
  std::shuffle(y.begin(), y.end(), b);
  EXPECT_EQ(x, y);
}

}  // namespace
}  // namespace prs::geometry
