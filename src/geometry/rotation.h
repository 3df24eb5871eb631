// Rotation conventions of the language (spec §4): yaw/pitch/roll, the Euler-vector
// compatibility rule, "facing" rotations, and a canonical quaternion for storage.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace prs::geometry {

/// R_WB = Rz(yaw)·Rx(pitch)·Ry(roll): intrinsic yaw about z, then pitch about the new x,
/// then roll about the new y. Angles in radians; any finite values.
Eigen::Matrix3d CalcRotationFromYawPitchRoll(double yaw, double pitch, double roll);

/// The inverse of CalcRotationFromYawPitchRoll: returns (yaw, pitch, roll) with yaw and roll
/// in (-pi, pi] and pitch in [-pi/2, pi/2]. At gimbal lock (|pitch| = pi/2, within 1e-12)
/// roll is 0 and yaw absorbs the remaining turn. Precondition: R_WB orthonormal.
Eigen::Vector3d CalcYawPitchRoll(const Eigen::Matrix3d& R_WB);

/// The compatibility reading of a vector (a, b, c) as an orientation:
/// R = Rx(c)·Ry(b)·Rz(a) (about world z by a, then world y by b, then world x by c).
Eigen::Matrix3d CalcRotationFromEulerVector(const Eigen::Vector3d& abc);

/// The smallest rotation taking +y onto `direction` (any positive length). When direction is
/// antiparallel to +y the answer is the half-turn about z. Throws std::invalid_argument when
/// direction is zero or not finite.
Eigen::Matrix3d CalcRotationFacing(const Eigen::Vector3d& direction);

/// A yaw-only rotation (about z) whose +y points horizontally from p_from at p_target. When
/// the target is directly above or below (horizontal distance < 1e-12 m) returns identity.
/// Throws std::invalid_argument when a coordinate is not finite.
Eigen::Matrix3d CalcRotationFacingToward(const Eigen::Vector3d& p_from,
                                         const Eigen::Vector3d& p_target);

/// The unit quaternion of R with w >= 0 (when w == 0 the first non-zero of x, y, z is made
/// positive), so equal rotations always give equal coefficients. Precondition: R orthonormal.
/// Throws std::invalid_argument when R has a non-finite entry.
Eigen::Quaterniond CanonicalQuaternion(const Eigen::Matrix3d& R);

/// Elementary rotations about the world axes (radians).
Eigen::Matrix3d CalcRotationX(double angle);
Eigen::Matrix3d CalcRotationY(double angle);
Eigen::Matrix3d CalcRotationZ(double angle);

}  // namespace prs::geometry
