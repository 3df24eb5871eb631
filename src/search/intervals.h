// The 95 % intervals every command gives for a failure rate (docs/search.md, "Intervals"): the
// exact binomial (Clopper–Pearson) interval for i.i.d. episodes, the same interval at the
// effective counts of a weighted estimate (Korn & Graubard's), and the effective sample size of
// a correlated sequence (a Markov chain's episodes) by batch means. One place, so that
// `prs estimate --from` and `prs report` give the same interval for the same records.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace prs::search {

/// A 95 % interval [low, high] within [0, 1].
struct RateInterval {
  double low = 0, high = 1;
};

/// The exact (Clopper–Pearson) 95 % interval of a binomial rate from `k` of `n` (real numbers,
/// so that effective counts work too; 0 <= k <= n): low is the rate at which P(X >= k) is
/// 2.5 %, high the one at which P(X <= k) is 2.5 %; low = 0 when k = 0 and high = 1 when k = n.
/// It covers at least 95 % for every rate, also for few events and rates near 0 or 1.
/// n = 0 gives [0, 1].
RateInterval CalcClopperPearsonInterval(double k, double n);

/// The interval of an estimate `p` with estimated variance `variance` (a weighted or
/// self-normalised mean of failure indicators): Clopper–Pearson at the effective counts
/// n* = p (1 - p) / variance, k* = p n* (Korn & Graubard 1998). For i.i.d. episodes n* = n, so
/// it is the exact binomial interval. When the variance is 0 (p is 0 or 1, or every episode
/// weighs the same and agrees), n* is `fallback_n` (the effective sample size).
RateInterval CalcEffectiveCountInterval(double p, double variance, double fallback_n);

/// The effective sample size of the mean of `values`, taken in order from a correlated
/// sequence: n times the plain variance over the batch-means variance of the mean, with
/// floor(sqrt(n)) batches; at most n, and n when the values do not vary. Needs n >= 4
/// (else n).
double CalcBatchMeansEss(const std::vector<double>& values);

}  // namespace prs::search
