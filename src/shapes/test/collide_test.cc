// Tests of mesh collisions (FCL): overlap, the touching convention, and a ring whose bounding
// box overlaps an object that passes through its hole without touching it.
#include <gtest/gtest.h>

#include "geometry/box.h"
#include "shapes/collide.h"
#include "shapes/test/test_meshes.h"

namespace prs::shapes {
namespace {

Eigen::Isometry3d At(double x, double y, double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

constexpr double kTouching = 1e-6;

TEST(CollideTest, BoxMeshesOverlapTouchAndSeparate) {
  const auto cube = LoadMeshShape(testing::BoxObj({0, 0, 0}, {1, 1, 1}), "cube.obj", "cube.obj");
  const auto a = Collider::MakeMesh(*cube, 0.1, kTouching);  // a 0.1 m cube
  EXPECT_TRUE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0.09, 0.02, 0)));
  EXPECT_FALSE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0.1, 0, 0)));  // faces touch
  EXPECT_FALSE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0, 0, 0.1)));  // stacked
  EXPECT_TRUE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0, 0, 0.0999)));
  EXPECT_FALSE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0.3, 0, 0)));
  // Against a box collider: the same answers as the exact box test away from contact.
  const auto box = Collider::MakeBox({0.05, 0.05, 0.05}, kTouching);
  for (double x : {0.0, 0.05, 0.0999, 0.1, 0.1001, 0.2}) {
    const bool boxes = geometry::DoBoxesOverlap(
        {{0, 0, 0}, Eigen::Matrix3d::Identity(), {0.05, 0.05, 0.05}},
        {{x, 0.01, 0}, Eigen::Matrix3d::Identity(), {0.05, 0.05, 0.05}});
    EXPECT_EQ(DoCollidersOverlap(*a, At(0, 0, 0), *box, At(x, 0.01, 0)), boxes) << x;
  }
}

TEST(CollideTest, ARodThroughARingsHoleDoesNotCollide) {
  const auto ring_shape = LoadMeshShape(testing::RingObj(1.0, 0.2, 0.2), "ring.obj", "ring.obj");
  const auto ring = Collider::MakeMesh(*ring_shape, 0.1, kTouching);  // 0.1 m, hole 0.06 m
  const auto rod = Collider::MakeBox({0.02, 0.1, 0.02}, kTouching);  // along y, through the hole
  EXPECT_FALSE(DoCollidersOverlap(*ring, At(0, 0, 0), *rod, At(0, 0, 0)));
  EXPECT_FALSE(DoCollidersOverlap(*ring, At(0, 0, 0), *rod, At(0.009, 0, -0.009)));
  EXPECT_TRUE(DoCollidersOverlap(*ring, At(0, 0, 0), *rod, At(0.015, 0, 0)));  // hits a bar
  // The bounding boxes overlap in all three cases: only the mesh test tells them apart.
  EXPECT_TRUE(geometry::DoBoxesOverlap({{0, 0, 0}, Eigen::Matrix3d::Identity(), {0.05, 0.01, 0.05}},
                                       {{0, 0, 0}, Eigen::Matrix3d::Identity(), {0.02, 0.1, 0.02}}));
}

TEST(CollideTest, RotationsAreApplied) {
  const auto slab = LoadMeshShape(testing::BoxObj({0, 0, 0}, {1, 0.1, 0.1}), "slab.obj", "slab.obj");
  const auto a = Collider::MakeMesh(*slab, 1, kTouching);  // 1 m along x
  Eigen::Isometry3d turned = At(0, 0.5, 0);
  turned.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(DoCollidersOverlap(*a, At(0, 0, 0), *a, turned));  // now along y, from y = 0 to 1
  EXPECT_FALSE(DoCollidersOverlap(*a, At(0, 0, 0), *a, At(0, 0.6, 0)));
}

}  // namespace
}  // namespace prs::shapes
