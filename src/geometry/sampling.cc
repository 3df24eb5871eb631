// Exact simplex-decomposition sampler for convex regions, and the hit-and-run comparison.
#include "geometry/sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "geometry/check.h"
#include "geometry/polytope.h"

namespace prs::geometry {
namespace {

constexpr int kMaxBallRejections = 10000;

double CalcSimplexMeasure(int dim, const Eigen::Vector3d* v) {
  switch (dim) {
    case 1: return (v[1] - v[0]).norm();
    case 2: return 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
    default: return std::abs((v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0]))) / 6.0;
  }
}

// A uniform point of the triangle (a, b, c) by folding the unit square.
Eigen::Vector3d SampleTriangle(const Eigen::Vector3d* v, Rng& rng) {
  double s = rng.Uniform01(), t = rng.Uniform01();
  if (s + t > 1) {
    s = 1 - s;
    t = 1 - t;
  }
  return v[0] + s * (v[1] - v[0]) + t * (v[2] - v[0]);
}

// Three given numbers of [0, 1), read in order like an Rng's Uniform01.
struct FixedCoordinates {
  double values[3];
  int next = 0;
  double Uniform01() { return values[next++]; }
};

// A uniform point of a tetrahedron by folding the unit cube (Rocchini & Cignoni 2000).
template <typename Uniforms>
Eigen::Vector3d SampleTetrahedron(const Eigen::Vector3d* v, Uniforms& rng) {
  double s = rng.Uniform01(), t = rng.Uniform01(), u = rng.Uniform01();
  if (s + t > 1) {  // cut the cube into a triangular prism
    s = 1 - s;
    t = 1 - t;
  }
  if (t + u > 1) {  // cut the prism into a tetrahedron
    const double tmp = u;
    u = 1 - s - t;
    t = 1 - tmp;
  } else if (s + t + u > 1) {
    const double tmp = u;
    u = s + t + u - 1;
    s = 1 - t - tmp;
  }
  return v[0] + s * (v[1] - v[0]) + t * (v[2] - v[0]) + u * (v[3] - v[0]);
}

// Cuts the canonical body into simplices; 3D fans start at `apex`.
void AppendSimplices(const internal::RegionCanon& c, const Eigen::Vector3d& apex,
                     std::vector<Eigen::Vector3d>* out) {
  switch (c.dimension) {
    case 0:
    case 1:
      out->insert(out->end(), c.vertices.begin(), c.vertices.end());
      break;
    case 2:
      for (size_t i = 1; i + 1 < c.vertices.size(); ++i) {
        out->insert(out->end(), {c.vertices[0], c.vertices[i], c.vertices[i + 1]});
      }
      break;
    default:
      for (size_t f = 0; f + 1 < c.face_start.size(); ++f) {
        const int begin = c.face_start[f], end = c.face_start[f + 1];
        for (int i = begin + 1; i + 1 < end; ++i) {
          out->insert(out->end(), {apex, c.face_points[begin], c.face_points[i],
                                   c.face_points[i + 1]});
        }
      }
  }
}

}  // namespace

RegionSampler::RegionSampler(const ConvexRegion& region) {
  if (region.IsEmpty()) {
    throw std::domain_error("RegionSampler: cannot sample an empty region: " + region.Describe());
  }
  const internal::RegionCanon& c = region.canon();
  if (!c.bounded) {
    throw std::domain_error("RegionSampler: cannot sample an unbounded region: " +
                            region.Describe());
  }
  dimension_ = c.dimension;
  balls_ = c.balls;
  if (dimension_ == 2) hull_ = c.hull;
  measure_is_exact_ = c.measure_exact;
  measure_ = c.measure_exact ? c.measure : c.polytope_measure;
  if (dimension_ == 0) {
    simplex_vertices_ = c.vertices;
    return;
  }
  // The 3D fan starts at the vertex centroid (with balls, p_interior is not the centroid).
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();
  for (const auto& v : c.vertices) apex += v;
  apex /= static_cast<double>(c.vertices.size());
  const int per = dimension_ + 1;
  simplex_vertices_.reserve(per * 16);
  AppendSimplices(c, apex, &simplex_vertices_);
  const size_t n = simplex_vertices_.size() / per;
  PRS_CHECK(n >= 1);
  std::vector<double> weights(n);
  for (size_t i = 0; i < n; ++i) {
    weights[i] = CalcSimplexMeasure(dimension_, &simplex_vertices_[i * per]);
  }
  BuildAliasTable(weights);
}

