// Computes the canonical form of a ConvexRegion: affine hull, clipped vertices and faces,
// sliver collapse, ball feasibility, measure and an interior point (docs/geometry.md).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/check.h"
#include "geometry/polytope.h"

namespace prs::geometry::internal {
namespace {

// Each constraint is relaxed by this in the second clipping pass, so that constraints
// crossing by less than 2 × kRelax = 1e-9 m still leave a (collapsed) region.
constexpr double kRelax = 0.5 * kGeometricTolerance;
// After a relaxed pass, anything thinner than this is a collapsed crossing.
constexpr double kRelaxedThin = 4 * kGeometricTolerance;
// Vertices this close to the big box count as unbounded.
constexpr double kBoundMargin = 1e-3;

// a·u <= b in hull coordinates (only the first k entries of a are used; |a| = 1).
struct HullConstraint {
  Eigen::Vector3d a;
  double b;
};

struct HullBall {
  Eigen::Vector3d u_center;  // hull coordinates
  double radius;             // radius of the ball's slice through the hull
};

// The region's body in hull coordinates, in its current dimension.
struct Body {
  int dim = -1;
  AffineHull hull;
  double lo = 0, hi = 0;                  // dim 1
  std::vector<Eigen::Vector2d> polygon;   // dim 2, CCW
  Polyhedron poly;                        // dim 3 (hull = world)
  std::vector<Eigen::Vector3d> vertices;  // dim 3: poly's distinct points
};

bool ProjectHalfSpaces(const std::vector<HalfSpace>& half_spaces, const AffineHull& hull,
                       std::vector<HullConstraint>* out) {
  const int k = static_cast<int>(hull.basis.cols());
  for (const HalfSpace& h : half_spaces) {
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    a.head(k) = hull.basis.transpose() * h.normal;
    const double b = h.offset - h.normal.dot(hull.p_origin);
    const double norm = a.norm();
    if (norm < 1e-12) {  // constant on the hull
      if (b < -kGeometricTolerance) return false;
      continue;
    }
    out->push_back({a / norm, b / norm});
  }
  return true;
}

// Slices the balls with the hull and adds their bounding boxes (exact when k <= 1).
bool AddBallBounds(const std::vector<Ball>& balls, const AffineHull& hull,
                   std::vector<HullConstraint>* out, std::vector<HullBall>* hull_balls) {
  const int k = static_cast<int>(hull.basis.cols());
  for (const Ball& ball : balls) {
    const Eigen::Vector3d d = ball.p_center - hull.p_origin;
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    u.head(k) = hull.basis.transpose() * d;
    const double dist2 = std::max(0.0, d.squaredNorm() - u.squaredNorm());
    if (std::sqrt(dist2) > ball.radius + kGeometricTolerance) return false;
    const double r = std::sqrt(std::max(0.0, ball.radius * ball.radius - dist2));
    hull_balls->push_back({u, r});
    for (int i = 0; i < k; ++i) {
      out->push_back({Eigen::Vector3d::Unit(i), u[i] + r});
      out->push_back({-Eigen::Vector3d::Unit(i), -u[i] + r});
    }
  }
  return true;
}

bool ClipBody(const std::vector<HullConstraint>& cons, double relax, Body* body) {
  const double big = kBigHalfSize;
  switch (body->dim) {
    case 0:
      return true;
    case 1:
      body->lo = -big;
      body->hi = big;
      for (const HullConstraint& c : cons) {
        if (c.a[0] > 0) body->hi = std::min(body->hi, (c.b + relax) / c.a[0]);
        else body->lo = std::max(body->lo, (c.b + relax) / c.a[0]);
      }
      return body->lo <= body->hi;
    case 2: {
      body->polygon = {{-big, -big}, {big, -big}, {big, big}, {-big, big}};
      std::vector<Eigen::Vector2d> scratch;
      scratch.reserve(16);
      for (const HullConstraint& c : cons) {
        if (!ClipPolygon(c.a.head<2>(), c.b + relax, &body->polygon, &scratch)) return false;
      }
      return true;
    }
    default: {
      MakeCubePolyhedron(big, &body->poly);
      ClipScratch scratch;
      for (Polyhedron* p : {&body->poly, &scratch.poly}) {
        p->points.reserve(128);
        p->face_start.reserve(33);
        p->face_normal.reserve(32);
        p->face_offset.reserve(32);
      }
      scratch.cut.reserve(32);
      scratch.cut_2d.reserve(32);
      scratch.hull.reserve(64);
      scratch.side.reserve(128);
      for (const HullConstraint& c : cons) {
        if (!ClipPolyhedron(c.a, c.b + relax, &body->poly, &scratch)) return false;
      }
      return true;
    }
  }
}

bool IsBodyBounded(const Body& body) {
  const double limit = kBigHalfSize - kBoundMargin;
  switch (body.dim) {
    case 1: return body.lo > -limit && body.hi < limit;
    case 2:
      for (const auto& p : body.polygon) if (p.cwiseAbs().maxCoeff() >= limit) return false;
      return true;
    case 3:
      for (const auto& p : body.poly.points) if (p.cwiseAbs().maxCoeff() >= limit) return false;
      return true;
    default: return true;
  }
}

// Thinnest width of a polyhedron (with distinct vertices `vertices`) over its face normals.
double CalcThinnestFace(const Polyhedron& poly, const std::vector<Eigen::Vector3d>& vertices,
                        Eigen::Vector3d* normal) {
  double best = INFINITY;
  for (int f = 0; f < poly.num_faces(); ++f) {
    double lowest = INFINITY;
    for (const auto& p : vertices) lowest = std::min(lowest, poly.face_normal[f].dot(p));
    const double width = poly.face_offset[f] - lowest;
    if (width < best) {
      best = width;
      *normal = poly.face_normal[f];
    }
  }
  return best;
}

// Thinnest width of a polygon over its edge normals; *along gets the edge direction.
double CalcThinnestEdge(const std::vector<Eigen::Vector2d>& polygon, Eigen::Vector2d* along) {
  const size_t n = polygon.size();
  if (n < 3) {
    if (n == 2 && (polygon[1] - polygon[0]).norm() > 0) {
      *along = (polygon[1] - polygon[0]).normalized();
    } else {
      *along = Eigen::Vector2d::UnitX();
    }
    return 0.0;
  }
  double best = INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d edge = polygon[(i + 1) % n] - polygon[i];
    const double len = edge.norm();
    if (len < 1e-15) continue;
    const Eigen::Vector2d e = edge / len, inward(-e.y(), e.x());
    double width = 0;
    for (const auto& p : polygon) width = std::max(width, inward.dot(p - polygon[i]));
    if (width < best) {
      best = width;
      *along = e;
    }
  }
  return best == INFINITY ? 0.0 : best;
}

void CollapseTo2(const Eigen::Vector3d& n, const std::vector<Eigen::Vector3d>& vertices,
                 Body* body) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : vertices) {
    lo = std::min(lo, n.dot(p));
    hi = std::max(hi, n.dot(p));
  }
  const Eigen::Matrix<double, 3, 2> basis = CalcPlaneBasis(n);
  std::vector<Eigen::Vector2d> flat;
  flat.reserve(vertices.size());
  for (const auto& p : vertices) flat.push_back(basis.transpose() * p);
  std::vector<int> order;
  CalcConvexHull2D(flat, &order);
  body->polygon.clear();
  for (int idx : order) body->polygon.push_back(flat[idx]);
  body->hull.p_origin = body->hull.p_origin + 0.5 * (lo + hi) * n;  // 3D hull: origin 0, I
  body->hull.basis = basis;
  body->dim = 2;
}

