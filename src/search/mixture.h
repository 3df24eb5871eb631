// The proposals of prs estimate (docs/search.md, "How often does it fail"): a defensive
// mixture of the uniform law and truncated normals over the unit cube of scene coordinates,
// its density, and the points an exact sampler's attempts run at when drawing from it.
#pragma once

#include <cstdint>
#include <vector>

#include "sampling/sampler.h"

namespace prs::search {

/// A defensive mixture over the unit cube: with probability `uniform_share` a uniform point,
/// else independent normals per coordinate truncated to [0, 1) (around `mean`, or around one of
/// `centres` picked at random; of those, a `wide_share` drawn `wide_factor` times wider). Its
/// density is at least `uniform_share` everywhere, so importance weights stay below
/// 1 / uniform_share.
struct MixtureProposal {
  /// Per coordinate; a `std` of 0 makes that coordinate uniform in the normals' component too
  /// (one that failing does not depend on).
  std::vector<double> mean, std;
  double uniform_share = 1;
  /// When not empty, the normals' component is itself an equal mixture of normals around
  /// these points (each of dimension() coordinates; `mean` unused), which follows a failure
  /// region of any shape.
  std::vector<std::vector<double>> centres;
  /// When not empty, each centre's own spread per coordinate (one vector per centre, used
  /// where `std` > 0): narrow where the centres are dense, wider where they are sparse.
  std::vector<std::vector<double>> centre_std;
  /// The share of the normals' component drawn around the same centre `wide_factor` times
  /// wider: a second layer that reaches the edges of a failure region the narrow normals
  /// cover thinly, with weights far below 1 / uniform_share there (0: none).
  double wide_share = 0, wide_factor = 1;

  /// The density at `u` (dimension() coordinates in [0, 1)).
  double CalcDensity(const double* u) const;
  /// The share of that density the normals give at `u` (0 where only the uniform share draws).
  double CalcKernelShare(const double* u) const;
  int dimension() const { return static_cast<int>(mean.size()); }
};

/// Every attempt of every scene at a point of the mixture (none reads the stream alone), so
/// that the accepted points are distributed as the mixture restricted to the accepted set, and
/// 1 / CalcDensity is each scene's importance weight against the program's law.
class MixturePoints : public sampling::AttemptPoints {
 public:
  explicit MixturePoints(MixtureProposal proposal) : proposal_(std::move(proposal)) {}
  int dimension() const override { return proposal_.dimension(); }
  bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const override;

 private:
  MixtureProposal proposal_;
};

}  // namespace prs::search
