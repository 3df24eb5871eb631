// Exact uniform sampling of convex regions (the hot path of scene sampling), plus the
// paper's hit-and-run chain, kept only for comparison.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geometry/random.h"
#include "geometry/region.h"

namespace prs::geometry {

/// Draws exactly uniform points from a bounded, non-empty region in its own dimension
/// (after sliver collapse): the region is cut into simplices (segments, fan triangles, or
/// tetrahedra from the vertex centroid to fan-triangulated faces), one is picked in
/// proportion to its measure with a Vose alias table, and a uniform point is drawn in it.
/// Regions with balls are sampled from their polytope part (which contains each ball's
/// bounding box) and points outside a ball are rejected. Each draw is O(1).
class RegionSampler {
 public:
  /// Builds the simplex table. Throws std::domain_error when the region is empty or
  /// unbounded (the message carries region.Describe()).
  explicit RegionSampler(const ConvexRegion& region);

  /// One uniform point of the region. For regions with balls, throws std::domain_error
  /// ("region too thin to sample") after 10,000 consecutive rejections.
  Eigen::Vector3d Sample(Rng& rng) const;

  /// The point of the region at `u`, a point of the unit cube [0,1)^dimension() (scene
  /// coordinates, docs/search.md): a measure-preserving map, so a uniform u gives a uniform
  /// point. A segment is walked from its first vertex; a polygon is mapped by its conditional
  /// distribution (u[0] is the quantile of the area along the region's first axis, u[1] the
  /// fraction of the chord across it), so nearby u give nearby points; a polyhedron picks its
  /// simplex by u[0]'s place in the cumulative volume and folds the rest into it. For regions
  /// with balls, the first candidate comes from u and any further ones from `rng` (each still
  /// uniform, so the result is). Throws as Sample.
  Eigen::Vector3d SampleAt(const double* u, Rng& rng) const;

  /// The measure of the sampled set (length/area/volume; 0 for a point). For balls cut by
  /// other constraints, where the exact measure is not computed, the measure of the polytope
  /// part (an upper bound); measure_is_exact() tells which.
  double measure() const { return measure_; }
  bool measure_is_exact() const { return measure_is_exact_; }
  int dimension() const { return dimension_; }
  /// One uniform point of the polytope part, ignoring the balls: for samplers of unions, which
  /// must restart a whole draw (piece and point) when a ball rejects the point (union.h).
  Eigen::Vector3d SamplePolytopePart(Rng& rng) const { return SamplePolytope(rng); }
  /// The point of the polytope part at `u`, as SampleAt maps it, ignoring the balls.
  Eigen::Vector3d MapPolytopePart(const double* u) const { return MapPolytope(u); }
  /// Whether p lies in every ball of the region (true when it has none).
  bool IsInBalls(const Eigen::Vector3d& p) const;
  bool has_balls() const { return !balls_.empty(); }
  int num_simplices() const { return static_cast<int>(probability_.size()); }

 private:
  Eigen::Vector3d SamplePolytope(Rng& rng) const;
  Eigen::Vector3d MapPolytope(const double* u) const;
  Eigen::Vector3d MapPolygon(const double* u) const;
  int PickSimplex(Rng& rng) const;
  void BuildAliasTable(const std::vector<double>& weights);

  int dimension_ = 0;
  std::vector<Eigen::Vector3d> simplex_vertices_;  // dimension_ + 1 per simplex
  std::vector<double> probability_;                // Vose alias table
  std::vector<int> alias_;
  std::vector<Ball> balls_;
  AffineHull hull_;  // the region's plane, for MapPolygon
  double measure_ = 0.0;
  bool measure_is_exact_ = true;
};

/// One exact uniform point of the region (builds a RegionSampler; prefer keeping the sampler
/// when drawing many points). Throws as RegionSampler.
Eigen::Vector3d SampleUniform(const ConvexRegion& region, Rng& rng);

/// The paper's hit-and-run chain: `steps` moves from p_start, each along a uniform random
/// direction in the region's hull to a uniform point of the chord. Biased for short chains
/// (it is not the default and exists only for comparison). Throws std::invalid_argument when
/// steps < 0 or p_start is not in the region, std::domain_error when the region is empty or
/// a chord is unbounded.
Eigen::Vector3d SampleHitAndRun(const ConvexRegion& region, const Eigen::Vector3d& p_start,
                                int steps, Rng& rng);

}  // namespace prs::geometry
