// Implementation of the deterministic xoshiro256** generator and its distributions.
#include "geometry/random.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <boost/math/special_functions/erf.hpp>

namespace prs::geometry {
namespace {

// The SplitMix64 output function: a bijective 64-bit mixer.
uint64_t Mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

uint64_t SplitMix64Next(uint64_t* state) {
  *state += 0x9E3779B97F4A7C15ULL;
  return Mix64(*state);
}

uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

// High 64 bits of the 128-bit product a*b, portable (no __int128).
uint64_t MulHi64(uint64_t a, uint64_t b, uint64_t* lo) {
  const uint64_t a_lo = a & 0xFFFFFFFFULL, a_hi = a >> 32;
  const uint64_t b_lo = b & 0xFFFFFFFFULL, b_hi = b >> 32;
  const uint64_t ll = a_lo * b_lo, lh = a_lo * b_hi, hl = a_hi * b_lo, hh = a_hi * b_hi;
  const uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFULL) + (hl & 0xFFFFFFFFULL);
  *lo = (mid << 32) | (ll & 0xFFFFFFFFULL);
  return hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
}

}  // namespace

Rng::Rng(uint64_t seed, uint64_t stream) {
  // Mix64 is a bijection, so for a fixed seed every stream starts SplitMix64 elsewhere.
  uint64_t state = Mix64(Mix64(seed) + 0x632BE59BD9B4E019ULL) ^ Mix64(stream + 0x9E3779B97F4A7C15ULL);
  state = Mix64(state);
  for (uint64_t& word : s_) word = SplitMix64Next(&state);
  if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0) s_[0] = 1;  // xoshiro must not be all zero
}

uint64_t Rng::NextU64() {
  const uint64_t result = Rotl(s_[1] * 5, 7) * 9;
  const uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = Rotl(s_[3], 45);
  return result;
}

double Rng::Uniform01() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }

namespace {

void CheckUniformBounds(double lo, double hi) {
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) {
    std::ostringstream msg;
    msg << "Rng::Uniform: need finite lo <= hi, got lo=" << lo << " hi=" << hi;
    throw std::invalid_argument(msg.str());
  }
}

void CheckIntBounds(int64_t lo, int64_t hi) {
  if (lo > hi) {
    std::ostringstream msg;
    msg << "Rng::UniformInt: need lo <= hi, got lo=" << lo << " hi=" << hi;
    throw std::invalid_argument(msg.str());
  }
}

// The standard normal's upper-tail probability Q(z) = P(Z > z), accurate far out in the tail.
double CalcUpperTail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

// The z with Q(z) = q, for q in (0, 1).
double CalcUpperTailQuantile(double q) {
  return std::sqrt(2.0) * boost::math::erfc_inv(2.0 * q);
}

}  // namespace

double MapUniform(double u, double lo, double hi) {
  CheckUniformBounds(lo, hi);
  const double x = lo + (hi - lo) * u;
  // Rounding can land exactly on hi; keep the interval half-open.
  return (x >= hi && hi > lo) ? std::nextafter(hi, lo) : x;
}

int64_t MapUniformInt(double u, int64_t lo, int64_t hi) {
  CheckIntBounds(lo, hi);
  const double n = static_cast<double>(static_cast<uint64_t>(hi) - static_cast<uint64_t>(lo)) + 1.0;
  const double k = std::min(std::floor(u * n), n - 1.0);
  return static_cast<int64_t>(static_cast<uint64_t>(lo) + static_cast<uint64_t>(std::max(0.0, k)));
}

double MapNormal(double u) {
  const double p = std::clamp(u, 0x1.0p-54, 1.0 - 0x1.0p-54);
  return -CalcUpperTailQuantile(p);  // Q(-z) = 1 - Q(z) = p
}

double MapTruncatedNormal(double u, double mean, double std, double lo, double hi) {
  double a = (lo - mean) / std, b = (hi - mean) / std;
  // Work in the upper tail, where Q keeps its precision: mirror when the interval lies below.
  const bool mirror = a + b < 0;
  if (mirror) {
    const double t = -a;
    a = -b;
    b = t;
  }
  const double q_a = CalcUpperTail(a), q_b = CalcUpperTail(b);  // q_a > q_b
  if (!(q_a > q_b) || !(q_a > 0)) return NAN;
  const double q = std::clamp(q_a - u * (q_a - q_b), std::min(q_b, q_a), q_a);
  if (!(q > 0) || !(q < 1)) return NAN;
  const double z = std::clamp(CalcUpperTailQuantile(q), a, b);
  const double x = mean + std * (mirror ? -z : z);
  return std::clamp(x, lo, hi);
}

double Rng::Uniform(double lo, double hi) {
  CheckUniformBounds(lo, hi);
  return MapUniform(Uniform01(), lo, hi);
}

int64_t Rng::UniformInt(int64_t lo, int64_t hi) {
  CheckIntBounds(lo, hi);
  const uint64_t range = static_cast<uint64_t>(hi) - static_cast<uint64_t>(lo);
  if (range == std::numeric_limits<uint64_t>::max()) return static_cast<int64_t>(NextU64());
  const uint64_t n = range + 1;
  uint64_t low = 0;
  uint64_t high = MulHi64(NextU64(), n, &low);
  if (low < n) {
    const uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    while (low < threshold) high = MulHi64(NextU64(), n, &low);
  }
  return static_cast<int64_t>(static_cast<uint64_t>(lo) + high);
}

double Rng::Normal() {
  for (;;) {
    const double u = 2.0 * Uniform01() - 1.0;
    const double v = 2.0 * Uniform01() - 1.0;
    const double s = u * u + v * v;
    if (s > 0.0 && s < 1.0) return u * std::sqrt(-2.0 * std::log(s) / s);
  }
}

}  // namespace prs::geometry
