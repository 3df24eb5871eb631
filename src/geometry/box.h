// Oriented boxes (an object's bounding box) and the exact separating-axis overlap test
// used for the "no collisions" scene constraint (spec §6).
#pragma once

#include <array>

#include <Eigen/Core>

namespace prs::geometry {

/// A box centred at p_center with its local axes given by the columns of R_WB and
/// half-extents along them (metres, each >= 0; zero gives a flat or degenerate box).
struct OrientedBox {
  Eigen::Vector3d p_center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();
};

/// Penetration below this (metres) is contact, not collision.
inline constexpr double kContactTolerance = 1e-6;

/// Exact separating-axis test over the 15 candidate axes (3 + 3 face normals, 9 edge
/// cross products normalized so that gaps are in metres; near-parallel edge pairs, whose
/// cross product is shorter than 1e-6, are covered by the face axes and skipped). Returns
/// true only when the boxes interpenetrate by at least `tolerance` along every axis, so
/// touching boxes do not overlap. Preconditions: R_WB orthonormal. Throws
/// std::invalid_argument for a negative tolerance or negative half-extents.
bool DoBoxesOverlap(const OrientedBox& a, const OrientedBox& b,
                    double tolerance = kContactTolerance);

/// The signed gap along the best separating axis: > 0 the boxes are apart by that much,
/// < 0 they interpenetrate by -gap along every tested axis (the minimum is returned).
/// DoBoxesOverlap(a, b, tol) == (CalcBoxSeparation(a, b) <= -tol).
double CalcBoxSeparation(const OrientedBox& a, const OrientedBox& b);

/// The 8 corners in world coordinates; corner k uses sign (-1)^(bit i of k) ... along local
/// axis i, i.e. corner k = p_center + R_WB·(s ∘ half_extents), s_i = (k >> i & 1) ? +1 : -1.
std::array<Eigen::Vector3d, 8> CalcBoxCorners(const OrientedBox& box);

/// The support of the centred box: max over the box of direction·y, which is
/// Σ_j |direction·R_WB.col(j)|·half_extents(j). Any direction (need not be unit).
double CalcBoxSupport(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& half_extents,
                      const Eigen::Vector3d& direction);

/// True when p_W lies in the box grown by `tolerance` along each local axis.
bool IsPointInBox(const OrientedBox& box, const Eigen::Vector3d& p_W, double tolerance = 1e-9);

/// True when the segment from a_W to b_W passes through the interior of the box shrunk by
/// `tolerance` (metres) on every side, so a segment that only touches or grazes the box within
/// the tolerance does not cross it. A line of sight is blocked by a box it crosses.
bool DoesSegmentCrossBox(const OrientedBox& box, const Eigen::Vector3d& a_W,
                         const Eigen::Vector3d& b_W, double tolerance = kContactTolerance);

}  // namespace prs::geometry
