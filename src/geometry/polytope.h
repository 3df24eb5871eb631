// Internal polytope machinery behind ConvexRegion: the affine hull of equalities, 2D/3D
// clipping of a big box by half-spaces, 2D convex hulls, and the cached canonical form.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/region.h"

namespace prs::geometry::internal {

/// Half-size (metres) of the box that is clipped to find a region's vertices.
inline constexpr double kBigHalfSize = kUnboundedExtent;

/// The canonical form of a region, computed once by Canonicalize().
struct RegionCanon {
  bool empty = true;
  bool bounded = true;
  int dimension = -1;
  AffineHull hull;
  // Extra Contains() tolerance so points of a collapsed sliver count as inside.
  double contains_slack = 0.0;
  // World vertices: 1 for a point, 2 for a segment, a polygon in cyclic (CCW in hull
  // coordinates) order, or the distinct vertices of a polyhedron.
  std::vector<Eigen::Vector3d> vertices;
  // 3D only: the faces' vertices in cyclic order, concatenated; face f is
  // face_points[face_start[f] .. face_start[f+1]).
  std::vector<Eigen::Vector3d> face_points;
  std::vector<int> face_start;
  double polytope_measure = 0.0;  // measure of the polytope part (balls' boxes included)
  double measure = 0.0;           // valid when measure_exact
  bool measure_exact = true;
  std::vector<Ball> balls;        // balls the sampler must still reject against
  Eigen::Vector3d p_interior = Eigen::Vector3d::Zero();
};

/// Builds the canonical form from normalized constraints (see docs/geometry.md).
RegionCanon Canonicalize(const std::vector<HalfSpace>& equalities,
                         const std::vector<HalfSpace>& half_spaces,
                         const std::vector<Ball>& balls);

/// The affine subspace {x : n_i·x = d_i} (origin = its point nearest the world origin).
/// Returns false when the equalities are inconsistent by more than 1e-9 m. Normals whose
/// directions agree within ~1e-6 rad are treated as parallel.
bool CalcEqualityHull(const std::vector<HalfSpace>& equalities, AffineHull* hull);

/// Two orthonormal columns spanning the plane orthogonal to unit_normal, with
/// col(0) × col(1) = unit_normal.
Eigen::Matrix<double, 3, 2> CalcPlaneBasis(const Eigen::Vector3d& unit_normal);

/// Indices of the convex hull of `points` in counter-clockwise order, without collinear or
/// duplicate points (Andrew's monotone chain). Fewer than 3 indices for degenerate input.
void CalcConvexHull2D(const std::vector<Eigen::Vector2d>& points, std::vector<int>* hull);

/// The points of `points` that differ by more than `tolerance` (metres), sorted.
void CalcDistinctPoints(const std::vector<Eigen::Vector3d>& points, double tolerance,
                        std::vector<Eigen::Vector3d>* distinct);

/// A convex polyhedron as a list of convex faces.
struct Polyhedron {
  std::vector<Eigen::Vector3d> points;  // faces' vertices, concatenated
  std::vector<int> face_start;          // size faces + 1
  std::vector<Eigen::Vector3d> face_normal;  // outward unit normal
  std::vector<double> face_offset;           // face plane: normal·x = offset
  int num_faces() const { return static_cast<int>(face_normal.size()); }
};

/// Scratch buffers reused across clips.
struct ClipScratch {
  Polyhedron poly;
  std::vector<Eigen::Vector3d> cut;
  std::vector<Eigen::Vector2d> cut_2d;
  std::vector<int> hull;
  std::vector<double> side;
};

/// The axis-aligned cube [-half, half]^3.
void MakeCubePolyhedron(double half, Polyhedron* poly);

/// Keeps the part of `poly` with a·x <= b (a unit). Returns false when nothing is left.
bool ClipPolyhedron(const Eigen::Vector3d& a, double b, Polyhedron* poly, ClipScratch* scratch);

/// Keeps the part of the CCW polygon with a·x <= b (a unit). Returns false when empty.
bool ClipPolygon(const Eigen::Vector2d& a, double b, std::vector<Eigen::Vector2d>* polygon,
                 std::vector<Eigen::Vector2d>* scratch);

}  // namespace prs::geometry::internal
