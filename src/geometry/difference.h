// Cutting obstacles out of convex regions, exactly: the set of centres at which a moving box
// overlaps a fixed one (a zonotope), and the difference of two convex regions as disjoint
// convex pieces. The sampler uses these to keep an object out of fixed obstacles without
// rejection.
#pragma once

#include <vector>

#include "geometry/box.h"
#include "geometry/region.h"

namespace prs::geometry {

/// The centres p at which a box with orientation R_WM and half extents `half_moving` overlaps
/// `obstacle` by more than `tolerance` (metres): the Minkowski sum of the two boxes, shrunk by
/// the tolerance, as the intersection of half-spaces. Touching within the tolerance is not an
/// overlap, as in DoBoxesOverlap.
ConvexRegion CalcBoxOverlapRegion(const OrientedBox& obstacle, const Eigen::Matrix3d& R_WM,
                                  const Eigen::Vector3d& half_moving, double tolerance = 1e-6);

/// Whether `b` covers part of `a` with a positive measure in a's own dimension (not just a
/// touching face or edge).
bool DoesRegionOverlap(const ConvexRegion& a, const ConvexRegion& b);

/// `a` minus the interior of `b`, as convex pieces with disjoint interiors whose union is the
/// difference; pieces of lower dimension than `a` are dropped. Piece i lies outside facet i of
/// b and inside facets 0..i-1, so there are at most as many pieces as b has half-spaces.
/// Returns {a} when b's interior does not meet a. `b` must have no equalities or balls.
std::vector<ConvexRegion> CalcRegionDifference(const ConvexRegion& a, const ConvexRegion& b);

}  // namespace prs::geometry