void RegionSampler::BuildAliasTable(const std::vector<double>& weights) {
  const int n = static_cast<int>(weights.size());
  double total = 0;
  for (double w : weights) total += w;
  probability_.assign(n, 1.0);
  alias_.resize(n);
  for (int i = 0; i < n; ++i) alias_[i] = i;
  if (!(total > 0)) return;  // a degenerate body: every simplex equally likely
  std::vector<double> scaled(n);
  std::vector<int> small, large;
  small.reserve(n);
  large.reserve(n);
  for (int i = 0; i < n; ++i) {
    scaled[i] = weights[i] * n / total;
    (scaled[i] < 1.0 ? small : large).push_back(i);
  }
  while (!small.empty() && !large.empty()) {
    const int s = small.back(), l = large.back();
    small.pop_back();
    probability_[s] = scaled[s];
    alias_[s] = l;
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Leftovers are 1 up to rounding.
  for (int i : small) probability_[i] = 1.0;
  for (int i : large) probability_[i] = 1.0;
}

int RegionSampler::PickSimplex(Rng& rng) const {
  const int n = static_cast<int>(probability_.size());
  if (n == 1) return 0;
  const int i = static_cast<int>(rng.UniformInt(0, n - 1));
  return rng.Uniform01() < probability_[i] ? i : alias_[i];
}

Eigen::Vector3d RegionSampler::SamplePolytope(Rng& rng) const {
  if (dimension_ == 0) return simplex_vertices_[0];
  const Eigen::Vector3d* v = &simplex_vertices_[PickSimplex(rng) * (dimension_ + 1)];
  switch (dimension_) {
    case 1: return v[0] + rng.Uniform01() * (v[1] - v[0]);
    case 2: return SampleTriangle(v, rng);
    default: return SampleTetrahedron(v, rng);
  }
}

bool RegionSampler::IsInBalls(const Eigen::Vector3d& p) const {
  return std::all_of(balls_.begin(), balls_.end(), [&](const Ball& b) {
    return (p - b.p_center).squaredNorm() <= b.radius * b.radius;
  });
}

Eigen::Vector3d RegionSampler::Sample(Rng& rng) const {
  if (balls_.empty()) return SamplePolytope(rng);
  for (int attempt = 0; attempt < kMaxBallRejections; ++attempt) {
    const Eigen::Vector3d p = SamplePolytope(rng);
    if (IsInBalls(p)) return p;
  }
  throw std::domain_error("RegionSampler: region too thin to sample (" +
                          std::to_string(kMaxBallRejections) + " points rejected by its balls)");
}

Eigen::Vector3d RegionSampler::SampleAt(const double* u, Rng& rng) const {
  const Eigen::Vector3d p = MapPolytope(u);
  if (balls_.empty() || IsInBalls(p)) return p;
  return Sample(rng);  // u's candidate was rejected: the next ones are i.i.d. from the stream
}

Eigen::Vector3d RegionSampler::MapPolytope(const double* u) const {
  if (dimension_ == 0) return simplex_vertices_[0];
  if (dimension_ == 2) return MapPolygon(u);
  const Eigen::Vector3d* v = simplex_vertices_.data();
  if (dimension_ == 1) return v[0] + u[0] * (v[1] - v[0]);  // one segment
  const int per = dimension_ + 1;
  const int n = static_cast<int>(simplex_vertices_.size()) / per;
  // The simplex whose share of the cumulative measure holds u[0]; the rest of u[0] within
  // that share is again uniform in [0, 1) and becomes the simplex's first coordinate.
  double total = 0;
  for (int i = 0; i < n; ++i) total += CalcSimplexMeasure(dimension_, &simplex_vertices_[i * per]);
  double target = u[0] * total, residual = u[0];
  int picked = n - 1;
  for (int i = 0; i < n; ++i) {
    const double w = CalcSimplexMeasure(dimension_, &simplex_vertices_[i * per]);
    if (target < w || i == n - 1) {
      picked = i;
      residual = w > 0 ? std::clamp(target / w, 0.0, 1.0) : 0.0;
      break;
    }
    target -= w;
  }
  FixedCoordinates fixed{{residual, u[1], u[2]}};
  return SampleTetrahedron(&simplex_vertices_[picked * per], fixed);
}

Eigen::Vector3d RegionSampler::MapPolygon(const double* u) const {
  // The polygon in hull coordinates (x along basis column 0, y along column 1), rebuilt from
  // the fan: v0, v1, v2 of the first triangle, then the last vertex of each later one.
  const int n_tri = static_cast<int>(simplex_vertices_.size()) / 3;
  std::vector<Eigen::Vector2d> poly;
  poly.reserve(n_tri + 2);
  auto to_2d = [&](const Eigen::Vector3d& p) -> Eigen::Vector2d {
    const Eigen::Vector3d d = p - hull_.p_origin;
    return {hull_.basis.col(0).dot(d), hull_.basis.col(1).dot(d)};
  };
  poly.push_back(to_2d(simplex_vertices_[0]));
  poly.push_back(to_2d(simplex_vertices_[1]));
  for (int t = 0; t < n_tri; ++t) poly.push_back(to_2d(simplex_vertices_[t * 3 + 2]));
  // The chord of the polygon at x: [lo, hi] over the edges that cross x.
  auto chord = [&](double x, double* lo, double* hi) {
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& a = poly[i];
      const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
      const double x0 = std::min(a.x(), b.x()), x1 = std::max(a.x(), b.x());
      if (x < x0 || x > x1) continue;
      double y0 = a.y(), y1 = a.y();
      if (x1 > x0) {
        y0 = y1 = a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
      } else {  // an edge along the chord itself
        y0 = std::min(a.y(), b.y());
        y1 = std::max(a.y(), b.y());
      }
      *lo = std::min(*lo, y0);
      *hi = std::max(*hi, y1);
    }
    if (*lo > *hi) *lo = *hi = 0;  // x outside by rounding: an empty chord
  };
  std::vector<double> xs;
  xs.reserve(poly.size());
  for (const auto& p : poly) xs.push_back(p.x());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  // The chord length is linear between vertex abscissae, so the area left of x is piecewise
  // quadratic: find u[0]'s slab by whole-slab areas, then solve the slab's quadratic.
  std::vector<double> length(xs.size());
  for (size_t k = 0; k < xs.size(); ++k) {
    double lo = 0, hi = 0;
    chord(xs[k], &lo, &hi);
    length[k] = hi - lo;
  }
  double total = 0;
  for (size_t k = 0; k + 1 < xs.size(); ++k) {
    total += 0.5 * (length[k] + length[k + 1]) * (xs[k + 1] - xs[k]);
  }
  double remaining = u[0] * total;
  double x = xs.back();
  for (size_t k = 0; k + 1 < xs.size(); ++k) {
    const double h = xs[k + 1] - xs[k];
    const double area = 0.5 * (length[k] + length[k + 1]) * h;
    if (remaining < area || k + 2 == xs.size()) {
      // area(t) = L_k t + (L_{k+1} - L_k) t² / (2h) = remaining, in the stable root form.
      const double a = (length[k + 1] - length[k]) / (2 * h), b = length[k];
      const double r = std::clamp(remaining, 0.0, area);
      const double disc = std::max(0.0, b * b + 4 * a * r);
      const double denom = b + std::sqrt(disc);
      const double t = denom > 0 ? 2 * r / denom : 0.0;
      x = xs[k] + std::clamp(t, 0.0, h);
      break;
    }
    remaining -= area;
  }
  double lo = 0, hi = 0;
  chord(x, &lo, &hi);
  const double y = lo + u[1] * (hi - lo);
  return hull_.p_origin + hull_.basis.col(0) * x + hull_.basis.col(1) * y;
}

