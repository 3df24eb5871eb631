// Tests of the rotation conventions (spec §4): yaw/pitch/roll, Euler vectors, facing.
#include "geometry/rotation.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "geometry/random.h"

namespace prs::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

void ExpectRotationNear(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double tol = 1e-12) {
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), tol) << "\n" << a << "\nvs\n" << b;
}

TEST(RotationTest, YawIsAboutZAndTurnsForwardLeft) {
  // A quarter yaw turns forward (+y) to -x (counter-clockwise seen from above).
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(kPi / 2, 0, 0);
  EXPECT_LT((R * Eigen::Vector3d::UnitY() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
}

TEST(RotationTest, PitchIsAboutNewXAndRollAboutNewY) {
  // Yaw a quarter turn first: the new x axis is world +y, so pitch tilts forward (-x) up.
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(kPi / 2, kPi / 2, 0);
  EXPECT_LT((R * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  // Roll about the new y: with no yaw/pitch, roll turns +x toward -z.
  const Eigen::Matrix3d R2 = CalcRotationFromYawPitchRoll(0, 0, kPi / 2);
  EXPECT_LT((R2 * Eigen::Vector3d::UnitX() - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  ExpectRotationNear(CalcRotationFromYawPitchRoll(0.3, -0.2, 0.7),
                     CalcRotationZ(0.3) * CalcRotationX(-0.2) * CalcRotationY(0.7));
}

TEST(RotationTest, YawPitchRollRoundTrip) {
  Rng rng(11);
  for (int i = 0; i < 2000; ++i) {
    const double yaw = rng.Uniform(-kPi, kPi), pitch = rng.Uniform(-kPi / 2 + 1e-6, kPi / 2 - 1e-6);
    const double roll = rng.Uniform(-kPi, kPi);
    const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(yaw, pitch, roll);
    const Eigen::Vector3d ypr = CalcYawPitchRoll(R);
    EXPECT_NEAR(ypr.x(), yaw, 1e-8);
    EXPECT_NEAR(ypr.y(), pitch, 1e-8);
    EXPECT_NEAR(ypr.z(), roll, 1e-8);
    ExpectRotationNear(CalcRotationFromYawPitchRoll(ypr.x(), ypr.y(), ypr.z()), R, 1e-11);
  }
}

TEST(RotationTest, GimbalLockGivesZeroRollAndSameMatrix) {
  for (double pitch : {kPi / 2, -kPi / 2}) {
    const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.4, pitch, 0.9);
    const Eigen::Vector3d ypr = CalcYawPitchRoll(R);
    EXPECT_EQ(ypr.z(), 0.0);
    EXPECT_NEAR(ypr.y(), pitch, 1e-9);
    EXPECT_TRUE(std::isfinite(ypr.x()));
    ExpectRotationNear(CalcRotationFromYawPitchRoll(ypr.x(), ypr.y(), ypr.z()), R, 1e-9);
  }
}

TEST(RotationTest, EulerVectorIsRxRyRz) {
  const Eigen::Vector3d abc(0.3, -1.1, 2.0);
  ExpectRotationNear(CalcRotationFromEulerVector(abc),
                     CalcRotationX(2.0) * CalcRotationY(-1.1) * CalcRotationZ(0.3));
  // Only a: a pure rotation about z.
  ExpectRotationNear(CalcRotationFromEulerVector({0.5, 0, 0}), CalcRotationZ(0.5));
}

TEST(RotationTest, FacingTakesForwardOntoDirection) {
  Rng rng(12);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d d(rng.Normal(), rng.Normal(), rng.Normal());
    const Eigen::Matrix3d R = CalcRotationFacing(d);
    EXPECT_LT((R * Eigen::Vector3d::UnitY() - d.normalized()).norm(), 1e-12);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    // Smallest rotation: the rotation axis is orthogonal to both +y and d.
    const Eigen::AngleAxisd aa(R);
    EXPECT_NEAR(aa.angle(), std::acos(std::clamp(d.normalized().y(), -1.0, 1.0)), 1e-9);
  }
}

TEST(RotationTest, FacingSpecialCases) {
  ExpectRotationNear(CalcRotationFacing({0, 2, 0}), Eigen::Matrix3d::Identity());
  ExpectRotationNear(CalcRotationFacing({0, -3, 0}), CalcRotationZ(kPi));
  EXPECT_THROW(CalcRotationFacing({0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(CalcRotationFacing({NAN, 1, 0}), std::invalid_argument);
  EXPECT_THROW(CalcRotationFacing({INFINITY, 1, 0}), std::invalid_argument);
}

TEST(RotationTest, FacingTowardIsYawOnly) {
  const Eigen::Vector3d from(1, 1, 0.5), target(0, 2, 3);
  const Eigen::Matrix3d R = CalcRotationFacingToward(from, target);
  const Eigen::Vector3d forward = R * Eigen::Vector3d::UnitY();
  EXPECT_LT((forward - Eigen::Vector3d(-1, 1, 0).normalized()).norm(), 1e-12);
  EXPECT_LT((R * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  ExpectRotationNear(CalcRotationFacingToward(from, from + Eigen::Vector3d(0, 0, 4)),
                     Eigen::Matrix3d::Identity());
  ExpectRotationNear(CalcRotationFacingToward(from, from), Eigen::Matrix3d::Identity());
}

TEST(RotationTest, CanonicalQuaternionHasNonNegativeW) {
  Rng rng(13);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(rng.Uniform(-kPi, kPi),
                                                           rng.Uniform(-1.5, 1.5),
                                                           rng.Uniform(-kPi, kPi));
    const Eigen::Quaterniond q = CanonicalQuaternion(R);
    EXPECT_GE(q.w(), 0.0);
    EXPECT_NEAR(q.norm(), 1.0, 1e-14);
    ExpectRotationNear(q.toRotationMatrix(), R, 1e-12);
  }
  // A half-turn has w = 0: the sign is fixed by the first non-zero of x, y, z.
  const Eigen::Quaterniond half = CanonicalQuaternion(CalcRotationZ(kPi));
  EXPECT_NEAR(half.w(), 0.0, 1e-15);
  EXPECT_GT(half.z(), 0.0);
}

}  // namespace
}  // namespace prs::geometry
