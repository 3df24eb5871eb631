// ConvexRegion: constructors, intersection, erosion by a box, and queries over the cached
// canonical form (computed in region_canon.cc).
#include "geometry/region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "geometry/polytope.h"

namespace prs::geometry {
namespace {

std::string FormatNumber(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", std::abs(x) < 5e-13 ? 0.0 : x);
  return buffer;
}

std::string FormatPoint(const Eigen::Vector3d& p) {
  std::string out = "(";
  out += FormatNumber(p.x());
  out += ", ";
  out += FormatNumber(p.y());
  out += ", ";
  out += FormatNumber(p.z());
  out += ")";
  return out;
}

void RequireFinite(const char* where, const char* what, const Eigen::Vector3d& v) {
  if (!v.allFinite()) {
    throw std::invalid_argument(std::string(where) + ": " + what + " must be finite, got " +
                                FormatPoint(v));
  }
}

void RequireExtent(const char* where, const char* what, double x) {
  if (!(x >= 0) || !std::isfinite(x)) {
    throw std::invalid_argument(std::string(where) + ": " + what +
                                " must be finite and >= 0, got " + FormatNumber(x));
  }
}

Eigen::Vector3d RequireDirection(const char* where, const Eigen::Vector3d& normal) {
  RequireFinite(where, "normal", normal);
  const double norm = normal.norm();
  if (norm < 1e-12) {
    throw std::invalid_argument(std::string(where) + ": normal must be non-zero, got " +
                                FormatPoint(normal));
  }
  return normal / norm;
}

// Adds the slab |axis·(x - p_center)| <= half (an equality when half is 0).
void AddSlab(const Eigen::Vector3d& axis, const Eigen::Vector3d& p_center, double half,
             std::vector<HalfSpace>* equalities, std::vector<HalfSpace>* half_spaces) {
  const Eigen::Vector3d n = axis.normalized();
  const double d = n.dot(p_center);
  if (half == 0) {
    equalities->push_back({n, d});
    return;
  }
  half_spaces->push_back({n, d + half});
  half_spaces->push_back({-n, half - d});
}

}  // namespace

ConvexRegion ConvexRegion::Empty() {
  ConvexRegion r;
  r.empty_ = true;
  r.kind_ = Kind::kEmpty;
  return r;
}

ConvexRegion ConvexRegion::All() { return ConvexRegion(); }

ConvexRegion ConvexRegion::FromHalfSpaces(const std::vector<HalfSpace>& half_spaces) {
  ConvexRegion r;
  r.kind_ = Kind::kHalfSpaces;
  r.half_spaces_.reserve(half_spaces.size());
  for (const HalfSpace& h : half_spaces) {
    if (!h.normal.allFinite() || !std::isfinite(h.offset)) {
      throw std::invalid_argument("FromHalfSpaces: non-finite half-space, normal " +
                                  FormatPoint(h.normal) + " offset " + FormatNumber(h.offset));
    }
    const double norm = h.normal.norm();
    if (norm < 1e-12) {
      if (h.offset < 0) return Empty();
      continue;  // 0 <= offset holds everywhere
    }
    r.half_spaces_.push_back({h.normal / norm, h.offset / norm});
  }
  r.count_label_ = static_cast<int>(r.half_spaces_.size());
  return r;
}

ConvexRegion ConvexRegion::MakeHalfSpace(const Eigen::Vector3d& p_point,
                                         const Eigen::Vector3d& normal) {
  RequireFinite("MakeHalfSpace", "point", p_point);
  const Eigen::Vector3d n = RequireDirection("MakeHalfSpace", normal);
  ConvexRegion r;
  r.kind_ = Kind::kHalfSpace;
  r.half_spaces_.push_back({-n, -n.dot(p_point)});
  r.p_label_ = p_point;
  r.size_label_ = n;
  return r;
}

ConvexRegion ConvexRegion::MakeCuboid(const Eigen::Vector3d& p_center,
                                      const Eigen::Matrix3d& R_WB, double width, double length,
                                      double height) {
  RequireFinite("MakeCuboid", "center", p_center);
  RequireExtent("MakeCuboid", "width", width);
  RequireExtent("MakeCuboid", "length", length);
  RequireExtent("MakeCuboid", "height", height);
  ConvexRegion r;
  r.kind_ = Kind::kCuboid;
  const double sizes[3] = {width, length, height};
  for (int i = 0; i < 3; ++i) {
    AddSlab(R_WB.col(i), p_center, 0.5 * sizes[i], &r.equalities_, &r.half_spaces_);
  }
  r.p_label_ = p_center;
  r.size_label_ = Eigen::Vector3d(width, length, height);
  return r;
}

ConvexRegion ConvexRegion::MakeRect3D(const Eigen::Vector3d& p_center,
                                      const Eigen::Matrix3d& R_WB, double width, double length) {
  RequireFinite("MakeRect3D", "center", p_center);
  RequireExtent("MakeRect3D", "width", width);
  RequireExtent("MakeRect3D", "length", length);
  ConvexRegion r;
  r.kind_ = Kind::kRect;
  AddSlab(R_WB.col(0), p_center, 0.5 * width, &r.equalities_, &r.half_spaces_);
  AddSlab(R_WB.col(1), p_center, 0.5 * length, &r.equalities_, &r.half_spaces_);
  AddSlab(R_WB.col(2), p_center, 0.0, &r.equalities_, &r.half_spaces_);
  r.p_label_ = p_center;
  r.size_label_ = Eigen::Vector3d(width, length, 0);
  return r;
}

ConvexRegion ConvexRegion::MakePlane(const Eigen::Vector3d& p_point,
                                     const Eigen::Vector3d& normal) {
  RequireFinite("MakePlane", "point", p_point);
  const Eigen::Vector3d n = RequireDirection("MakePlane", normal);
  ConvexRegion r;
  r.kind_ = Kind::kPlane;
  r.equalities_.push_back({n, n.dot(p_point)});
  r.p_label_ = p_point;
  r.size_label_ = n;
  return r;
}

ConvexRegion ConvexRegion::MakeConvexPolygon3D(const std::vector<Eigen::Vector3d>& vertices) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& v : vertices) {
    RequireFinite("MakeConvexPolygon3D", "vertex", v);
    const bool seen = std::any_of(pts.begin(), pts.end(), [&](const Eigen::Vector3d& q) {
      return (q - v).norm() <= kGeometricTolerance;
    });
    if (!seen) pts.push_back(v);
  }
  if (pts.empty()) return Empty();
  if (pts.size() == 1) return MakePoint(pts[0]);
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pts) c += p;
  c /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - c) * (p - c).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  const Eigen::Vector3d along = solver.eigenvectors().col(2);
  const Eigen::Vector3d n = solver.eigenvectors().col(0).normalized();
  double off_line = 0, off_plane = 0, t_lo = INFINITY, t_hi = -INFINITY;
  for (const auto& p : pts) {
    const double t = along.dot(p - c);
    t_lo = std::min(t_lo, t);
    t_hi = std::max(t_hi, t);
    off_line = std::max(off_line, ((p - c) - t * along).norm());
    off_plane = std::max(off_plane, std::abs(n.dot(p - c)));
  }
  if (off_line <= kGeometricTolerance) return MakeSegment(c + t_lo * along, c + t_hi * along);
  if (off_plane > kGeometricTolerance) {
    throw std::invalid_argument("MakeConvexPolygon3D: the " + std::to_string(pts.size()) +
                                " points are not coplanar: one is " + FormatNumber(off_plane) +
                                " m from their best-fit plane (tolerance 1e-9 m)");
  }
  const Eigen::Matrix<double, 3, 2> basis = internal::CalcPlaneBasis(n);
  std::vector<Eigen::Vector2d> flat;
  for (const auto& p : pts) flat.push_back(basis.transpose() * (p - c));
  std::vector<int> order;
  internal::CalcConvexHull2D(flat, &order);
  if (order.size() < 3) return MakeSegment(c + t_lo * along, c + t_hi * along);
  ConvexRegion r;
  r.kind_ = Kind::kPolygon;
  r.equalities_.push_back({n, n.dot(c)});
  for (size_t i = 0; i < order.size(); ++i) {
    const Eigen::Vector2d& p = flat[order[i]];
    const Eigen::Vector2d e = (flat[order[(i + 1) % order.size()]] - p).normalized();
    const Eigen::Vector3d normal = basis * Eigen::Vector2d(e.y(), -e.x());  // outward (CCW)
    r.half_spaces_.push_back({normal, normal.dot(c + basis * p)});
  }
  r.p_label_ = c;
  r.count_label_ = static_cast<int>(order.size());
  return r;
}

