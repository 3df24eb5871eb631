// Tests of the camera model: the frustum region agrees with projection into the image, its
// outside pieces partition the rest of space, the object-to-camera pose matches how MJCF
// cameras are written, sight targets sit on the faces facing the eye, and occluders are found.
#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "camera/camera.h"
#include "geometry/random.h"
#include "geometry/rotation.h"

namespace prs::camera {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d RandomPose(geometry::Rng& rng) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = geometry::CalcRotationFromYawPitchRoll(rng.Uniform(-kPi, kPi), rng.Uniform(-1.5, 1.5),
                                                      rng.Uniform(-kPi, kPi));
  X.translation() = Vector3d(rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1));
  return X;
}

TEST(CameraTest, ProjectionAndBackProjectionAreInverse) {
  geometry::Rng rng(1, 0);
  PinholeCamera camera;
  camera.X_WC = RandomPose(rng);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector2d pixel(rng.Uniform(0, 640), rng.Uniform(0, 480));
    const double depth = rng.Uniform(0.1, 5);
    const Vector3d p = Project(camera, BackProject(camera, pixel, depth));
    EXPECT_NEAR(p.x(), pixel.x(), 1e-9);
    EXPECT_NEAR(p.y(), pixel.y(), 1e-9);
    EXPECT_NEAR(p.z(), depth, 1e-9);
  }
}

TEST(CameraTest, FrustumHoldsExactlyThePointsThatProjectIntoTheImage) {
  geometry::Rng rng(2, 0);
  for (int trial = 0; trial < 20; ++trial) {
    CameraIntrinsics k;
    k.fovy_rad = rng.Uniform(0.3, 2.5);
    k.aspect = rng.Uniform(0.5, 2.0);
    k.near_m = rng.Uniform(0.01, 0.3);
    k.far_m = k.near_m + rng.Uniform(0.5, 3);
    PinholeCamera camera;
    camera.X_WC = RandomPose(rng);
    camera.fovy_rad = k.fovy_rad;
    camera.height = 1000;
    camera.width = static_cast<int>(1000 * k.aspect);
    k.aspect = camera.width / 1000.0;
    const geometry::ConvexRegion frustum = CalcViewFrustum(camera.X_WC, k);
    const std::vector<geometry::ConvexRegion> outside = CalcOutsideViewPieces(camera.X_WC, k);
    int in_view = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vector3d p_W = camera.X_WC * Vector3d(rng.Uniform(-4, 4), rng.Uniform(-4, 4), rng.Uniform(-4, 0.5));
      const Vector3d pixel = Project(camera, p_W);
      const bool seen = pixel.z() >= k.near_m && pixel.z() <= k.far_m && pixel.x() >= 0 &&
                        pixel.x() <= camera.width && pixel.y() >= 0 && pixel.y() <= camera.height;
      // Points within a hair of the boundary may go either way.
      if (frustum.Contains(p_W, 1e-9) != frustum.Contains(p_W, -1e-9)) continue;
      ASSERT_EQ(frustum.Contains(p_W, 0), seen) << "trial " << trial << " pixel " << pixel.transpose();
      in_view += seen;
      int pieces = 0;
      for (const geometry::ConvexRegion& piece : outside) pieces += piece.Contains(p_W, -1e-9);
      ASSERT_EQ(pieces, seen ? 0 : 1) << "outside pieces must cover the rest of space once";
    }
    EXPECT_GT(in_view, 0);
  }
}

