// The original tool's perception (paper_perception.h): its numbers by hand on small depth
// images, and on a rendered scene of the original's object model, where the mask is the cube
// alone (an object above it hides it from the full image, not from the mask) and the estimate
// is a pinhole back-projection of the mask's middle pixel.
#include "sim/paper_perception.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/model_renderer.h"
#include "sim/perception.h"
#include "sim/test/table_cube_scenes.h"
#include "sim/world.h"

namespace prs::sim {
namespace {

constexpr float kNothing = std::numeric_limits<float>::infinity();

// An 8 x 6 image, nothing drawn but `pixels` (x, y) at `depth_m`.
render::DepthImage MakeDepth(const std::vector<std::pair<int, int>>& pixels, float depth_m) {
  render::DepthImage image{8, 6, std::vector<float>(48, kNothing)};
  for (const auto& [x, y] : pixels) image.depth_m[y * 8 + x] = depth_m;
  return image;
}

// A camera 3 m up looking straight down (MuJoCo's frame: −z down the view, +y up in the image,
// +x right), clipping planes 0.5 and 5.5 m, a 90° perspective angle: tan(45°) = 1.
MaskCamera MakeCamera() {
  MaskCamera camera;
  camera.X_WC.translation() = Eigen::Vector3d(0, 0, 3);
  camera.near_m = 0.5;
  camera.far_m = 5.5;
  camera.perspective_angle_rad = M_PI / 2;
  return camera;
}

TEST(PaperPerceptionTest, AFilledRectangleByHand) {
  // Pixels x 2..4, y 1..3 at 1.5 m: first (2, 1), last (4, 3), middle (3, 2); the depth there
  // is 1.5 m, raw (1.5 − 0.5) / 5 = 0.2; bx = 3/8, by = 2/6. In the sensor frame
  // x = 1.5 · 1 · (0.5 − 3/8) · 2 = 0.375, y = 1.5 · (0.5 − 1/3) · 2 = 0.5, z = 1.5; in the
  // camera frame (−0.375, 0.5, −1.5), in the world (−0.375, 0.5, 1.5).
  std::vector<std::pair<int, int>> pixels;
  for (int y = 1; y <= 3; ++y) {
    for (int x = 2; x <= 4; ++x) pixels.emplace_back(x, y);
  }
  const std::optional<MaskEstimate> e = EstimateFromMask(MakeDepth(pixels, 1.5f), MakeCamera());
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->first_px, Eigen::Vector2d(2, 1));
  EXPECT_EQ(e->last_px, Eigen::Vector2d(4, 3));
  EXPECT_EQ(e->middle_px, Eigen::Vector2d(3, 2));
  EXPECT_NEAR(e->depth_raw, 0.2, 1e-7);
  EXPECT_NEAR(e->depth_m, 1.5, 1e-6);
  EXPECT_NEAR((e->p_S - Eigen::Vector3d(0.375, 0.5, 1.5)).norm(), 0, 1e-6);
  EXPECT_NEAR((e->p_W - Eigen::Vector3d(-0.375, 0.5, 1.5)).norm(), 0, 1e-6);
}

TEST(PaperPerceptionTest, AMiddleOffTheMaskReadsTheFarPlane) {
  // Two pixels, (0, 0) and (7, 5): middle (3.5, 2.5), read at (3, 2), where nothing was drawn:
  // raw 1, so 5.5 m. bx = 3.5/8, by = 2.5/6: x = 5.5 · (0.5 − 0.4375) · 2 = 0.6875,
  // y = 5.5 · (0.5 − 2.5/6) · 2 = 0.91666...
  const std::optional<MaskEstimate> e =
      EstimateFromMask(MakeDepth({{0, 0}, {7, 5}}, 1.0f), MakeCamera());
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->middle_px, Eigen::Vector2d(3.5, 2.5));
  EXPECT_EQ(e->depth_raw, 1.0);
  EXPECT_NEAR(e->depth_m, 5.5, 1e-12);
  EXPECT_NEAR((e->p_S - Eigen::Vector3d(0.6875, 5.5 / 6, 5.5)).norm(), 0, 1e-12);
  EXPECT_NEAR((e->p_W - Eigen::Vector3d(-0.6875, 5.5 / 6, 3 - 5.5)).norm(), 0, 1e-12);
}

