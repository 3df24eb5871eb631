// Pinhole cameras: intrinsics checks, projection, frustum regions and lines of sight (see
// camera.h).
#include "camera/camera.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace prs::camera {
namespace {

using Eigen::Vector3d;
using geometry::HalfSpace;

std::string Format(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

// The frustum's six faces in the camera frame, n·x <= d: left, right, bottom, top, near, far.
std::vector<HalfSpace> CalcFrustumFaces_C(const CameraIntrinsics& k) {
  const double ty = std::tan(k.fovy_rad / 2), tx = k.aspect * ty;
  // Depth along the look axis is −z: |x| <= depth·tx, |y| <= depth·ty, near <= depth <= far.
  return {{Vector3d(-1, 0, tx), 0}, {Vector3d(1, 0, tx), 0}, {Vector3d(0, -1, ty), 0},
          {Vector3d(0, 1, ty), 0},  {Vector3d(0, 0, 1), -k.near_m}, {Vector3d(0, 0, -1), k.far_m}};
}

std::vector<HalfSpace> MoveToWorld(std::vector<HalfSpace> faces, const Eigen::Isometry3d& X_WC) {
  for (HalfSpace& h : faces) {
    const double norm = h.normal.norm();
    h.normal = X_WC.linear() * (h.normal / norm);
    h.offset = h.offset / norm + h.normal.dot(X_WC.translation());
  }
  return faces;
}

}  // namespace

void CheckIntrinsics(const CameraIntrinsics& k) {
  const double pi = std::numbers::pi;
  if (!(k.fovy_rad > 0 && k.fovy_rad < pi)) {
    throw std::invalid_argument("the vertical field of view must be between 0° and 180°, not " +
                                Format(k.fovy_rad * 180 / pi) + "°");
  }
  if (!(k.aspect > 0) || !std::isfinite(k.aspect)) {
    throw std::invalid_argument("the aspect ratio (image width / height) must be positive, not " +
                                Format(k.aspect));
  }
  if (!(k.near_m > 0) || !std::isfinite(k.near_m)) {
    throw std::invalid_argument("the near distance must be positive, not " + Format(k.near_m) + " m");
  }
  if (!(k.far_m > k.near_m) || !std::isfinite(k.far_m)) {
    throw std::invalid_argument("the far distance must be finite and beyond the near distance (" +
                                Format(k.near_m) + " m), not " + Format(k.far_m) + " m");
  }
}

double PinholeCamera::focal_px() const { return 0.5 * height / std::tan(fovy_rad / 2); }

Vector3d BackProject(const PinholeCamera& camera, const Eigen::Vector2d& pixel, double depth_m) {
  const double f = camera.focal_px();
  const Vector3d p_C((pixel.x() - camera.width / 2.0) / f * depth_m,
                     (camera.height / 2.0 - pixel.y()) / f * depth_m, -depth_m);
  return camera.X_WC * p_C;
}

Vector3d Project(const PinholeCamera& camera, const Vector3d& p_W) {
  const Vector3d p_C = camera.X_WC.inverse() * p_W;
  const double depth = -p_C.z(), f = camera.focal_px();
  return {camera.width / 2.0 + f * p_C.x() / depth, camera.height / 2.0 - f * p_C.y() / depth, depth};
}

Eigen::Isometry3d CalcCameraPose(const Vector3d& p_WO, const Eigen::Quaterniond& R_WO) {
  // A quarter turn about x takes the camera's −z (look) to the object's +y and its +y (up) to
  // the object's +z: the rotation prs export writes as the MJCF camera's quat.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = p_WO;
  X.linear() = R_WO.toRotationMatrix() *
               Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitX()).toRotationMatrix();
  return X;
}

geometry::ConvexRegion CalcViewFrustum(const Eigen::Isometry3d& X_WC, const CameraIntrinsics& k) {
  return geometry::ConvexRegion::FromHalfSpaces(MoveToWorld(CalcFrustumFaces_C(k), X_WC));
}

std::vector<geometry::ConvexRegion> CalcOutsideViewPieces(const Eigen::Isometry3d& X_WC,
                                                          const CameraIntrinsics& k) {
  const std::vector<HalfSpace> faces = MoveToWorld(CalcFrustumFaces_C(k), X_WC);
  std::vector<geometry::ConvexRegion> pieces;
  for (size_t i = 0; i < faces.size(); ++i) {
    std::vector<HalfSpace> h(faces.begin(), faces.begin() + i);
    h.push_back({-faces[i].normal, -faces[i].offset});
    pieces.push_back(geometry::ConvexRegion::FromHalfSpaces(h));
  }
  return pieces;
}

std::vector<Vector3d> CalcSightTargets(const geometry::OrientedBox& box, const Vector3d& p_eye) {
  std::vector<Vector3d> targets;
  if (geometry::IsPointInBox(box, p_eye, 0)) return targets;
  constexpr double kInset = 0.98;
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      const Vector3d n = side * box.R_WB.col(axis);
      const Vector3d p_face = box.p_center + n * box.half_extents[axis];
      if (n.dot(p_eye - p_face) <= 0) continue;  // the face looks away from the eye
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = -1; i <= 1; ++i) {
        for (int j = -1; j <= 1; ++j) {
          targets.push_back(p_face + box.R_WB.col(u) * (i * kInset * box.half_extents[u]) +
                            box.R_WB.col(v) * (j * kInset * box.half_extents[v]));
        }
      }
    }
  }
  return targets;
}

int FindOccluder(const Vector3d& p_eye, const Vector3d& p_target,
                 const std::vector<geometry::OrientedBox>& occluders) {
  for (size_t i = 0; i < occluders.size(); ++i) {
    if (geometry::DoesSegmentCrossBox(occluders[i], p_eye, p_target)) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace prs::camera
