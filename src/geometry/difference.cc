// Box-overlap zonotopes and convex differences (see difference.h).
#include "geometry/difference.h"

#include <Eigen/Geometry>
#include <cmath>

namespace prs::geometry {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Adds the unit direction n (and -n) to `normals` unless it (or its opposite) is there already.
void AddDirection(const Vector3d& n, std::vector<Vector3d>& normals) {
  const double norm = n.norm();
  if (norm < 1e-9) return;
  const Vector3d unit = n / norm;
  for (const Vector3d& existing : normals) {
    if (std::abs(existing.dot(unit)) > 1 - 1e-12) return;
  }
  normals.push_back(unit);
}

// Whether `inner` (a subset of `outer`, as a candidate piece) has the full dimension of outer.
bool HasFullDimension(const ConvexRegion& inner, const ConvexRegion& outer) {
  return !inner.IsEmpty() && inner.dimension() == outer.dimension();
}

}  // namespace

ConvexRegion CalcBoxOverlapRegion(const OrientedBox& obstacle, const Matrix3d& R_WM,
                                  const Vector3d& half_moving, double tolerance) {
  // The overlap set is the zonotope p_center + sum of t_i g_i, t_i in [-1, 1], over the six
  // half-axes g_i of the two boxes. Its facet normals are cross products of generator pairs;
  // in-plane normals (g x (g x h)) cover the flat case. Extra directions only add redundant
  // supporting half-spaces, so the description stays exact.
  std::vector<Vector3d> generators;
  for (int i = 0; i < 3; ++i) {
    if (obstacle.half_extents[i] > 0) generators.push_back(obstacle.R_WB.col(i) * obstacle.half_extents[i]);
    if (half_moving[i] > 0) generators.push_back(R_WM.col(i) * half_moving[i]);
  }
  std::vector<Vector3d> directions;
  for (int i = 0; i < 3; ++i) {
    AddDirection(obstacle.R_WB.col(i), directions);
    AddDirection(R_WM.col(i), directions);
  }
  for (size_t a = 0; a < generators.size(); ++a) {
    for (size_t b = a + 1; b < generators.size(); ++b) {
      const Vector3d n = generators[a].cross(generators[b]);
      AddDirection(n, directions);
      AddDirection(generators[a].cross(n), directions);
      AddDirection(generators[b].cross(n), directions);
    }
  }
  std::vector<HalfSpace> half_spaces;
  for (const Vector3d& n : directions) {
    double support = 0;
    for (const Vector3d& g : generators) support += std::abs(n.dot(g));
    const double centre = n.dot(obstacle.p_center);
    half_spaces.push_back({n, centre + support - tolerance});
    half_spaces.push_back({-n, -centre + support - tolerance});
  }
  return ConvexRegion::FromHalfSpaces(half_spaces);
}

bool DoesRegionOverlap(const ConvexRegion& a, const ConvexRegion& b) {
  return HasFullDimension(Intersect(a, b), a);
}

std::vector<ConvexRegion> CalcRegionDifference(const ConvexRegion& a, const ConvexRegion& b) {
  if (!DoesRegionOverlap(a, b)) return {a};
  std::vector<ConvexRegion> pieces;
  ConvexRegion inside_earlier = a;  // a within facets 0..i-1 of b
  for (const HalfSpace& h : b.half_spaces()) {
    const ConvexRegion outside = ConvexRegion::FromHalfSpaces({{-h.normal, -h.offset}});
    ConvexRegion piece = Intersect(inside_earlier, outside);
    if (HasFullDimension(piece, a)) pieces.push_back(std::move(piece));
    inside_earlier = Intersect(inside_earlier, ConvexRegion::FromHalfSpaces({h}));
    if (!HasFullDimension(inside_earlier, a)) break;
  }
  return pieces;
}

}  // namespace prs::geometry
