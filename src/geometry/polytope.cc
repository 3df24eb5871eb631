// Clipping and hull primitives behind the canonical form of a ConvexRegion.
#include "geometry/polytope.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <Eigen/Eigenvalues>

#include "geometry/check.h"

namespace prs::geometry::internal {
namespace {

// Below this eigenvalue of Σ n nᵀ a direction counts as unconstrained (angle ~1e-6 rad).
constexpr double kRankEigenvalue = 1e-12;

double Cross2(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// True when b does not make a strict left turn after o→a (collinear within ~1e-12 rad).
bool IsNotLeftTurn(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double cross = Cross2(o, a, b);
  return cross <= 0 || cross * cross <= 1e-24 * (a - o).squaredNorm() * (b - o).squaredNorm();
}

// The point where segment inside→outside crosses the plane; always called inside-first so
// that the two faces sharing an edge compute bitwise-identical points.
template <typename Vec>
Vec CrossingPoint(const Vec& inside, const Vec& outside, double s_in, double s_out) {
  const double t = s_in / (s_in - s_out);
  return inside + t * (outside - inside);
}

}  // namespace

bool CalcEqualityHull(const std::vector<HalfSpace>& equalities, AffineHull* hull) {
  if (equalities.empty()) {
    hull->p_origin.setZero();
    hull->basis = Eigen::Matrix3d::Identity();
    return true;
  }
  if (equalities.size() == 1) {
    hull->p_origin = equalities[0].offset * equalities[0].normal;
    hull->basis = CalcPlaneBasis(equalities[0].normal);
    return true;
  }
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const HalfSpace& e : equalities) {
    AtA += e.normal * e.normal.transpose();
    Atb += e.offset * e.normal;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(AtA);
  const Eigen::Vector3d& lambda = solver.eigenvalues();  // ascending
  const Eigen::Matrix3d& V = solver.eigenvectors();
  int free_dims = 0;
  hull->p_origin.setZero();
  for (int i = 0; i < 3; ++i) {
    if (lambda[i] <= kRankEigenvalue) {
      ++free_dims;
    } else {
      hull->p_origin += V.col(i) * (V.col(i).dot(Atb) / lambda[i]);
    }
  }
  for (const HalfSpace& e : equalities) {
    if (std::abs(e.normal.dot(hull->p_origin) - e.offset) > kGeometricTolerance) return false;
  }
  hull->basis = V.leftCols(free_dims);
  return true;
}

Eigen::Matrix<double, 3, 2> CalcPlaneBasis(const Eigen::Vector3d& unit_normal) {
  int helper = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(unit_normal[i]) < std::abs(unit_normal[helper])) helper = i;
  }
  const Eigen::Vector3d h = Eigen::Vector3d::Unit(helper);
  const Eigen::Vector3d u = (h - h.dot(unit_normal) * unit_normal).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = u;
  basis.col(1) = unit_normal.cross(u);
  return basis;
}

void CalcConvexHull2D(const std::vector<Eigen::Vector2d>& points, std::vector<int>* hull) {
  hull->clear();
  const int n = static_cast<int>(points.size());
  if (n == 0) return;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return points[i].x() < points[j].x() ||
           (points[i].x() == points[j].x() && points[i].y() < points[j].y());
  });
  std::vector<int>& h = *hull;
  h.reserve(2 * n);
  for (int pass = 0; pass < 2; ++pass) {  // lower chain, then upper chain
    const size_t chain_start = h.size();
    for (int k = 0; k < n; ++k) {
      const int idx = order[pass == 0 ? k : n - 1 - k];
      while (h.size() >= chain_start + 2 &&
             IsNotLeftTurn(points[h[h.size() - 2]], points[h.back()], points[idx])) {
        h.pop_back();
      }
      h.push_back(idx);
    }
    h.pop_back();  // the chain's last point starts the other chain
  }
  // Drop points that coincide (within 1e-12 m) with their predecessor, in place.
  size_t kept = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    if (kept == 0 || (points[h[i]] - points[h[kept - 1]]).squaredNorm() > 1e-24) h[kept++] = h[i];
  }
  h.resize(kept);
  while (h.size() > 1 && (points[h.back()] - points[h[0]]).squaredNorm() <= 1e-24) h.pop_back();
}

