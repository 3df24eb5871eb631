// A small deterministic random number generator (xoshiro256** seeded by SplitMix64) that
// gives the same stream on every platform; no std:: distributions are used anywhere. Also the
// maps from one number u of [0, 1) to each distribution, for draws at scene coordinates.
#pragma once

#include <cstdint>
#include <limits>

namespace prs::geometry {

/// Deterministic pseudo-random generator: xoshiro256** with its state filled by SplitMix64
/// from a (seed, stream) pair. Satisfies std::uniform_random_bit_generator. Copying an Rng
/// copies its state (the copy replays the same numbers).
/// `lo + (hi - lo)·u`, kept below hi (exactly lo when lo == hi). Throws std::invalid_argument
/// when lo > hi or either bound is not finite.
double MapUniform(double u, double lo, double hi);

/// `lo + ⌊u·(hi − lo + 1)⌋`, an integer of [lo, hi] (uniform for uniform u, up to the 2^-53
/// grain of u for ranges wider than 2^53). Throws std::invalid_argument when lo > hi.
int64_t MapUniformInt(double u, int64_t lo, int64_t hi);

/// The standard normal's quantile at u (inverse CDF; u = 0 is taken as 2^-54).
double MapNormal(double u);

/// The quantile at u of the normal (mean, std > 0) truncated to [lo, hi] (lo < hi), by
/// inverting the CDF on the interval, computed in the tail that holds it. NaN when the
/// interval holds too little of the normal's mass for doubles (over ~37 std out).
double MapTruncatedNormal(double u, double mean, double std, double lo, double hi);

class Rng {
 public:
  using result_type = uint64_t;

  /// Seeds from (seed, stream); distinct pairs give independent-looking streams. Any values
  /// are allowed.
  explicit Rng(uint64_t seed, uint64_t stream = 0);

  /// The next 64 raw bits.
  uint64_t NextU64();

  /// A uniform double in [0, 1) with 53 random bits.
  double Uniform01();

  /// A uniform double in [lo, hi) (exactly lo when lo == hi). Throws std::invalid_argument
  /// when lo > hi or either bound is not finite.
  double Uniform(double lo, double hi);

  /// A uniform integer in [lo, hi], inclusive and unbiased (Lemire's multiply-and-reject).
  /// Throws std::invalid_argument when lo > hi.
  int64_t UniformInt(int64_t lo, int64_t hi);

  /// A standard normal draw (Marsaglia's polar method; uses std::log and std::sqrt).
  double Normal();

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<uint64_t>::max(); }
  result_type operator()() { return NextU64(); }

 private:
  uint64_t s_[4];
};

}  // namespace prs::geometry
