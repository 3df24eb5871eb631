// Implementation of the rotation conventions declared in rotation.h.
#include "geometry/rotation.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace prs::geometry {

Eigen::Matrix3d CalcRotationX(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, c, -s, 0, s, c;
  return R;
}

Eigen::Matrix3d CalcRotationY(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}

Eigen::Matrix3d CalcRotationZ(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Eigen::Matrix3d CalcRotationFromYawPitchRoll(double yaw, double pitch, double roll) {
  return CalcRotationZ(yaw) * CalcRotationX(pitch) * CalcRotationY(roll);
}

Eigen::Vector3d CalcYawPitchRoll(const Eigen::Matrix3d& R_WB) {
  // Row 2 of Rz·Rx·Ry is (-cp·sr, sp, cp·cr); column 1 is (-sy·cp, cy·cp, sp).
  const double cos_pitch = std::hypot(R_WB(0, 1), R_WB(1, 1));
  const double pitch = std::atan2(R_WB(2, 1), cos_pitch);
  if (cos_pitch < 1e-12) {
    // Gimbal lock: only yaw ± roll is determined; report it all as yaw.
    return {std::atan2(R_WB(1, 0), R_WB(0, 0)), pitch, 0.0};
  }
  const double yaw = std::atan2(-R_WB(0, 1), R_WB(1, 1));
  const double roll = std::atan2(-R_WB(2, 0), R_WB(2, 2));
  return {yaw, pitch, roll};
}

Eigen::Matrix3d CalcRotationFromEulerVector(const Eigen::Vector3d& abc) {
  return CalcRotationX(abc.z()) * CalcRotationY(abc.y()) * CalcRotationZ(abc.x());
}

Eigen::Matrix3d CalcRotationFacing(const Eigen::Vector3d& direction) {
  const double norm = direction.norm();
  if (!std::isfinite(norm) || norm == 0.0) {
    std::ostringstream msg;
    msg << "CalcRotationFacing: direction must be finite and non-zero, got ("
        << direction.x() << ", " << direction.y() << ", " << direction.z() << ")";
    throw std::invalid_argument(msg.str());
  }
  const Eigen::Vector3d d = direction / norm;
  const Eigen::Vector3d y_axis = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d axis = y_axis.cross(d);
  const double sin_angle = axis.norm();
  const double cos_angle = y_axis.dot(d);
  if (sin_angle < 1e-12) {
    if (cos_angle > 0) return Eigen::Matrix3d::Identity();
    return Eigen::Vector3d(-1, -1, 1).asDiagonal();  // half-turn about z
  }
  return Eigen::AngleAxisd(std::atan2(sin_angle, cos_angle), axis / sin_angle)
      .toRotationMatrix();
}

Eigen::Matrix3d CalcRotationFacingToward(const Eigen::Vector3d& p_from,
                                         const Eigen::Vector3d& p_target) {
  if (!p_from.allFinite() || !p_target.allFinite()) {
    std::ostringstream msg;
    msg << "CalcRotationFacingToward: non-finite point, from (" << p_from.transpose()
        << ") to (" << p_target.transpose() << ")";
    throw std::invalid_argument(msg.str());
  }
  const double dx = p_target.x() - p_from.x(), dy = p_target.y() - p_from.y();
  const double horizontal = std::hypot(dx, dy);
  if (horizontal < 1e-12) return Eigen::Matrix3d::Identity();
  // Rz(yaw)·(0,1,0) = (-sin yaw, cos yaw) must equal (dx, dy)/horizontal.
  const double s = -dx / horizontal, c = dy / horizontal;
  Eigen::Matrix3d R;
  R << c, -s, 0, s, c, 0, 0, 0, 1;
  return R;
}

Eigen::Quaterniond CanonicalQuaternion(const Eigen::Matrix3d& R) {
  if (!R.allFinite()) {
    std::ostringstream msg;
    msg << "CanonicalQuaternion: non-finite rotation matrix\n" << R;
    throw std::invalid_argument(msg.str());
  }
  Eigen::Quaterniond q(R);
  q.normalize();
  Eigen::Vector4d c = q.coeffs();  // (x, y, z, w)
  bool flip = c[3] < 0;
  if (c[3] == 0) {
    for (int i = 0; i < 3; ++i) {
      if (c[i] != 0) {
        flip = c[i] < 0;
        break;
      }
    }
  }
  if (flip) c = -c;
  return Eigen::Quaterniond(c[3], c[0], c[1], c[2]);
}

}  // namespace prs::geometry
