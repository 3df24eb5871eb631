// Cameras, below the language (which uses them for `in view of` and `visible from`), the
// simulator and the renderer: a pinhole camera's pose and intrinsics, its view frustum as an
// exact convex region, projection to pixels and back, and lines of sight past other boxes.
// Frames follow MuJoCo and OpenGL: a camera looks along its frame's −z with +y up, +x right.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/box.h"
#include "geometry/region.h"

namespace prs::camera {

/// What a camera sees, apart from where it is. The defaults are the case study's ceiling
/// camera: a 45° vertical field of view at 640×480 pixels.
struct CameraIntrinsics {
  double fovy_rad = 0.7853981633974483;  // vertical field of view, in (0, π)
  double aspect = 4.0 / 3.0;             // image width / height, > 0
  double near_m = 0.01;                  // nearest and farthest seen depth, 0 < near < far
  double far_m = 10.0;
};

/// Throws std::invalid_argument, naming the value and its allowed range, when an intrinsic is
/// out of range or not finite.
void CheckIntrinsics(const CameraIntrinsics& intrinsics);

/// A camera that makes images: its pose, vertical field of view and image size in pixels.
/// Pixels are counted from the top-left corner, rows downwards.
struct PinholeCamera {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  double fovy_rad = 0.7853981633974483;
  int width = 640;
  int height = 480;

  /// Focal length in pixels.
  double focal_px() const;
};

/// The point at `depth_m` along the look axis that projects to `pixel` (column, row; pixel
/// centres at +0.5), in world coordinates.
Eigen::Vector3d BackProject(const PinholeCamera& camera, const Eigen::Vector2d& pixel, double depth_m);
/// Where a world point lands in the image (column, row), and its depth along the look axis.
Eigen::Vector3d Project(const PinholeCamera& camera, const Eigen::Vector3d& p_W);

/// X_WC of a camera standing for a scene object at (p_WO, R_WO): the object's forward axis
/// (+y) is the look direction and its up axis (+z) the image's up, as `prs export` writes
/// cameras into MJCF (so the simulator's camera and the language's agree).
Eigen::Isometry3d CalcCameraPose(const Eigen::Vector3d& p_WO, const Eigen::Quaterniond& R_WO);

/// The view frustum in the world frame: the points at depths near..far whose projection lies
/// inside the image. An intersection of six half-spaces, exact. Preconditions: valid
/// intrinsics (CheckIntrinsics).
geometry::ConvexRegion CalcViewFrustum(const Eigen::Isometry3d& X_WC, const CameraIntrinsics& intrinsics);

/// Everything outside the view frustum, as six convex pieces with disjoint interiors (piece i
/// lies beyond face i of the frustum and inside faces 0..i-1). Unbounded.
std::vector<geometry::ConvexRegion> CalcOutsideViewPieces(const Eigen::Isometry3d& X_WC,
                                                          const CameraIntrinsics& intrinsics);

/// The points of a box a line-of-sight test aims at from p_eye: on each face that faces the
/// eye, a 3×3 grid (the face's centre, the midpoints of its edges and its corners, all pulled
/// in by 2 % of the face's size, so that rays do not graze the edges of touching objects).
/// At most 27 points; none when the eye is inside the box.
std::vector<Eigen::Vector3d> CalcSightTargets(const geometry::OrientedBox& box, const Eigen::Vector3d& p_eye);

/// The index of the first box in `occluders` that the segment from p_eye to p_target crosses
/// (geometry::DoesSegmentCrossBox: touching does not count), or -1 when the line is clear.
int FindOccluder(const Eigen::Vector3d& p_eye, const Eigen::Vector3d& p_target,
                 const std::vector<geometry::OrientedBox>& occluders);

}  // namespace prs::camera