void CalcDistinctPoints(const std::vector<Eigen::Vector3d>& points, double tolerance,
                        std::vector<Eigen::Vector3d>* distinct) {
  // Shared vertices are bitwise equal (see CrossingPoint), so sort + unique does most of the
  // work; a tolerance pass over the few survivors catches the rest.
  std::vector<Eigen::Vector3d> sorted = points;
  std::sort(sorted.begin(), sorted.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  distinct->clear();
  for (const Eigen::Vector3d& p : sorted) {
    const bool seen = std::any_of(distinct->begin(), distinct->end(), [&](const Eigen::Vector3d& v) {
      return (v - p).squaredNorm() <= tolerance * tolerance;
    });
    if (!seen) distinct->push_back(p);
  }
}

void MakeCubePolyhedron(double half, Polyhedron* poly) {
  poly->points.clear();
  poly->face_start.assign(1, 0);
  poly->face_normal.clear();
  poly->face_offset.clear();
  static constexpr double kCycle[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double sign : {-1.0, 1.0}) {
      for (const auto& c : kCycle) {
        Eigen::Vector3d p;
        p[axis] = sign * half;
        p[u] = c[0] * half;
        p[v] = c[1] * sign * half;  // reverse the cycle on the negative face
        poly->points.push_back(p);
      }
      poly->face_start.push_back(static_cast<int>(poly->points.size()));
      poly->face_normal.push_back(sign * Eigen::Vector3d::Unit(axis));
      poly->face_offset.push_back(half);
    }
  }
}

// Adds the cap face that closes a cut through the plane a·x = b.
static void AddCapFace(const Eigen::Vector3d& a, double b, ClipScratch* s, Polyhedron* out) {
  if (s->cut.size() < 3) return;
  const Eigen::Matrix<double, 3, 2> basis = CalcPlaneBasis(a);
  s->cut_2d.resize(s->cut.size());
  for (size_t i = 0; i < s->cut.size(); ++i) {
    s->cut_2d[i] = basis.transpose() * (s->cut[i] - s->cut[0]);
  }
  CalcConvexHull2D(s->cut_2d, &s->hull);
  if (s->hull.size() < 3) return;
  for (int idx : s->hull) out->points.push_back(s->cut[idx]);
  out->face_start.push_back(static_cast<int>(out->points.size()));
  out->face_normal.push_back(a);
  out->face_offset.push_back(b);
}

bool ClipPolyhedron(const Eigen::Vector3d& a, double b, Polyhedron* poly, ClipScratch* s) {
  const size_t n = poly->points.size();
  s->side.resize(n);
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    s->side[i] = a.dot(poly->points[i]) - b;
    lo = std::min(lo, s->side[i]);
    hi = std::max(hi, s->side[i]);
  }
  if (hi <= 0) return true;   // redundant constraint
  if (lo > 0) return false;   // everything cut away
  Polyhedron& out = s->poly;
  out.points.clear();
  out.face_start.assign(1, 0);
  out.face_normal.clear();
  out.face_offset.clear();
  s->cut.clear();
  for (int f = 0; f < poly->num_faces(); ++f) {
    const int begin = poly->face_start[f], end = poly->face_start[f + 1];
    const size_t start = out.points.size();
    for (int i = begin; i < end; ++i) {
      const int j = (i + 1 == end) ? begin : i + 1;
      const double sp = s->side[i], sq = s->side[j];
      const Eigen::Vector3d& p = poly->points[i];
      const Eigen::Vector3d& q = poly->points[j];
      if (sp <= 0) {
        out.points.push_back(p);
        if (sp == 0) s->cut.push_back(p);
      }
      if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) {
        const Eigen::Vector3d x = sp < 0 ? CrossingPoint(p, q, sp, sq) : CrossingPoint(q, p, sq, sp);
        out.points.push_back(x);
        // The neighbouring face walks this edge the other way: record the point once.
        if (sp < 0) s->cut.push_back(x);
      }
    }
    if (out.points.size() - start >= 3) {
      out.face_start.push_back(static_cast<int>(out.points.size()));
      out.face_normal.push_back(poly->face_normal[f]);
      out.face_offset.push_back(poly->face_offset[f]);
    } else {
      out.points.resize(start);
    }
  }
  AddCapFace(a, b, s, &out);
  if (out.num_faces() == 0) return false;
  std::swap(*poly, out);
  return true;
}

bool ClipPolygon(const Eigen::Vector2d& a, double b, std::vector<Eigen::Vector2d>* polygon,
                 std::vector<Eigen::Vector2d>* scratch) {
  const size_t n = polygon->size();
  PRS_CHECK(n > 0);
  double lo = INFINITY, hi = -INFINITY;
  for (const Eigen::Vector2d& p : *polygon) {
    const double s = a.dot(p) - b;
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  if (hi <= 0) return true;
  if (lo > 0) return false;
  scratch->clear();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = (*polygon)[i];
    const Eigen::Vector2d& q = (*polygon)[(i + 1) % n];
    const double sp = a.dot(p) - b, sq = a.dot(q) - b;
    if (sp <= 0) scratch->push_back(p);
    if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) {
      scratch->push_back(sp < 0 ? CrossingPoint(p, q, sp, sq) : CrossingPoint(q, p, sq, sp));
    }
  }
  if (scratch->empty()) return false;
  std::swap(*polygon, *scratch);
  return true;
}

}  // namespace prs::geometry::internal
