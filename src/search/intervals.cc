// Binomial and effective-count intervals (see intervals.h); Boost.Math gives the beta quantiles.
#include "search/intervals.h"

#include <algorithm>
#include <boost/math/distributions/beta.hpp>
#include <cmath>

namespace prs::search {
namespace {

constexpr double kTail = 0.025;  // each side of a two-sided 95 % interval

}  // namespace

RateInterval CalcClopperPearsonInterval(double k, double n) {
  if (!(n > 0)) return {0, 1};
  k = std::clamp(k, 0.0, n);
  RateInterval interval;
  // P(X >= k | p) = I_p(k, n - k + 1) and P(X <= k | p) = 1 - I_p(k + 1, n - k), so the
  // bounds are quantiles of those beta laws (which hold for real k and n too).
  if (k > 0) {
    interval.low = boost::math::quantile(boost::math::beta_distribution<>(k, n - k + 1), kTail);
  }
  if (k < n) {
    interval.high =
        boost::math::quantile(boost::math::beta_distribution<>(k + 1, n - k), 1 - kTail);
  }
  return interval;
}

RateInterval CalcEffectiveCountInterval(double p, double variance, double fallback_n) {
  p = std::clamp(p, 0.0, 1.0);
  const double n = variance > 0 && p > 0 && p < 1 ? p * (1 - p) / variance : fallback_n;
  return CalcClopperPearsonInterval(p * n, n);
}

double CalcBatchMeansEss(const std::vector<double>& values) {
  const size_t n = values.size();
  if (n < 4) return double(n);
  const size_t batches = size_t(std::sqrt(double(n))), size = n / batches;
  double mean = 0;
  for (double v : values) mean += v / double(n);
  double variance = 0;
  for (double v : values) variance += (v - mean) * (v - mean) / double(n - 1);
  if (!(variance > 0)) return double(n);
  // The batches cover the first batches * size values; their means' spread estimates the
  // variance of a mean of `size` consecutive values.
  std::vector<double> means(batches, 0.0);
  double grand = 0;
  for (size_t b = 0; b < batches; ++b) {
    for (size_t i = 0; i < size; ++i) means[b] += values[b * size + i] / double(size);
    grand += means[b] / double(batches);
  }
  double spread = 0;
  for (double m : means) spread += (m - grand) * (m - grand) / double(batches - 1);
  // Var(mean of n) ~ spread * size / n; an i.i.d. sequence would give variance / n.
  if (!(spread > 0)) return double(n);
  return std::min(double(n), double(n) * variance / (spread * double(size)));
}

}  // namespace prs::search