ConvexRegion ConvexRegion::MakeConvexPolyhedron(const std::vector<HalfSpace>& half_spaces) {
  ConvexRegion r = FromHalfSpaces(half_spaces);
  if (!r.empty_) r.kind_ = Kind::kPolyhedron;
  return r;
}

ConvexRegion ConvexRegion::MakeSphere(const Eigen::Vector3d& p_center, double radius) {
  RequireFinite("MakeSphere", "center", p_center);
  RequireExtent("MakeSphere", "radius", radius);
  if (radius == 0) return MakePoint(p_center);
  ConvexRegion r;
  r.kind_ = Kind::kSphere;
  r.balls_.push_back({p_center, radius});
  r.p_label_ = p_center;
  r.size_label_ = Eigen::Vector3d::Constant(radius);
  return r;
}

ConvexRegion ConvexRegion::MakeSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  RequireFinite("MakeSegment", "a", a);
  RequireFinite("MakeSegment", "b", b);
  const double length = (b - a).norm();
  if (length < 1e-12) return MakePoint(0.5 * (a + b));
  const Eigen::Vector3d d = (b - a) / length;
  const Eigen::Matrix<double, 3, 2> basis = internal::CalcPlaneBasis(d);
  ConvexRegion r;
  r.kind_ = Kind::kSegment;
  r.equalities_.push_back({basis.col(0), basis.col(0).dot(a)});
  r.equalities_.push_back({basis.col(1), basis.col(1).dot(a)});
  r.half_spaces_.push_back({d, d.dot(b)});
  r.half_spaces_.push_back({-d, -d.dot(a)});
  r.p_label_ = a;
  r.size_label_ = b;
  return r;
}

