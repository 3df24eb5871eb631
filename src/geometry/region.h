// Convex regions of the language (spec §5): an affine subspace ∩ half-spaces ∩ balls, with
// cheap construction and intersection and a lazily computed, cached canonical form.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/box.h"

namespace prs::geometry {

/// The half-space normal·x <= offset (world frame). Region constructors normalize it.
struct HalfSpace {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};

/// A solid ball (world frame).
struct Ball {
  Eigen::Vector3d p_center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// An affine subspace {p_origin + basis·u}: basis is 3×k with orthonormal columns, k = 0..3.
struct AffineHull {
  Eigen::Vector3d p_origin = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3> basis;
};

/// Geometric tolerance (metres): slivers thinner than this collapse, constraints that cross
/// by less than this do not make a region empty.
inline constexpr double kGeometricTolerance = 1e-9;
/// A region reaching farther than this from the origin (metres) is reported as unbounded.
inline constexpr double kUnboundedExtent = 1e5;

class ConvexRegion;
namespace internal {
struct RegionCanon;
/// `region` with its canonical form given instead of computed (for callers that derived it
/// exactly another way: unions slicing a piece by a plane's polygon, union.cc).
ConvexRegion AttachCanon(ConvexRegion region, RegionCanon canon);
}

/// A convex set in 3D: {x : E x = f} ∩ {x : n_i·x <= d_i} ∩ balls. A cheap value type:
/// copying shares the cache, Intersect() just stacks constraints. The canonical form
/// (hull after sliver collapse, vertices, faces, measure, boundedness) is computed on the
/// first query that needs it and cached. Thread safety: a region whose cache is not yet
/// filled must not be queried from two threads at once; call Finalize() first to fill it,
/// after which all const queries are safe to run concurrently.
class ConvexRegion {
 public:
  /// The empty set.
  static ConvexRegion Empty();
  /// All of space (unbounded).
  static ConvexRegion All();
  /// The intersection of the half-spaces normal·x <= offset. Normals are normalized; a zero
  /// normal (norm < 1e-12) is dropped when offset >= 0 and makes the region Empty otherwise.
  /// Throws std::invalid_argument for non-finite values.
  static ConvexRegion FromHalfSpaces(const std::vector<HalfSpace>& half_spaces);
  /// {x : normal·(x - p_point) >= 0}, the side `normal` points into ("ahead of").
  /// Throws std::invalid_argument when normal is zero or a value is not finite.
  static ConvexRegion MakeHalfSpace(const Eigen::Vector3d& p_point, const Eigen::Vector3d& normal);
  /// The solid box with extents width, length, height along the local x, y, z axes (columns
  /// of R_WB, which must be orthonormal). A zero extent gives a flat box (an equality).
  /// Throws std::invalid_argument for negative or non-finite extents.
  static ConvexRegion MakeCuboid(const Eigen::Vector3d& p_center, const Eigen::Matrix3d& R_WB,
                                 double width, double length, double height);
  /// The planar rectangle width × length in the local xy plane through p_center.
  /// Throws std::invalid_argument for negative or non-finite extents.
  static ConvexRegion MakeRect3D(const Eigen::Vector3d& p_center, const Eigen::Matrix3d& R_WB,
                                 double width, double length);
  /// The plane through p_point with the given normal. Throws std::invalid_argument when the
  /// normal is zero or a value is not finite.
  static ConvexRegion MakePlane(const Eigen::Vector3d& p_point, const Eigen::Vector3d& normal);
  /// The convex hull of coplanar points (within 1e-9 m of their best-fit plane): a polygon,
  /// a segment when collinear, a point when all coincide, Empty for no points. Throws
  /// std::invalid_argument when the points are not coplanar or not finite.
  static ConvexRegion MakeConvexPolygon3D(const std::vector<Eigen::Vector3d>& vertices);
  /// The intersection of half-spaces (as FromHalfSpaces; described as a polyhedron).
  static ConvexRegion MakeConvexPolyhedron(const std::vector<HalfSpace>& half_spaces);
  /// The solid ball; radius 0 gives the point. Throws std::invalid_argument for a negative or
  /// non-finite radius or centre.
  static ConvexRegion MakeSphere(const Eigen::Vector3d& p_center, double radius);
  /// The segment from a to b (a point when they coincide within 1e-12 m).
  /// Throws std::invalid_argument for non-finite points.
  static ConvexRegion MakeSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b);
  /// The single point p. Throws std::invalid_argument for a non-finite point.
  static ConvexRegion MakePoint(const Eigen::Vector3d& p);