void CollapseTo1(const Eigen::Vector2d& e, Body* body) {
  const Eigen::Vector2d m(-e.y(), e.x());
  double lo = INFINITY, hi = -INFINITY, mlo = INFINITY, mhi = -INFINITY;
  for (const auto& p : body->polygon) {
    lo = std::min(lo, e.dot(p));
    hi = std::max(hi, e.dot(p));
    mlo = std::min(mlo, m.dot(p));
    mhi = std::max(mhi, m.dot(p));
  }
  const Eigen::Matrix<double, 3, 2> B = body->hull.basis;
  body->hull.p_origin += B * (0.5 * (mlo + mhi) * m);
  body->hull.basis = B * e;
  body->lo = lo;
  body->hi = hi;
  body->dim = 1;
}

void CollapseTo0(Body* body) {
  body->hull.p_origin += body->hull.basis * Eigen::Matrix<double, 1, 1>(0.5 * (body->lo + body->hi));
  body->hull.basis.resize(3, 0);
  body->dim = 0;
}

// Collapses dimensions thinner than `thin`; returns the largest width collapsed.
double CollapseSlivers(double thin, Body* body) {
  double collapsed = 0;
  for (;;) {
    if (body->dim == 3) {
      CalcDistinctPoints(body->poly.points, kGeometricTolerance, &body->vertices);
      Eigen::Vector3d n;
      const double width = CalcThinnestFace(body->poly, body->vertices, &n);
      if (width >= thin) break;
      collapsed = std::max(collapsed, width);
      CollapseTo2(n, body->vertices, body);
    } else if (body->dim == 2) {
      Eigen::Vector2d e;
      const double width = CalcThinnestEdge(body->polygon, &e);
      if (width >= thin) break;
      collapsed = std::max(collapsed, width);
      CollapseTo1(e, body);
    } else if (body->dim == 1) {
      if (body->hi - body->lo >= thin) break;
      collapsed = std::max(collapsed, body->hi - body->lo);
      CollapseTo0(body);
    } else {
      break;
    }
  }
  return collapsed;
}

