// Perception's pure functions on synthetic pictures: projection and back-projection are
// inverse, blobs are found whole and their border contact reported, other colours ignored.
#include <gtest/gtest.h>

#include "geometry/random.h"
#include "sim/perception.h"

namespace prs::sim {
namespace {

PinholeCamera TiltedCamera() {
  PinholeCamera camera;
  camera.X_WC.translation() = Eigen::Vector3d(0.1, -0.2, 2.0);
  camera.X_WC.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  camera.fovy_rad = 0.8;
  return camera;
}

TEST(PerceptionTest, BackProjectInvertsProject) {
  const PinholeCamera camera = TiltedCamera();
  geometry::Rng rng(1, 0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p_W(rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5), rng.Uniform(0, 1));
    const Eigen::Vector3d pixel_depth = Project(camera, p_W);
    EXPECT_LT((BackProject(camera, pixel_depth.head<2>(), pixel_depth.z()) - p_W).norm(), 1e-9);
  }
  // The image centre looks straight along the camera's -z.
  const Eigen::Vector3d p = BackProject(camera, {320, 240}, 1.0);
  EXPECT_LT((p - camera.X_WC * Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
}

render::Image GreyImage(int w, int h) { return {w, h, std::vector<uint8_t>(size_t(w) * h * 3, 128)}; }

void Paint(render::Image& image, int x0, int y0, int x1, int y1, uint8_t r, uint8_t g, uint8_t b) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      uint8_t* p = &image.rgb[3 * (size_t(y) * image.width + x)];
      p[0] = r, p[1] = g, p[2] = b;
    }
  }
}

TEST(PerceptionTest, FindsTheLargestBlueBlobAndItsCentre) {
  render::Image image = GreyImage(64, 48);
  Paint(image, 10, 10, 20, 16, 20, 30, 200);  // 60 pixels of blue
  Paint(image, 40, 30, 43, 33, 10, 10, 90);   // 9 pixels of dark (shaded) blue
  Paint(image, 30, 5, 40, 15, 200, 40, 40);   // red: ignored
  const std::optional<ColorBlob> blob = FindLargestBlob(image, IsBluePixel);
  ASSERT_TRUE(blob.has_value());
  EXPECT_EQ(blob->pixel_count, 60);
  EXPECT_NEAR(blob->centroid_px.x(), 15.0, 1e-12);
  EXPECT_NEAR(blob->centroid_px.y(), 13.0, 1e-12);
  EXPECT_FALSE(blob->touches_border);
}

TEST(PerceptionTest, ReportsABlobAtTheBorderAndNothingWithoutBlue) {
  render::Image image = GreyImage(64, 48);
  EXPECT_FALSE(FindLargestBlob(image, IsBluePixel).has_value());
  Paint(image, 0, 20, 6, 30, 30, 40, 220);
  const std::optional<ColorBlob> blob = FindLargestBlob(image, IsBluePixel);
  ASSERT_TRUE(blob.has_value());
  EXPECT_TRUE(blob->touches_border);
}

}  // namespace
}  // namespace prs::sim
