// Tests of support surfaces: a shelf's board tops as whole rectangles, a non-convex surface
// kept as its triangles, and the tilt limit.
#include <gtest/gtest.h>

#include <cmath>

#include "shapes/mesh.h"
#include "shapes/test/test_meshes.h"

namespace prs::shapes {
namespace {

TEST(SupportTest, AShelfHasItsBoardAndSideTopsAsRectangles) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  testing::AppendBox({-0.3, -0.15, 0}, {-0.28, 0.15, 0.5}, v, t);     // left side
  testing::AppendBox({0.28, -0.15, 0}, {0.3, 0.15, 0.5}, v, t);       // right side
  testing::AppendBox({-0.28, -0.15, 0.1}, {0.28, 0.15, 0.12}, v, t);  // lower board
  testing::AppendBox({-0.28, -0.15, 0.35}, {0.28, 0.15, 0.37}, v, t); // upper board
  const auto shelf = LoadMeshShape(testing::FormatObj(v, t), "shelf.obj", "shelf.obj");
  ASSERT_EQ(shelf->supports_O.size(), 4u);
  // Largest first: the two boards (0.56 x 0.3), then the two side tops (0.02 x 0.3).
  EXPECT_NEAR(shelf->supports_O[0].area, 0.56 * 0.3, 1e-12);
  EXPECT_NEAR(shelf->supports_O[1].area, 0.56 * 0.3, 1e-12);
  EXPECT_NEAR(shelf->supports_O[2].area, 0.02 * 0.3, 1e-12);
  for (const SupportPolygon& s : shelf->supports_O) {
    EXPECT_EQ(s.vertices_O.size(), 4u);
    EXPECT_TRUE(s.normal_O.isApprox(Eigen::Vector3d::UnitZ()));
  }
  // Heights in the mesh's frame (bounding box centred: z from -0.25 to 0.25).
  std::vector<double> heights;
  for (const SupportPolygon& s : shelf->supports_O) heights.push_back(s.vertices_O[0].z());
  std::sort(heights.begin(), heights.end());
  EXPECT_NEAR(heights[0], 0.12 - 0.25, 1e-12);
  EXPECT_NEAR(heights[1], 0.37 - 0.25, 1e-12);
  EXPECT_NEAR(heights[3], 0.25, 1e-12);
}

TEST(SupportTest, ANonConvexSurfaceIsKeptAsTriangles) {
  // An L of three unit squares in the plane z = 0, facing up.
  const std::vector<Eigen::Vector3d> v{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                       {2, 1, 0}, {0, 2, 0}, {1, 2, 0}};
  const std::vector<Eigen::Vector3i> t{{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4},
                                       {3, 4, 7}, {3, 7, 6}};
  const auto pieces = CalcSupportPolygons({v, t});
  ASSERT_EQ(pieces.size(), 6u);
  double area = 0;
  for (const SupportPolygon& s : pieces) area += s.area;
  EXPECT_NEAR(area, 3, 1e-12);
  // The same two squares side by side (a rectangle) are one piece.
  const std::vector<Eigen::Vector3i> rectangle{{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  const auto one = CalcSupportPolygons({v, rectangle});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].vertices_O.size(), 6u);
  EXPECT_NEAR(one[0].area, 2, 1e-12);
}

TEST(SupportTest, FacesTiltedPastTheLimitAndDownwardFacesAreNotSupports) {
  auto tilted = [](double degrees) {
    const double s = std::tan(degrees * M_PI / 180);
    const std::vector<Eigen::Vector3d> v{{0, 0, 0}, {1, 0, s}, {0, 1, 0}};
    return CalcSupportPolygons({v, {{0, 1, 2}}}).size();
  };
  EXPECT_EQ(tilted(0), 1u);
  EXPECT_EQ(tilted(4.9), 1u);
  EXPECT_EQ(tilted(5.1), 0u);
  const std::vector<Eigen::Vector3d> v{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(CalcSupportPolygons({v, {{0, 2, 1}}}).empty());  // facing down
}

}  // namespace
}  // namespace prs::shapes