  /// True when the region is empty (after the 1e-9 m crossing rule; for balls intersected
  /// with other constraints, decided by alternating projections to 1e-9 m).
  bool IsEmpty() const;
  /// False when the region extends beyond 1e5 m from the origin. Empty regions are bounded.
  bool IsBounded() const;
  /// Dimension of the region after sliver collapse: -1 empty, 0 point, ... 3 solid.
  int dimension() const;
  /// True when p_W satisfies every constraint within `tolerance` (metres; may be negative to
  /// ask for a point at least -tolerance inside). Always false for an empty region.
  bool Contains(const Eigen::Vector3d& p_W, double tolerance = kGeometricTolerance) const;
  /// Contains() for every point (false for none when the region is empty), canonicalizing the
  /// region only when some point is not inside its raw constraints, or none strictly (a mesh's
  /// hull in the workspace, checked in every scene).
  bool ContainsAll(const std::vector<Eigen::Vector3d>& points_W,
                   double tolerance = kGeometricTolerance) const;
  /// True when the box lies inside the region within tolerance; for a region of lower
  /// dimension (by its equality constraints) the box's centre must lie in the region and the
  /// box's projection onto the region's affine hull must lie inside it.
  bool ContainsBox(const OrientedBox& box, double tolerance = kGeometricTolerance) const;
  /// A point inside the region (the vertex centroid; for balls a feasible point found by
  /// alternating projections). Throws std::domain_error when the region is empty.
  Eigen::Vector3d CalcInteriorPoint() const;
  /// The vertices (world frame): a point 1, a segment 2, a polygon in cyclic order, a
  /// polyhedron in no particular order. For regions with balls, the vertices of the
  /// polytope part (which includes each ball's bounding box). Empty → {}. Throws
  /// std::domain_error when unbounded.
  std::vector<Eigen::Vector3d> CalcVertices() const;
  /// Length, area or volume in the region's own dimension (0 for a point or empty set,
  /// +infinity when unbounded). With balls it is exact only for a lone ball that the other
  /// constraints do not cut (a ball, a disc, a chord); otherwise throws std::domain_error.
  double CalcMeasure() const;
  /// The affine hull after sliver collapse (origin = the hull point nearest the world
  /// origin, except after a collapse). Empty: origin 0 and a 3×0 basis.
  const AffineHull& hull() const;
  /// The unit normal of a planar region (dimension() == 2), with z >= 0; for vertical planes
  /// x > 0, or y > 0 when x is 0 too. Throws std::domain_error when dimension() != 2.
  Eigen::Vector3d CalcPlaneNormal() const;
  /// Fills the cache now (see the class comment on threads). Returns *this.
  const ConvexRegion& Finalize() const;

  /// The raw constraints (world frame, unit normals).
  const std::vector<HalfSpace>& half_spaces() const { return half_spaces_; }
  /// Equalities normal·x == offset (unit normals).
  const std::vector<HalfSpace>& equalities() const { return equalities_; }
  const std::vector<Ball>& balls() const { return balls_; }

  /// A short human description for diagnostics, e.g. "rectangle 0.24 m × 0.45 m at (0, 0,
  /// 0.8)". Never throws for a valid region.
  std::string Describe() const;

  /// The region's canonical form (internal; used by the sampler).
  const internal::RegionCanon& canon() const;

 private:
  enum class Kind { kEmpty, kAll, kHalfSpaces, kHalfSpace, kCuboid, kRect, kPlane, kPolygon,
                    kPolyhedron, kSphere, kSegment, kPoint, kIntersection, kEroded };
  friend ConvexRegion Intersect(const ConvexRegion& a, const ConvexRegion& b);
  friend ConvexRegion ErodeByBox(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                                 const Eigen::Vector3d& half_extents);
  friend ConvexRegion ErodeByRound(const ConvexRegion& region, const Eigen::Vector3d& axis,
                                   double radius);
  friend ConvexRegion ErodeByPoints(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                                    const std::vector<Eigen::Vector3d>& points_B);
  friend ConvexRegion internal::AttachCanon(ConvexRegion region, internal::RegionCanon canon);
  bool RawContains(const Eigen::Vector3d& p_W, double tolerance) const;
  std::string DescribeGeneric() const;

  std::vector<HalfSpace> equalities_;
  std::vector<HalfSpace> half_spaces_;
  std::vector<Ball> balls_;
  bool empty_ = false;
  Kind kind_ = Kind::kAll;
  Eigen::Vector3d p_label_ = Eigen::Vector3d::Zero();  // centre/point used by Describe()
  Eigen::Vector3d size_label_ = Eigen::Vector3d::Zero();  // extents/normal used by Describe()
  int count_label_ = 0;
  mutable std::shared_ptr<const internal::RegionCanon> canon_;
};

/// The intersection of two regions (stacks their constraints; O(size), no geometry).
ConvexRegion Intersect(const ConvexRegion& a, const ConvexRegion& b);

/// The set of centres c for which the box {c + R_WB·(s ∘ half_extents), |s_i| <= 1} lies in
/// `region` (a Minkowski difference, exact for any orientation). Half-space offsets shrink
/// by the box's support along the normal; a ball becomes 8 balls, one per corner. For a
/// region of lower dimension (by its equalities) the box is first projected onto the
/// region's affine hull, so a Rect3D eroded by an object's box is the set of footprint-
/// contained centres in the rectangle's plane. Throws std::invalid_argument for negative or
/// non-finite half_extents.
ConvexRegion ErodeByBox(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                        const Eigen::Vector3d& half_extents);

/// Erosion by a round set K centred at the origin: the disk of `radius` in the plane normal to
/// `axis` (a non-zero vector), or the ball of `radius` when `axis` is zero. Like ErodeByBox, K
/// is first projected onto the region's affine hull. The half-spaces are eroded exactly (each
/// offset shrinks by K's support along the normal); ball constraints are kept as they are,
/// which holds every valid centre because K contains the origin. So the result is the exact
/// erosion for polytopes and a superset when the region has balls. Used where the box's turn
/// is not known yet: a disk inside the box is inside it for every turn about `axis`.
/// Throws std::invalid_argument for a negative or non-finite radius or a non-finite axis.
ConvexRegion ErodeByRound(const ConvexRegion& region, const Eigen::Vector3d& axis, double radius);

/// The set of centres c for which the convex hull of {c + R_WB·p, p in points_B} lies in
/// `region`: exact for any convex region, since a convex region holds a hull iff it holds its
/// vertices (used for mesh shapes with their hull's vertices). Like ErodeByBox, the points are
/// first projected onto the region's affine hull; each half-space offset shrinks by the
/// points' support along its normal and a ball becomes one ball per point. Throws
/// std::invalid_argument for an empty or non-finite point set.
ConvexRegion ErodeByPoints(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                           const std::vector<Eigen::Vector3d>& points_B);

}  // namespace prs::geometry