TEST(CameraTest, RejectsImpossibleIntrinsics) {
  CameraIntrinsics k;
  EXPECT_NO_THROW(CheckIntrinsics(k));
  for (double fov : {0.0, -0.1, kPi, 4.0, std::numeric_limits<double>::quiet_NaN()}) {
    CameraIntrinsics bad = k;
    bad.fovy_rad = fov;
    EXPECT_THROW(CheckIntrinsics(bad), std::invalid_argument) << fov;
  }
  CameraIntrinsics bad = k;
  bad.aspect = 0;
  EXPECT_THROW(CheckIntrinsics(bad), std::invalid_argument);
  bad = k;
  bad.near_m = 0;
  EXPECT_THROW(CheckIntrinsics(bad), std::invalid_argument);
  bad = k;
  bad.far_m = k.near_m;
  try {
    CheckIntrinsics(bad);
    FAIL() << "far == near must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("far distance"), std::string::npos) << e.what();
  }
}

TEST(CameraTest, ObjectCameraLooksAlongItsForwardAxisWithItsUpAxisUp) {
  // The case study's camera: 2 m above the table, `facing V3D(0, 0, -1)`.
  const Eigen::Quaterniond R_WO(geometry::CalcRotationFacing(Vector3d(0, 0, -1)));
  PinholeCamera camera;
  camera.X_WC = CalcCameraPose(Vector3d(0, 0, 2), R_WO);
  const Vector3d centre = Project(camera, Vector3d(0, 0, 0.8));
  EXPECT_NEAR(centre.x(), 320, 1e-9);
  EXPECT_NEAR(centre.y(), 240, 1e-9);
  EXPECT_NEAR(centre.z(), 1.2, 1e-12);
  // The object's up axis is the image's up: a point that way is above the centre (smaller row).
  const Vector3d up_W = R_WO * Vector3d::UnitZ();
  EXPECT_LT(Project(camera, Vector3d(0, 0, 0.8) + 0.1 * up_W).y(), 240);
  // and its right axis (+x) is the image's right.
  const Vector3d right_W = R_WO * Vector3d::UnitX();
  EXPECT_GT(Project(camera, Vector3d(0, 0, 0.8) + 0.1 * right_W).x(), 320);
}

TEST(CameraTest, SightTargetsLieOnTheFacesThatFaceTheEye) {
  geometry::OrientedBox box;
  box.p_center = Vector3d(0.2, 0.1, 0.8);
  box.half_extents = Vector3d(0.025, 0.05, 0.025);
  const std::vector<Vector3d> above = CalcSightTargets(box, Vector3d(0.2, 0.1, 2));
  ASSERT_EQ(above.size(), 9u);
  for (const Vector3d& p : above) EXPECT_NEAR(p.z(), 0.825, 1e-12);
  EXPECT_EQ(CalcSightTargets(box, Vector3d(1, 1, 2)).size(), 27u);
  EXPECT_EQ(CalcSightTargets(box, Vector3d(0.2, 2, 0.8)).size(), 9u);
  EXPECT_TRUE(CalcSightTargets(box, box.p_center).empty());
  for (const Vector3d& p : CalcSightTargets(box, Vector3d(1, 1, 2))) {
    EXPECT_TRUE(geometry::IsPointInBox(box, p, 1e-12));
    EXPECT_FALSE(geometry::IsPointInBox(box, p, -1e-6)) << "on the surface, not inside";
  }
}

TEST(CameraTest, OccludersBetweenEyeAndTargetAreFound) {
  const Vector3d eye(0, 0, 2), target(0, 0, 0.85);
  geometry::OrientedBox between, beside, below;
  between.p_center = Vector3d(0.02, 0, 1.4);
  between.half_extents = Vector3d(0.05, 0.05, 0.05);
  beside.p_center = Vector3d(0.3, 0, 1.4);
  beside.half_extents = Vector3d(0.05, 0.05, 0.05);
  below.p_center = Vector3d(0, 0, 0.8);  // the support under the target: touching is not blocking
  below.half_extents = Vector3d(0.5, 0.5, 0.05);
  EXPECT_EQ(FindOccluder(eye, target, {beside, below}), -1);
  EXPECT_EQ(FindOccluder(eye, target, {beside, between, below}), 1);
}

}  // namespace
}  // namespace prs::camera
