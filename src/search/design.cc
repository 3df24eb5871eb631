// Sobol' (Boost.Random), Halton and rank-1 lattice point sets, each randomised by the seed so
// that every point alone is uniform; and the L2-star discrepancy that compares them.
#include "search/design.h"

#include <algorithm>
#include <boost/random/sobol.hpp>
#include <cmath>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "geometry/random.h"

namespace prs::search {
namespace {

// Randomisations draw from their own seed, never from a scene's stream (seed, index).
constexpr uint64_t kDesignSeedSalt = 0xD1B54A32D192ED03ULL;

double ToUnit(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

std::vector<int> FirstPrimes(int count) {
  std::vector<int> primes;
  for (int n = 2; static_cast<int>(primes.size()) < count; ++n) {
    bool prime = true;
    for (int p : primes) {
      if (p * p > n) break;
      if (n % p == 0) {
        prime = false;
        break;
      }
    }
    if (prime) primes.push_back(n);
  }
  return primes;
}

// P_2 of the Korobov lattice with multiplier a (Sloan & Joe's figure of merit, unit weights):
// smaller is better.
double CalcKorobovMerit(uint64_t n, uint64_t a, int dimension) {
  std::vector<uint64_t> z(dimension);
  z[0] = 1;
  for (int j = 1; j < dimension; ++j) z[j] = (z[j - 1] * a) % n;
  double sum = 0;
  for (uint64_t k = 0; k < n; ++k) {
    double product = 1;
    for (int j = 0; j < dimension; ++j) {
      const double x = static_cast<double>((k * z[j]) % n) / static_cast<double>(n);
      product *= 1 + 2 * std::numbers::pi * std::numbers::pi * (x * x - x + 1.0 / 6.0);
    }
    sum += product;
  }
  return sum / static_cast<double>(n) - 1;
}

uint64_t Gcd(uint64_t a, uint64_t b) {
  while (b) {
    const uint64_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

// The Korobov generating vector (1, a, a², …) mod n with the best P_2 among a bounded number
// of multipliers (all of them for small n), so building it stays under ~5·10^7 operations.
std::vector<uint64_t> FindKorobovGenerator(uint64_t n, int dimension) {
  std::vector<uint64_t> z(dimension, 1);
  if (n < 3 || dimension == 1) return z;
  const double budget = 5e7 / (static_cast<double>(n) * dimension);
  const uint64_t candidates = std::clamp<uint64_t>(static_cast<uint64_t>(budget), 8, n - 2);
  const uint64_t step = std::max<uint64_t>(1, (n - 2) / candidates);
  uint64_t best_a = 1;
  double best = INFINITY;
  for (uint64_t a = 2; a < n; a += step) {
    if (Gcd(a, n) != 1) continue;
    const double merit = CalcKorobovMerit(n, a, dimension);
    if (merit < best) {
      best = merit;
      best_a = a;
    }
  }
  for (int j = 1; j < dimension; ++j) z[j] = (z[j - 1] * best_a) % n;
  return z;
}

}  // namespace

const char* DesignName(DesignKind kind) {
  switch (kind) {
    case DesignKind::kRandom:
      return "random";
    case DesignKind::kSobol:
      return "sobol";
    case DesignKind::kHalton:
      return "halton";
    case DesignKind::kLattice:
      return "lattice";
  }
  return "random";
}

std::vector<std::string> DesignNames() { return {"random", "sobol", "halton", "lattice"}; }

bool ParseDesign(const std::string& name, DesignKind* kind) {
  for (DesignKind k :
       {DesignKind::kRandom, DesignKind::kSobol, DesignKind::kHalton, DesignKind::kLattice}) {
    if (name == DesignName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

// Per-design state that is expensive to rebuild: Sobol engines (each holds its direction
// numbers) lent to one thread at a time, and the Halton permutations of the last seed.
struct Design::Impl {
  std::mutex mutex;
  std::vector<std::unique_ptr<boost::random::sobol>> idle_engines;
  bool have_permutations = false;
  uint64_t permutation_seed = 0;
  std::vector<std::vector<int>> permutations;  // per dimension, a permutation of its digits
  std::vector<int> primes;
};

Design::Design(DesignKind kind, int dimension, uint64_t size)
    : kind_(kind), dimension_(dimension), size_(size), impl_(std::make_unique<Impl>()) {
  if (kind == DesignKind::kRandom) {
    throw std::invalid_argument("Design: 'random' is no design (sample without one)");
  }
  if (dimension < 1 || dimension > sampling::kMaxCoordinates) {
    throw std::invalid_argument("Design: dimension must be 1.." +
                                std::to_string(sampling::kMaxCoordinates) + ", got " +
                                std::to_string(dimension));
  }
  if (kind == DesignKind::kLattice) {
    if (size < 1) throw std::invalid_argument("Design: a lattice needs at least one point");
    lattice_generator_ = FindKorobovGenerator(size, dimension);
  }
  if (kind == DesignKind::kHalton) impl_->primes = FirstPrimes(dimension);
}

Design::~Design() = default;

bool Design::Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const {
  if (attempt != 0) return false;
  CalcPoint(seed, index, u);
  return true;
}

void Design::CalcPoint(uint64_t seed, uint64_t index, double* u) const {
  const uint64_t design_seed = seed ^ kDesignSeedSalt;
  switch (kind_) {
    case DesignKind::kSobol: {
      std::unique_ptr<boost::random::sobol> engine;
      {
        std::lock_guard lock(impl_->mutex);
        if (!impl_->idle_engines.empty()) {
          engine = std::move(impl_->idle_engines.back());
          impl_->idle_engines.pop_back();
        }
      }
      if (!engine) engine = std::make_unique<boost::random::sobol>(dimension_);
      engine->seed(index);
      // A random digital shift: every point XORed with the same random bits per dimension
      // keeps the net's structure and makes each point uniform.
      geometry::Rng shift(design_seed, 1);
      for (int j = 0; j < dimension_; ++j) u[j] = ToUnit((*engine)() ^ shift.NextU64());
      std::lock_guard lock(impl_->mutex);
      impl_->idle_engines.push_back(std::move(engine));
      return;
    }
    case DesignKind::kHalton: {
      std::lock_guard lock(impl_->mutex);
      if (!impl_->have_permutations || impl_->permutation_seed != seed) {
        geometry::Rng rng(design_seed, 2);
        impl_->permutations.assign(dimension_, {});
        for (int j = 0; j < dimension_; ++j) {
          std::vector<int>& perm = impl_->permutations[j];
          perm.resize(impl_->primes[j]);
          for (int d = 0; d < impl_->primes[j]; ++d) perm[d] = d;
          for (int d = impl_->primes[j] - 1; d > 0; --d) {
            std::swap(perm[d], perm[rng.UniformInt(0, d)]);
          }
        }
        impl_->have_permutations = true;
        impl_->permutation_seed = seed;
      }
      for (int j = 0; j < dimension_; ++j) {
        const int base = impl_->primes[j];
        const std::vector<int>& perm = impl_->permutations[j];
        double value = 0, scale = 1.0 / base;
        uint64_t rest = index;
        // Every digit position down to 2^-53, the ones past the index's length permuted 0s.
        while (scale > 0x1.0p-53) {
          value += perm[rest % base] * scale;
          rest /= base;
          scale /= base;
        }
        u[j] = std::min(value, 1.0 - 0x1.0p-53);
      }
      return;
    }
    case DesignKind::kLattice: {
      const uint64_t copy = index / size_, k = index % size_;
      geometry::Rng shift(design_seed, 3 + copy);
      for (int j = 0; j < dimension_; ++j) {
        const double x =
            static_cast<double>((k * lattice_generator_[j]) % size_) / static_cast<double>(size_) +
            shift.Uniform01();
        u[j] = std::min(x - std::floor(x), 1.0 - 0x1.0p-53);
      }
      return;
    }
    case DesignKind::kRandom:
      break;
  }
}

double CalcL2StarDiscrepancy(const std::vector<std::vector<double>>& points) {
  const size_t n = points.size();
  if (n == 0) return 0;
  const size_t d = points[0].size();
  double sum_single = 0;
  for (const auto& x : points) {
    double product = 1;
    for (size_t j = 0; j < d; ++j) product *= (1 - x[j] * x[j]) / 2;
    sum_single += product;
  }
  double sum_pairs = 0;
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) {
      double product = 1;
      for (size_t j = 0; j < d; ++j) product *= 1 - std::max(points[a][j], points[b][j]);
      sum_pairs += product;
    }
  }
  const double square = std::pow(3.0, -static_cast<double>(d)) -
                        2.0 / static_cast<double>(n) * sum_single +
                        sum_pairs / (static_cast<double>(n) * static_cast<double>(n));
  return std::sqrt(std::max(0.0, square));
}

}  // namespace prs::search