Eigen::Vector3d SampleUniform(const ConvexRegion& region, Rng& rng) {
  return RegionSampler(region).Sample(rng);
}

namespace {

// The chord {p + t·d} ∩ region as [*t_lo, *t_hi] (containing 0). False when unbounded.
bool CalcChord(const ConvexRegion& region, const Eigen::Vector3d& p, const Eigen::Vector3d& d,
               double* t_lo, double* t_hi) {
  double lo = -INFINITY, hi = INFINITY;
  for (const HalfSpace& h : region.half_spaces()) {
    const double nd = h.normal.dot(d);
    if (std::abs(nd) < 1e-15) continue;
    const double t = (h.offset - h.normal.dot(p)) / nd;
    if (nd > 0) hi = std::min(hi, t);
    else lo = std::max(lo, t);
  }
  for (const Ball& b : region.balls()) {
    const Eigen::Vector3d q = p - b.p_center;
    const double half_b = d.dot(q), c = q.squaredNorm() - b.radius * b.radius;
    const double root = std::sqrt(std::max(0.0, half_b * half_b - c));
    lo = std::max(lo, -half_b - root);
    hi = std::min(hi, -half_b + root);
  }
  if (!std::isfinite(lo) || !std::isfinite(hi)) return false;
  *t_lo = std::min(lo, 0.0);
  *t_hi = std::max(hi, 0.0);
  return true;
}

}  // namespace

Eigen::Vector3d SampleHitAndRun(const ConvexRegion& region, const Eigen::Vector3d& p_start,
                                int steps, Rng& rng) {
  if (steps < 0) {
    throw std::invalid_argument("SampleHitAndRun: steps must be >= 0, got " +
                                std::to_string(steps));
  }
  if (region.IsEmpty()) throw std::domain_error("SampleHitAndRun: the region is empty");
  if (!region.Contains(p_start)) {
    throw std::invalid_argument("SampleHitAndRun: the start point is not in the region: " +
                                region.Describe());
  }
  const AffineHull& hull = region.hull();
  const int k = static_cast<int>(hull.basis.cols());
  Eigen::Vector3d p = p_start;
  for (int step = 0; step < steps && k > 0; ++step) {
    // Gaussian weights on an orthonormal basis give a uniform direction in the hull.
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    while (d.squaredNorm() == 0) {
      for (int i = 0; i < k; ++i) d += rng.Normal() * Eigen::Vector3d(hull.basis.col(i));
    }
    d.normalize();
    double t_lo = 0, t_hi = 0;
    if (!CalcChord(region, p, d, &t_lo, &t_hi)) {
      throw std::domain_error("SampleHitAndRun: unbounded chord in " + region.Describe());
    }
    p += rng.Uniform(t_lo, t_hi) * d;
  }
  return p;
}

}  // namespace prs::geometry