ConvexRegion ConvexRegion::MakePoint(const Eigen::Vector3d& p) {
  RequireFinite("MakePoint", "point", p);
  ConvexRegion r;
  r.kind_ = Kind::kPoint;
  for (int i = 0; i < 3; ++i) r.equalities_.push_back({Eigen::Vector3d::Unit(i), p[i]});
  r.p_label_ = p;
  return r;
}

ConvexRegion Intersect(const ConvexRegion& a, const ConvexRegion& b) {
  using Kind = ConvexRegion::Kind;
  if (a.empty_ || b.empty_) return ConvexRegion::Empty();
  if (b.kind_ == Kind::kAll) return a;
  if (a.kind_ == Kind::kAll) return b;
  ConvexRegion r;
  r.kind_ = Kind::kIntersection;
  r.equalities_.reserve(a.equalities_.size() + b.equalities_.size());
  r.equalities_ = a.equalities_;
  r.equalities_.insert(r.equalities_.end(), b.equalities_.begin(), b.equalities_.end());
  r.half_spaces_.reserve(a.half_spaces_.size() + b.half_spaces_.size());
  r.half_spaces_ = a.half_spaces_;
  r.half_spaces_.insert(r.half_spaces_.end(), b.half_spaces_.begin(), b.half_spaces_.end());
  r.balls_ = a.balls_;
  r.balls_.insert(r.balls_.end(), b.balls_.begin(), b.balls_.end());
  return r;
}

