// Tests of the box-overlap zonotope and the convex difference against brute force: random
// centres are classified by DoBoxesOverlap and by membership in the computed regions.
#include <vector>

#include <gtest/gtest.h>

#include "geometry/difference.h"
#include "geometry/test/test_util.h"

namespace prs::geometry {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using testing::RandomRotation;
using testing::RandomVector;

// Points whose overlap is closer than this to the 1e-6 m contact tolerance are skipped:
// either answer is right there.
bool NearContact(const OrientedBox& a, const OrientedBox& b) {
  const double depth = -CalcBoxSeparation(a, b);
  return std::abs(depth - 1e-6) < 1e-7;
}

TEST(BoxOverlapRegionTest, MatchesSeparatingAxisTestForRandomBoxes) {
  Rng rng(3, 0);
  for (int trial = 0; trial < 200; ++trial) {
    const OrientedBox obstacle{RandomVector(rng, -1, 1), RandomRotation(rng),
                               RandomVector(rng, 0.05, 0.5)};
    const Matrix3d R_WM = trial % 3 == 0 ? obstacle.R_WB : RandomRotation(rng);
    const Vector3d half = RandomVector(rng, 0.05, 0.5);
    const ConvexRegion overlap = CalcBoxOverlapRegion(obstacle, R_WM, half);
    for (int i = 0; i < 200; ++i) {
      const Vector3d p = obstacle.p_center + RandomVector(rng, -1.2, 1.2);
      const OrientedBox moving{p, R_WM, half};
      if (NearContact(obstacle, moving)) continue;
      ASSERT_EQ(DoBoxesOverlap(obstacle, moving), overlap.Contains(p, 0))
          << "trial " << trial << " point " << p.transpose();
    }
  }
}

TEST(BoxOverlapRegionTest, FlatMovingBoxStillGivesABoundedRegion) {
  const OrientedBox obstacle{Vector3d::Zero(), Matrix3d::Identity(), Vector3d(0.1, 0.2, 0.3)};
  const ConvexRegion overlap =
      CalcBoxOverlapRegion(obstacle, Matrix3d::Identity(), Vector3d(0.5, 0.5, 0));
  EXPECT_TRUE(overlap.IsBounded());
  EXPECT_TRUE(overlap.Contains(Vector3d(0.55, 0, 0), 0));
  EXPECT_FALSE(overlap.Contains(Vector3d(0.65, 0, 0), 0));
  EXPECT_FALSE(overlap.Contains(Vector3d(0, 0, 0.31), 0));
}

TEST(RegionDifferenceTest, PiecesAreDisjointAndCoverTheDifference) {
  Rng rng(4, 0);
  const ConvexRegion table_top =
      ConvexRegion::MakeRect3D(Vector3d(0, 0, 0.8), Matrix3d::Identity(), 1.8, 0.8);
  const OrientedBox robot{Vector3d(-0.4, -0.4, 0.85), Matrix3d::Identity(), Vector3d(0.1, 0.1, 0.05)};
  const ConvexRegion forbidden =
      CalcBoxOverlapRegion(robot, Eigen::AngleAxisd(0.7, Vector3d::UnitZ()).toRotationMatrix(),
                           Vector3d(0.12, 0.225, 0.015));
  const std::vector<ConvexRegion> pieces = CalcRegionDifference(table_top, forbidden);
  ASSERT_GE(pieces.size(), 2u);
  double area = 0;
  for (const ConvexRegion& piece : pieces) area += piece.CalcMeasure();
  EXPECT_LT(area, table_top.CalcMeasure());
  for (int i = 0; i < 20000; ++i) {
    const Vector3d p(rng.Uniform(-0.9, 0.9), rng.Uniform(-0.4, 0.4), 0.8);
    int containing = 0;
    for (const ConvexRegion& piece : pieces) containing += piece.Contains(p, 1e-12);
    const bool in_forbidden = forbidden.Contains(p, 1e-9);
    if (forbidden.Contains(p, -1e-9) != in_forbidden) continue;  // on the boundary
    EXPECT_EQ(containing, in_forbidden ? 0 : 1) << p.transpose();
  }
}

TEST(RegionDifferenceTest, DisjointObstacleLeavesTheRegionWhole) {
  const ConvexRegion a = ConvexRegion::MakeCuboid(Vector3d::Zero(), Matrix3d::Identity(), 1, 1, 1);
  const ConvexRegion b = ConvexRegion::MakeCuboid(Vector3d(2, 0, 0), Matrix3d::Identity(), 1, 1, 1);
  const std::vector<ConvexRegion> pieces = CalcRegionDifference(a, b);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(pieces[0].CalcMeasure(), 1.0);
}

TEST(RegionDifferenceTest, CoveringObstacleLeavesNothing) {
  const ConvexRegion a = ConvexRegion::MakeCuboid(Vector3d::Zero(), Matrix3d::Identity(), 1, 1, 1);
  const ConvexRegion b = ConvexRegion::MakeCuboid(Vector3d::Zero(), Matrix3d::Identity(), 2, 2, 2);
  EXPECT_TRUE(CalcRegionDifference(a, b).empty());
}

}  // namespace
}  // namespace prs::geometry