Eigen::Vector3d CalcBodyCentroid(const Body& body) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  if (body.dim == 1) {
    u[0] = 0.5 * (body.lo + body.hi);
  } else if (body.dim == 2) {
    for (const auto& p : body.polygon) u.head<2>() += p;
    u /= static_cast<double>(body.polygon.size());
  } else if (body.dim == 3) {
    for (const auto& p : body.poly.points) u += p;
    u /= static_cast<double>(body.poly.points.size());
  }
  return u;
}

double CalcBallViolation(const Eigen::Vector3d& u, const std::vector<HullConstraint>& cons,
                         const std::vector<HullBall>& balls) {
  double worst = -INFINITY;
  for (const auto& c : cons) worst = std::max(worst, c.a.dot(u) - c.b);
  for (const auto& b : balls) worst = std::max(worst, (u - b.u_center).norm() - b.radius);
  return worst;
}

// Alternating projections onto the half-spaces and balls, from *u. True when a point
// within 1e-9 m of every set was found (left in *u).
bool FindBallFeasiblePoint(const std::vector<HullConstraint>& cons,
                           const std::vector<HullBall>& balls, Eigen::Vector3d* u) {
  for (int sweep = 0; sweep < 5000; ++sweep) {
    if (CalcBallViolation(*u, cons, balls) <= kGeometricTolerance) return true;
    for (const auto& c : cons) {
      const double excess = c.a.dot(*u) - c.b;
      if (excess > 0) *u -= excess * c.a;
    }
    for (const auto& b : balls) {
      const Eigen::Vector3d d = *u - b.u_center;
      const double dist = d.norm();
      if (dist > b.radius) *u = b.u_center + d * (b.radius / dist);
    }
  }
  return CalcBallViolation(*u, cons, balls) <= kGeometricTolerance;
}

double CalcPolygonArea(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const auto& p = polygon[i];
    const auto& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::abs(twice);
}

void FinishPolyhedron(const Body& body, RegionCanon* canon) {
  canon->face_points = body.poly.points;
  canon->face_start = body.poly.face_start;
  canon->vertices = body.vertices;  // filled by CollapseSlivers
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& v : canon->vertices) c += v;
  c /= static_cast<double>(canon->vertices.size());
  double volume = 0;
  for (int f = 0; f < body.poly.num_faces(); ++f) {
    const int begin = body.poly.face_start[f], end = body.poly.face_start[f + 1];
    const Eigen::Vector3d& p0 = body.poly.points[begin];
    for (int i = begin + 1; i + 1 < end; ++i) {
      volume += std::abs((p0 - c).dot((body.poly.points[i] - c).cross(body.poly.points[i + 1] - c)));
    }
  }
  canon->polytope_measure = volume / 6.0;
  canon->p_interior = c;
}

