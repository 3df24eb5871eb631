// Tests of oriented boxes: the separating-axis overlap test against independent checks on
// 100,000 random pairs, touching contacts, degenerate boxes, support and corners.
#include "geometry/box.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>

#include "geometry/region.h"
#include "geometry/rotation.h"
#include "geometry/sampling.h"
#include "geometry/test/test_util.h"

namespace prs::geometry {
namespace {

using testing::CalcDepthInBox;
using testing::RandomPointInBox;
using testing::RandomRotation;
using testing::RandomVector;

OrientedBox RandomBox(Rng& rng, const Eigen::Vector3d& p_center) {
  OrientedBox box;
  box.p_center = p_center;
  box.R_WB = RandomRotation(rng);
  box.half_extents = RandomVector(rng, 0.01, 0.5);
  if (rng.Uniform01() < 0.1) box.half_extents[rng.UniformInt(0, 2)] = 0;  // a flat box
  return box;
}

ConvexRegion BoxRegion(const OrientedBox& b) {
  const Eigen::Vector3d size = 2 * b.half_extents;
  return ConvexRegion::MakeCuboid(b.p_center, b.R_WB, size.x(), size.y(), size.z());
}

// Every point of A ∩ B is at most `penetration` deep in either box (the separating axis
// bounds the depth), checked on the corners and random points of each box, and on exact
// uniform points of A ∩ B (`both`) from the region code.
void ExpectShallowIntersection(const OrientedBox& a, const OrientedBox& b,
                               const ConvexRegion& both, double penetration, Rng& rng) {
  const double limit = std::max(penetration, 0.0) + 1e-9;
  for (const auto& [inner, outer] : {std::pair(&a, &b), std::pair(&b, &a)}) {
    for (const Eigen::Vector3d& p : CalcBoxCorners(*inner)) {
      ASSERT_LE(CalcDepthInBox(*outer, p), limit);
    }
    for (int i = 0; i < 8; ++i) ASSERT_LE(CalcDepthInBox(*outer, RandomPointInBox(*inner, rng)), limit);
  }
  if (both.IsEmpty() || both.dimension() < 3) return;
  const RegionSampler sampler(both);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d p = sampler.Sample(rng);
    ASSERT_LE(CalcDepthInBox(a, p), limit);
    ASSERT_LE(CalcDepthInBox(b, p), limit);
  }
}

TEST(BoxTest, OverlapAgreesWithIndependentChecksOn100kPairs) {
  Rng rng(2024);
  int overlapping = 0, separated = 0;
  const int pairs = testing::Scaled(100000);
  for (int i = 0; i < pairs; ++i) {
    const OrientedBox a = RandomBox(rng, RandomVector(rng, -1, 1));
    const OrientedBox b = RandomBox(rng, a.p_center + RandomVector(rng, -0.7, 0.7));
    const double gap = CalcBoxSeparation(a, b);
    const bool overlap = DoBoxesOverlap(a, b);
    ASSERT_EQ(overlap, gap <= -kContactTolerance);
    ASSERT_EQ(overlap, DoBoxesOverlap(b, a)) << "pair " << i;
    const ConvexRegion both = Intersect(BoxRegion(a), BoxRegion(b));
    if (overlap) {
      ++overlapping;
      // SAT says they interpenetrate: a common point must exist (found by clipping).
      ASSERT_FALSE(both.IsEmpty()) << "pair " << i;
      const Eigen::Vector3d p = both.CalcInteriorPoint();
      ASSERT_TRUE(IsPointInBox(a, p, 1e-9) && IsPointInBox(b, p, 1e-9)) << "pair " << i;
    } else {
      ++separated;
      ExpectShallowIntersection(a, b, both, -gap, rng);
    }
  }
  // Both outcomes must be well represented for the test to mean anything.
  EXPECT_GT(overlapping, pairs / 5);
  EXPECT_GT(separated, pairs / 5);
}

TEST(BoxTest, SeparationIsExactForAxisAlignedBoxes) {
  OrientedBox a, b;
  a.half_extents = {0.5, 0.5, 0.5};
  b.half_extents = {0.25, 0.25, 0.25};
  b.p_center = {1.0, 0.0, 0.0};
  EXPECT_NEAR(CalcBoxSeparation(a, b), 0.25, 1e-15);
  b.p_center = {0.6, 0.1, 0.0};
  EXPECT_NEAR(CalcBoxSeparation(a, b), -0.15, 1e-15);
}

TEST(BoxTest, FaceToFaceTouchingIsNotOverlap) {
  Rng rng(5);
  for (int i = 0; i < 200; ++i) {
    OrientedBox a = RandomBox(rng, RandomVector(rng, -1, 1));
    a.half_extents = RandomVector(rng, 0.05, 0.5);
    OrientedBox b = a;
    const int axis = static_cast<int>(rng.UniformInt(0, 2));
    const double shift = a.half_extents[axis] + b.half_extents[axis];
    for (double delta : {0.0, 1e-7, -1e-7}) {  // exactly touching, or within 1e-7
      b.p_center = a.p_center + a.R_WB.col(axis) * (shift + delta);
      EXPECT_FALSE(DoBoxesOverlap(a, b)) << "delta " << delta;
    }
    b.p_center = a.p_center + a.R_WB.col(axis) * (shift - 1e-4);
    EXPECT_TRUE(DoBoxesOverlap(a, b));
  }
}

TEST(BoxTest, EdgeToEdgeTouchingIsNotOverlap) {
  // A has a top edge along x, B a bottom edge along y; the edges cross and touch.
  OrientedBox a, b;
  a.half_extents = b.half_extents = {0.5, 0.5, 0.5};
  a.R_WB = CalcRotationX(std::numbers::pi / 4);
  b.R_WB = CalcRotationY(std::numbers::pi / 4);
  const double reach = 0.5 * std::sqrt(2.0);
  for (double delta : {0.0, 1e-7, -1e-7}) {
    b.p_center = {0, 0, 2 * reach + delta};
    EXPECT_FALSE(DoBoxesOverlap(a, b)) << "delta " << delta;
    EXPECT_NEAR(CalcBoxSeparation(a, b), delta, 1e-12);
  }
  b.p_center = {0, 0, 2 * reach - 1e-5};
  EXPECT_TRUE(DoBoxesOverlap(a, b));
}

TEST(BoxTest, IdenticalAndZeroSizeBoxes) {
  Rng rng(6);
  OrientedBox a = RandomBox(rng, {0.3, -0.2, 1.0});
  a.half_extents = {0.1, 0.2, 0.3};
  EXPECT_TRUE(DoBoxesOverlap(a, a));
  OrientedBox point;  // zero-size box
  point.p_center = a.p_center;
  EXPECT_TRUE(DoBoxesOverlap(a, point));   // a point 0.1 m deep inside a
  EXPECT_FALSE(DoBoxesOverlap(point, point));  // two coincident points only touch
  point.p_center = a.p_center + a.R_WB * Eigen::Vector3d(0.1, 0, 0);  // on a's face
  EXPECT_FALSE(DoBoxesOverlap(a, point));
  EXPECT_TRUE(std::isfinite(CalcBoxSeparation(point, point)));
}

TEST(BoxTest, BadArgumentsThrow) {
  OrientedBox a, b;
  a.half_extents = {1, 1, 1};
  b.half_extents = {1, -1, 1};
  EXPECT_THROW(DoBoxesOverlap(a, b), std::invalid_argument);
  EXPECT_THROW(DoBoxesOverlap(a, a, -1e-3), std::invalid_argument);
}

TEST(BoxTest, SupportMatchesCorners) {
  Rng rng(7);
  for (int i = 0; i < 500; ++i) {
    OrientedBox box = RandomBox(rng, RandomVector(rng, -1, 1));
    const Eigen::Vector3d dir = RandomVector(rng, -1, 1);
    double best = -INFINITY;
    for (const Eigen::Vector3d& c : CalcBoxCorners(box)) best = std::max(best, dir.dot(c));
    EXPECT_NEAR(CalcBoxSupport(box.R_WB, box.half_extents, dir), best - dir.dot(box.p_center),
                1e-12);
  }
}

TEST(BoxTest, PointInBox) {
  OrientedBox box;
  box.p_center = {1, 2, 3};
  box.R_WB = CalcRotationZ(std::numbers::pi / 2);
  box.half_extents = {0.5, 0.1, 0.2};
  // Local x is world y after the quarter turn.
  EXPECT_TRUE(IsPointInBox(box, {1, 2.45, 3}));
  EXPECT_FALSE(IsPointInBox(box, {1.45, 2, 3}));
  EXPECT_TRUE(IsPointInBox(box, {1, 2.5 + 5e-10, 3}));
  EXPECT_FALSE(IsPointInBox(box, {1, 2.5 + 5e-9, 3}));
}

TEST(BoxTest, SegmentCrossingMatchesDenseSamplingAlongTheSegment) {
  Rng rng(8);
  int crossing = 0, mismatches = 0;
  for (int i = 0; i < 2000; ++i) {
    const OrientedBox box = RandomBox(rng, RandomVector(rng, -0.3, 0.3));
    const Eigen::Vector3d a = RandomVector(rng, -1.5, 1.5), b = RandomVector(rng, -1.5, 1.5);
    // Dense points along the segment, inside the box shrunk by the tolerance.
    bool inside = false;
    for (int k = 0; k <= 4000 && !inside; ++k) {
      inside = IsPointInBox(box, a + (b - a) * (k / 4000.0), -kContactTolerance);
    }
    const bool crosses = DoesSegmentCrossBox(box, a, b);
    crossing += crosses;
    // Sampling can miss a corner clip shorter than the sample spacing, so only one direction
    // is exact; the counts below show the two agree almost always.
    if (inside) {
      ASSERT_TRUE(crosses) << "segment " << a.transpose() << " to " << b.transpose();
    }
    mismatches += crosses != inside;
  }
  EXPECT_LE(mismatches, 5);
  EXPECT_GT(crossing, 100);  // both answers occur often enough to be tested
  EXPECT_LT(crossing, 1900);
}

TEST(BoxTest, SegmentsThatTouchOrEndOutsideDoNotCross) {
  OrientedBox box;
  box.half_extents = {0.5, 0.5, 0.5};
  // Grazing a face, along an edge, ending at the face, and stopping short of it.
  EXPECT_FALSE(DoesSegmentCrossBox(box, {-1, 0, 0.5}, {1, 0, 0.5}));
  EXPECT_FALSE(DoesSegmentCrossBox(box, {-1, 0.5, 0.5}, {1, 0.5, 0.5}));
  EXPECT_FALSE(DoesSegmentCrossBox(box, {0, 0, 2}, {0, 0, 0.5}));
  EXPECT_FALSE(DoesSegmentCrossBox(box, {0, 0, 2}, {0, 0, 0.6}));
  EXPECT_TRUE(DoesSegmentCrossBox(box, {0, 0, 2}, {0, 0, 0.49}));
  EXPECT_TRUE(DoesSegmentCrossBox(box, {-1, 0.2, 0.3}, {1, -0.2, 0.1}));
  EXPECT_TRUE(DoesSegmentCrossBox(box, {0, 0, 0}, {0.1, 0, 0}));  // wholly inside
}

}  // namespace
}  // namespace prs::geometry
