// Space-filling designs over scene coordinates (docs/search.md): the first attempt of scene i
// runs at point i of a scrambled Sobol, Halton or rank-1 lattice point set instead of at an
// i.i.d. point, so n scenes cover the space of what is random more evenly than n i.i.d. ones.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sampling/sampler.h"

namespace prs::search {

enum class DesignKind {
  kRandom,  // no design: every attempt reads the stream (today's sampling, bit for bit)
  kSobol,  // Sobol' points (Boost.Random's sobol, Joe–Kuo directions) with a random digital shift
  kHalton,   // Halton points with random digit permutations per dimension
  kLattice,  // a rank-1 Korobov lattice of `size` points with a random shift
};

/// The design's name as the command line spells it ("random", "sobol", "halton", "lattice").
const char* DesignName(DesignKind kind);
/// Every design name, in the order above.
std::vector<std::string> DesignNames();
/// The design called `name`, or false.
bool ParseDesign(const std::string& name, DesignKind* kind);

/// A randomised point set over the unit cube of `dimension` coordinates: point i of seed s is a
/// pure function of (kind, s, i, dimension, and for lattices their size). Each point, over the
/// seed's randomisation, is uniform in the cube, so each scene keeps the program's exact
/// distribution; the points together are more even than i.i.d. ones. Thread-safe.
class Design : public sampling::AttemptPoints {
 public:
  /// `size` is the number of points a lattice is built for (ignored by the others); point i
  /// of a lattice with i >= size starts another copy of the lattice with a fresh shift.
  /// Throws std::invalid_argument for kRandom, dimension < 1 or > sampling::kMaxCoordinates,
  /// or a lattice size < 1.
  Design(DesignKind kind, int dimension, uint64_t size = 1);
  ~Design() override;

  int dimension() const override { return dimension_; }
  /// Attempt 0 of scene `index` runs at point `index` of seed `seed`; later attempts (after a
  /// rejection) read the stream.
  bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const override;
  /// Point `index` of the design randomised by `seed`.
  void CalcPoint(uint64_t seed, uint64_t index, double* u) const;

 private:
  struct Impl;
  DesignKind kind_;
  int dimension_;
  uint64_t size_;
  std::vector<uint64_t> lattice_generator_;  // z_j of the lattice
  std::unique_ptr<Impl> impl_;
};

/// The coverage measure of docs/search.md: the L2-star discrepancy of points in the
/// unit square or cube (Warnock's formula), for comparing designs; O(n² d).
double CalcL2StarDiscrepancy(const std::vector<std::vector<double>>& points);

}  // namespace prs::search