// Fills vertices, faces, measure and interior point from the (collapsed) body.
void FinishCanon(Body& body, RegionCanon* canon) {
  PRS_CHECK(body.dim != 3 || !body.vertices.empty());
  canon->dimension = body.dim;
  canon->hull = body.hull;
  const AffineHull& h = body.hull;
  switch (body.dim) {
    case 0:
      canon->vertices = {h.p_origin};
      canon->p_interior = h.p_origin;
      break;
    case 1:
      canon->vertices = {h.p_origin + h.basis.col(0) * body.lo, h.p_origin + h.basis.col(0) * body.hi};
      canon->polytope_measure = body.hi - body.lo;
      canon->p_interior = 0.5 * (canon->vertices[0] + canon->vertices[1]);
      break;
    case 2: {
      std::vector<int> order;
      CalcConvexHull2D(body.polygon, &order);
      if (order.size() >= 3) {
        std::vector<Eigen::Vector2d> clean;
        for (int idx : order) clean.push_back(body.polygon[idx]);
        body.polygon.swap(clean);
      }
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (const auto& p : body.polygon) {
        canon->vertices.push_back(h.p_origin + h.basis * p);
        c += p;
      }
      c /= static_cast<double>(body.polygon.size());
      canon->polytope_measure = CalcPolygonArea(body.polygon);
      canon->p_interior = h.p_origin + h.basis * c;
      break;
    }
    default:
      FinishPolyhedron(body, canon);
  }
  canon->measure = canon->bounded ? canon->polytope_measure : INFINITY;
}

// The exact measure when a lone ball is not cut by the other constraints (k = 2, 3).
void SetBallMeasure(int k, int num_plain, const std::vector<HullConstraint>& cons,
                    const std::vector<HullBall>& balls, RegionCanon* canon) {
  canon->measure_exact = false;
  if (balls.size() != 1 || canon->dimension != k) return;
  const HullBall& b = balls[0];
  for (int i = 0; i < num_plain; ++i) {
    if (cons[i].a.dot(b.u_center) + b.radius > cons[i].b + 1e-12) return;
  }
  canon->measure_exact = true;
  canon->measure = k == 3 ? 4.0 / 3.0 * std::numbers::pi * std::pow(b.radius, 3)
                          : std::numbers::pi * b.radius * b.radius;
}

}  // namespace

RegionCanon Canonicalize(const std::vector<HalfSpace>& equalities,
                         const std::vector<HalfSpace>& half_spaces,
                         const std::vector<Ball>& balls) {
  RegionCanon canon;
  canon.hull.basis.resize(3, 0);
  Body body;
  if (!CalcEqualityHull(equalities, &body.hull)) return canon;
  const int k = static_cast<int>(body.hull.basis.cols());
  std::vector<HullConstraint> cons;
  cons.reserve(half_spaces.size() + 2 * k * balls.size());
  if (!ProjectHalfSpaces(half_spaces, body.hull, &cons)) return canon;
  const int num_plain = static_cast<int>(cons.size());
  std::vector<HullBall> hull_balls;
  if (!AddBallBounds(balls, body.hull, &cons, &hull_balls)) return canon;

  body.dim = k;
  double thin = kGeometricTolerance;
  if (!ClipBody(cons, 0.0, &body)) {
    if (!ClipBody(cons, kRelax, &body)) return canon;
    thin = kRelaxedThin;
    canon.contains_slack = 2 * kRelax;
  }
  canon.bounded = IsBodyBounded(body);
  Eigen::Vector3d u_feasible = CalcBodyCentroid(body);
  if (k >= 2 && !hull_balls.empty() && !FindBallFeasiblePoint(cons, hull_balls, &u_feasible)) {
    return canon;
  }
  const AffineHull full_hull = body.hull;
  canon.contains_slack = std::max(canon.contains_slack, CollapseSlivers(thin, &body));
  canon.empty = false;
  FinishCanon(body, &canon);
  if (k >= 2 && !balls.empty()) {
    canon.balls = balls;
    canon.p_interior = full_hull.p_origin + full_hull.basis * u_feasible.head(k);
    SetBallMeasure(k, num_plain, cons, hull_balls, &canon);
  }
  PRS_CHECK(canon.dimension >= 0 && canon.dimension <= 3);
  return canon;
}

}  // namespace prs::geometry::internal