ConvexRegion ErodeByBox(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                        const Eigen::Vector3d& half_extents) {
  for (int i = 0; i < 3; ++i) RequireExtent("ErodeByBox", "half_extents", half_extents[i]);
  if (region.empty_) return ConvexRegion::Empty();
  AffineHull hull;
  if (!internal::CalcEqualityHull(region.equalities_, &hull)) return ConvexRegion::Empty();
  // Only the in-hull part of the box matters: project it with P = B·Bᵀ.
  const Eigen::Matrix3d P = hull.basis * hull.basis.transpose();
  ConvexRegion r = region;
  r.canon_.reset();
  r.kind_ = ConvexRegion::Kind::kEroded;
  for (HalfSpace& h : r.half_spaces_) h.offset -= CalcBoxSupport(R_WB, half_extents, P * h.normal);
  r.balls_.clear();
  for (const Ball& ball : region.balls_) {
    const size_t first = r.balls_.size();
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d s((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
      const Eigen::Vector3d center = ball.p_center - P * (R_WB * s.cwiseProduct(half_extents));
      const bool seen = std::any_of(r.balls_.begin() + first, r.balls_.end(),
                                    [&](const Ball& b) { return b.p_center == center; });
      if (!seen) r.balls_.push_back({center, ball.radius});
    }
  }
  r.size_label_ = half_extents;
  return r;
}

ConvexRegion ErodeByRound(const ConvexRegion& region, const Eigen::Vector3d& axis, double radius) {
  RequireExtent("ErodeByRound", "radius", radius);
  RequireFinite("ErodeByRound", "axis", axis);
  if (region.empty_) return ConvexRegion::Empty();
  AffineHull hull;
  if (!internal::CalcEqualityHull(region.equalities_, &hull)) return ConvexRegion::Empty();
  const Eigen::Matrix3d P = hull.basis * hull.basis.transpose();
  // K's support along v is radius·|Q·v|, Q projecting onto the disk's plane (I for a ball).
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
  if (axis.norm() > 0) Q -= axis.normalized() * axis.normalized().transpose();
  ConvexRegion r = region;
  r.canon_.reset();
  r.kind_ = ConvexRegion::Kind::kEroded;
  for (HalfSpace& h : r.half_spaces_) h.offset -= radius * (Q * (P * h.normal)).norm();
  r.size_label_ = Eigen::Vector3d::Constant(radius);
  return r;
}

ConvexRegion ErodeByPoints(const ConvexRegion& region, const Eigen::Matrix3d& R_WB,
                           const std::vector<Eigen::Vector3d>& points_B) {
  if (points_B.empty()) throw std::invalid_argument("ErodeByPoints: no points");
  Eigen::Vector3d lo = points_B[0], hi = points_B[0];
  for (const Eigen::Vector3d& p : points_B) {
    RequireFinite("ErodeByPoints", "points_B", p);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (region.empty_) return ConvexRegion::Empty();
  AffineHull hull;
  if (!internal::CalcEqualityHull(region.equalities_, &hull)) return ConvexRegion::Empty();
  const Eigen::Matrix3d P = hull.basis * hull.basis.transpose();
  std::vector<Eigen::Vector3d> points_W;  // rotated and projected: P·R_WB·p
  points_W.reserve(points_B.size());
  for (const Eigen::Vector3d& p : points_B) points_W.push_back(P * (R_WB * p));
  ConvexRegion r = region;
  r.canon_.reset();
  r.kind_ = ConvexRegion::Kind::kEroded;
  for (HalfSpace& h : r.half_spaces_) {
    double support = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : points_W) support = std::max(support, h.normal.dot(p));
    h.offset -= support;
  }
  r.balls_.clear();
  for (const Ball& ball : region.balls_) {
    for (const Eigen::Vector3d& p : points_W) r.balls_.push_back({ball.p_center - p, ball.radius});
  }
  r.size_label_ = (hi - lo) / 2;
  return r;
}

ConvexRegion internal::AttachCanon(ConvexRegion region, RegionCanon canon) {
  region.canon_ = std::make_shared<const RegionCanon>(std::move(canon));
  return region;
}

const internal::RegionCanon& ConvexRegion::canon() const {
  if (!canon_) {
    if (empty_) {
      auto c = std::make_shared<internal::RegionCanon>();
      c->hull.basis.resize(3, 0);
      canon_ = std::move(c);
    } else {
      canon_ = std::make_shared<const internal::RegionCanon>(
          internal::Canonicalize(equalities_, half_spaces_, balls_));
    }
  }
  return *canon_;
}

const ConvexRegion& ConvexRegion::Finalize() const {
  canon();
  return *this;
}

bool ConvexRegion::IsEmpty() const { return empty_ || canon().empty; }
bool ConvexRegion::IsBounded() const { return IsEmpty() || canon().bounded; }
int ConvexRegion::dimension() const { return IsEmpty() ? -1 : canon().dimension; }
const AffineHull& ConvexRegion::hull() const { return canon().hull; }

bool ConvexRegion::RawContains(const Eigen::Vector3d& p_W, double tolerance) const {
  const double eq_tolerance = std::max(tolerance, kGeometricTolerance);
  for (const HalfSpace& e : equalities_) {
    if (std::abs(e.normal.dot(p_W) - e.offset) > eq_tolerance) return false;
  }
  for (const HalfSpace& h : half_spaces_) {
    if (h.normal.dot(p_W) - h.offset > tolerance) return false;
  }
  for (const Ball& b : balls_) {
    if ((p_W - b.p_center).norm() - b.radius > tolerance) return false;
  }
  return true;
}

bool ConvexRegion::Contains(const Eigen::Vector3d& p_W, double tolerance) const {
  if (empty_ || !p_W.allFinite()) return false;
  if (RawContains(p_W, tolerance)) {
    // A point strictly inside every half-space proves the region non-empty.
    if (RawContains(p_W, std::min(tolerance, 0.0) - kGeometricTolerance)) return true;
    return !canon().empty;
  }
  // Points of a collapsed sliver may sit a few 1e-9 m outside the raw constraints.
  if (!RawContains(p_W, tolerance + 4 * kGeometricTolerance)) return false;
  const internal::RegionCanon& c = canon();
  return !c.empty && c.contains_slack > 0 && RawContains(p_W, tolerance + c.contains_slack);
}

bool ConvexRegion::ContainsAll(const std::vector<Eigen::Vector3d>& points_W, double tolerance) const {
  if (empty_) return false;
  bool proven_nonempty = false;  // by a point strictly inside every constraint (see Contains)
  for (const Eigen::Vector3d& p : points_W) {
    if (!p.allFinite()) return false;
    if (!RawContains(p, tolerance)) {
      if (!RawContains(p, tolerance + 4 * kGeometricTolerance)) return false;
      // Only a collapsed sliver's slack can keep it: the full test for each point.
      return std::all_of(points_W.begin(), points_W.end(),
                         [&](const Eigen::Vector3d& q) { return Contains(q, tolerance); });
    }
    proven_nonempty = proven_nonempty || RawContains(p, std::min(tolerance, 0.0) - kGeometricTolerance);
  }
  // Every point is inside the raw constraints: Contains() holds for each iff the region is
  // non-empty.
  return proven_nonempty || !canon().empty;
}

bool ConvexRegion::ContainsBox(const OrientedBox& box, double tolerance) const {
  // Contains() proves non-emptiness on its own, mostly without canonicalizing the region
  // (the workspace is checked in every scene, so this matters for speed).
  if (!Contains(box.p_center, tolerance)) return false;
  if (equalities_.empty() && balls_.empty()) {
    // A polytope holds the box iff each half-space holds the box's support point along its
    // normal: one dot product per face instead of eight corner tests.
    double excess = -std::numeric_limits<double>::infinity();
    for (const HalfSpace& h : half_spaces_) {
      const Eigen::Vector3d n_B = box.R_WB.transpose() * h.normal;
      excess = std::max(excess, h.normal.dot(box.p_center) + n_B.cwiseAbs().dot(box.half_extents) -
                                    h.offset);
    }
    if (excess <= tolerance) return true;
    // Clearly outside; only a collapsed sliver's extra slack (see Contains) needs the corners.
    if (excess > tolerance + 4 * kGeometricTolerance) return false;
  }
  AffineHull eq_hull;
  if (!internal::CalcEqualityHull(equalities_, &eq_hull)) return false;
  const Eigen::Matrix3d P = eq_hull.basis * eq_hull.basis.transpose();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d s((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
    const Eigen::Vector3d corner = box.p_center + P * (box.R_WB * s.cwiseProduct(box.half_extents));
    if (!Contains(corner, tolerance)) return false;
  }
  return true;
}

Eigen::Vector3d ConvexRegion::CalcInteriorPoint() const {
  if (IsEmpty()) throw std::domain_error("CalcInteriorPoint: the region is empty: " + Describe());
  return canon().p_interior;
}

std::vector<Eigen::Vector3d> ConvexRegion::CalcVertices() const {
  if (IsEmpty()) return {};
  if (!canon().bounded) {
    throw std::domain_error("CalcVertices: the region is unbounded: " + Describe());
  }
  return canon().vertices;
}

double ConvexRegion::CalcMeasure() const {
  if (IsEmpty()) return 0.0;
  const internal::RegionCanon& c = canon();
  if (!c.bounded) return INFINITY;
  if (!c.measure_exact) {
    throw std::domain_error("CalcMeasure: not supported for balls cut by other constraints: " +
                            Describe());
  }
  return c.measure;
}

Eigen::Vector3d ConvexRegion::CalcPlaneNormal() const {
  if (dimension() != 2) {
    throw std::domain_error("CalcPlaneNormal: the region has dimension " +
                            std::to_string(dimension()) + ", not 2: " + Describe());
  }
  const auto& B = canon().hull.basis;
  Eigen::Vector3d n = B.col(0).cross(B.col(1)).normalized();
  constexpr double kFlat = 1e-12;
  const bool flip = std::abs(n.z()) > kFlat ? n.z() < 0
                    : std::abs(n.x()) > kFlat ? n.x() < 0
                                              : n.y() < 0;
  return flip ? Eigen::Vector3d(-n) : n;
}

std::string ConvexRegion::DescribeGeneric() const {
  const std::string constraints = std::to_string(equalities_.size() + half_spaces_.size() +
                                                 balls_.size()) + " constraints";
  if (IsEmpty()) return "empty region (" + constraints + ")";
  const internal::RegionCanon& c = canon();
  const std::string dim = "region of dimension " + std::to_string(c.dimension);
  if (!c.bounded) return "unbounded " + dim + " (" + constraints + ")";
  Eigen::Vector3d lo = c.vertices[0], hi = c.vertices[0];
  for (const auto& v : c.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d size = hi - lo;
  return dim + ", extent " + FormatNumber(size.x()) + " m × " + FormatNumber(size.y()) +
         " m × " + FormatNumber(size.z()) + " m around " + FormatPoint(c.p_interior) + " (" +
         constraints + ")";
}

std::string ConvexRegion::Describe() const {
  const Eigen::Vector3d& s = size_label_;
  const std::string at = " at " + FormatPoint(p_label_);
  switch (kind_) {
    case Kind::kEmpty: return "empty region";
    case Kind::kAll: return "all of space";
    case Kind::kHalfSpace: return "half-space through " + FormatPoint(p_label_) +
                                  " toward " + FormatPoint(s);
    case Kind::kCuboid: return "cuboid " + FormatNumber(s.x()) + " m × " + FormatNumber(s.y()) +
                               " m × " + FormatNumber(s.z()) + " m" + at;
    case Kind::kRect: return "rectangle " + FormatNumber(s.x()) + " m × " + FormatNumber(s.y()) +
                             " m" + at;
    case Kind::kPlane: return "plane through " + FormatPoint(p_label_) + " with normal " +
                              FormatPoint(s);
    case Kind::kPolygon: return "convex polygon with " + std::to_string(count_label_) +
                                " vertices around " + FormatPoint(p_label_);
    case Kind::kPolyhedron: return "convex polyhedron of " + std::to_string(count_label_) +
                                   " half-spaces: " + DescribeGeneric();
    case Kind::kSphere: return "sphere of radius " + FormatNumber(s.x()) + " m" + at;
    case Kind::kSegment: return "segment from " + FormatPoint(p_label_) + " to " + FormatPoint(s);
    case Kind::kPoint: return "point " + FormatPoint(p_label_);
    case Kind::kEroded: return "eroded by a box of half-extents " + FormatPoint(s) + ": " +
                               DescribeGeneric();
    case Kind::kHalfSpaces:
    case Kind::kIntersection: return DescribeGeneric();
  }
  return DescribeGeneric();
}

}  // namespace prs::geometry