TEST(PaperPerceptionTest, DepthBeyondTheClippingPlanesIsClampedAndAnEmptyMaskIsNothing) {
  const std::optional<MaskEstimate> e = EstimateFromMask(MakeDepth({{4, 3}}, 9.0f), MakeCamera());
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->depth_raw, 1.0);
  EXPECT_FALSE(EstimateFromMask(MakeDepth({}, 1.0f), MakeCamera()).has_value());
}

// Scene 1 of seed 1 of examples/table_cube_paper_model.prs (the original's object model), its
// camera at the original's 60° and 256 x 256 pixels, with a static grey slab 10 cm above the
// cube that hides it from the full image.
TEST(PaperPerceptionTest, TheRenderedMaskIsTheCubeAloneAndTheEstimateABackProjection) {
  exporting::ExportScene scene =
      exporting::MakeExportScene(testing_scenes::SamplePaperModel(1), "test");
  const exporting::Body* cube_body = nullptr;
  for (exporting::Body& b : scene.bodies) {
    if (b.class_name == "Camera") b.fovy_deg = 60;
    if (b.class_name == "Cube") cube_body = &b;
  }
  ASSERT_NE(cube_body, nullptr);
  exporting::Body slab = *cube_body;
  slab.name = "slab";
  slab.class_name = "Slab";
  slab.size = Eigen::Vector3d(0.2, 0.2, 0.01);
  slab.p_WO = cube_body->p_WO + Eigen::Vector3d(0, 0, 0.1);
  slab.color = exporting::Rgba{0.5, 0.5, 0.5, 1};
  slab.mass_kg = 0;
  const Eigen::Vector3d p_cube = cube_body->p_WO, size = cube_body->size;
  scene.bodies.push_back(slab);
  World world = BuildWorld(std::move(scene));
  render::ModelRenderer renderer(*world.model, 256, 256);
  EXPECT_FALSE(FindLargestBlob(renderer.Render(*world.data, 0), IsBluePixel).has_value())
      << "the slab should hide the cube from the full image";
  render::DepthImage depth;
  renderer.Render(*world.data, 0, &depth, world.body("Cube_5"));
  MaskCamera camera;
  camera.X_WC.translation() = Eigen::Map<const Eigen::Vector3d>(world.data->cam_xpos);
  camera.X_WC.linear() =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(world.data->cam_xmat);
  camera.near_m = renderer.GetClippingPlanes().near_m;
  camera.far_m = renderer.GetClippingPlanes().far_m;
  camera.perspective_angle_rad = M_PI / 3;
  const std::optional<MaskEstimate> e = EstimateFromMask(depth, camera);
  ASSERT_TRUE(e.has_value());

  // The mask spans the cube's projection: the centres of its first and last rows lie inside
  // the rows the cube's eight corners reach, within two pixels of them (a corner's tip may
  // cover no pixel centre).
  const PinholeCamera pinhole{camera.X_WC, M_PI / 3, 256, 256};
  double top_row = 1e9, bottom_row = -1e9;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d offset((corner & 1 ? 0.5 : -0.5) * size.x(),
                                 (corner & 2 ? 0.5 : -0.5) * size.y(),
                                 (corner & 4 ? 0.5 : -0.5) * size.z());
    const double row = Project(pinhole, p_cube + offset).y();
    top_row = std::min(top_row, row), bottom_row = std::max(bottom_row, row);
  }
  constexpr double kRasterSlack_px = 0.05;  // OpenGL's own rounding at an edge
  EXPECT_GE(e->first_px.y() + 0.5, top_row - kRasterSlack_px);
  EXPECT_LT(e->first_px.y() + 0.5, top_row + 2);
  EXPECT_LE(e->last_px.y() + 0.5, bottom_row + kRasterSlack_px);
  EXPECT_GT(e->last_px.y() + 0.5, bottom_row - 2);
  // On a square image the original's formula is a pinhole back-projection of the middle
  // pixel's indices (not its centre) at the depth read there.
  EXPECT_EQ(e->middle_px, (e->first_px + e->last_px) / 2);
  const float read = depth.depth_m[int(e->middle_px.y()) * 256 + int(e->middle_px.x())];
  ASSERT_TRUE(std::isfinite(read));
  EXPECT_NEAR(e->depth_m, read, 1e-5);
  EXPECT_NEAR((e->p_W - BackProject(pinhole, e->middle_px, read)).norm(), 0, 1e-5);
  // ... and it lands on the cube's top face, within a centimetre of its centre.
  EXPECT_LT((e->p_W - (p_cube + Eigen::Vector3d(0, 0, size.z() / 2))).norm(), 0.01);
}

}  // namespace
}  // namespace prs::sim
