// Oriented-box utilities and the separating-axis test.
#include "geometry/box.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace prs::geometry {
namespace {

// Edge pairs closer than this to parallel (|e_i × b_j|, i.e. the sine of their angle) are
// skipped: the cross product is then dominated by rounding, and the face axes already
// separate such boxes to within about this angle times the box size.
constexpr double kMinEdgeAxis = 1e-6;

void ThrowBadBox(const char* where, const OrientedBox& box) {
  std::ostringstream msg;
  msg << where << ": half_extents must be >= 0, got (" << box.half_extents.transpose() << ")";
  throw std::invalid_argument(msg.str());
}

// The separation of CalcBoxSeparation, except that it returns as soon as some axis separates
// the boxes by more than `stop` (a lower bound of the separation, which is then above `stop`):
// DoBoxesOverlap needs only to know whether the separation is above -tolerance, and most pairs
// of a scene are far apart, which A's face axes already show.
double CalcBoxSeparationUpTo(const OrientedBox& a, const OrientedBox& b, double stop) {
  // Work in A's frame: R = rotation of B in A, t = B's centre in A.
  const Eigen::Matrix3d R = a.R_WB.transpose() * b.R_WB;
  const Eigen::Vector3d t = a.R_WB.transpose() * (b.p_center - a.p_center);
  const Eigen::Matrix3d abs_R = R.cwiseAbs();
  const Eigen::Vector3d& ha = a.half_extents;
  const Eigen::Vector3d& hb = b.half_extents;

  // A's face axes.
  const Eigen::Vector3d gap_a = t.cwiseAbs() - ha - abs_R * hb;
  double best = gap_a.maxCoeff();
  if (best > stop) return best;
  // B's face axes.
  const Eigen::Vector3d gap_b = (R.transpose() * t).cwiseAbs() - abs_R.transpose() * ha - hb;
  best = std::max(best, gap_b.maxCoeff());
  if (best > stop) return best;
  // Edge-edge axes e_i × b_j (in A's frame).
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      // |L|² from L's own components (accurate even when the edges are nearly parallel).
      const double len2 = R(i1, j) * R(i1, j) + R(i2, j) * R(i2, j);
      if (len2 < kMinEdgeAxis * kMinEdgeAxis) continue;  // near-parallel: face axes decide
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      // Axis L = e_i × b_j; |L·e_k| and |L·b_m| follow from the orthonormality of R.
      const double dist = std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j));
      const double ra = ha[i1] * abs_R(i2, j) + ha[i2] * abs_R(i1, j);
      const double rb = hb[j1] * abs_R(i, j2) + hb[j2] * abs_R(i, j1);
      best = std::max(best, (dist - ra - rb) / std::sqrt(len2));
      if (best > stop) return best;
    }
  }
  return best;
}

}  // namespace

double CalcBoxSeparation(const OrientedBox& a, const OrientedBox& b) {
  if ((a.half_extents.array() < 0).any()) ThrowBadBox("CalcBoxSeparation", a);
  if ((b.half_extents.array() < 0).any()) ThrowBadBox("CalcBoxSeparation", b);
  return CalcBoxSeparationUpTo(a, b, HUGE_VAL);
}

bool DoBoxesOverlap(const OrientedBox& a, const OrientedBox& b, double tolerance) {
  if (!(tolerance >= 0)) {
    std::ostringstream msg;
    msg << "DoBoxesOverlap: tolerance must be >= 0, got " << tolerance;
    throw std::invalid_argument(msg.str());
  }
  if ((a.half_extents.array() < 0).any()) ThrowBadBox("DoBoxesOverlap", a);
  if ((b.half_extents.array() < 0).any()) ThrowBadBox("DoBoxesOverlap", b);
  return CalcBoxSeparationUpTo(a, b, -tolerance) <= -tolerance;
}

std::array<Eigen::Vector3d, 8> CalcBoxCorners(const OrientedBox& box) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d s((k & 1) ? 1.0 : -1.0, (k & 2) ? 1.0 : -1.0, (k & 4) ? 1.0 : -1.0);
    corners[k] = box.p_center + box.R_WB * s.cwiseProduct(box.half_extents);
  }
  return corners;
}

double CalcBoxSupport(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& half_extents,
                      const Eigen::Vector3d& direction) {
  return (R_WB.transpose() * direction).cwiseAbs().dot(half_extents);
}

bool IsPointInBox(const OrientedBox& box, const Eigen::Vector3d& p_W, double tolerance) {
  const Eigen::Vector3d p_B = box.R_WB.transpose() * (p_W - box.p_center);
  return (p_B.cwiseAbs().array() <= (box.half_extents.array() + tolerance)).all();
}

bool DoesSegmentCrossBox(const OrientedBox& box, const Eigen::Vector3d& a_W,
                         const Eigen::Vector3d& b_W, double tolerance) {
  // Slabs in the box's frame (Kay and Kajiya): the part of the segment inside all three slabs
  // of the box shrunk by the tolerance, as an interval of the segment's parameter t in [0, 1].
  const Eigen::Vector3d a = box.R_WB.transpose() * (a_W - box.p_center);
  const Eigen::Vector3d d = box.R_WB.transpose() * (b_W - a_W);
  double t_in = 0, t_out = 1;
  for (int i = 0; i < 3; ++i) {
    const double half = box.half_extents[i] - tolerance;
    if (half <= 0) return false;  // thinner than the tolerance: nothing to cross
    if (std::abs(d[i]) < 1e-15) {
      if (std::abs(a[i]) >= half) return false;
      continue;
    }
    double t0 = (-half - a[i]) / d[i], t1 = (half - a[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
    if (t_in >= t_out) return false;
  }
  return true;
}

}  // namespace prs::geometry
