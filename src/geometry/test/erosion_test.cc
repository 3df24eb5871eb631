// Tests of ErodeByBox against brute force (all 8 corners inside) for 3D regions and for
// the footprint semantics of a rotated Rect3D; ErodeByPoints against ErodeByBox (a box's
// corners) and against brute force for a random point set.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/region.h"
#include "geometry/rotation.h"
#include "geometry/test/test_util.h"

namespace prs::geometry {
namespace {

using testing::RandomRotation;
using testing::RandomVector;

// Box corners at centre c, projected by P onto the region's hull directions.
std::vector<Eigen::Vector3d> Corners(const Eigen::Vector3d& c, const Eigen::Matrix3d& R,
                                     const Eigen::Vector3d& h, const Eigen::Matrix3d& P) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& k : CalcBoxCorners({Eigen::Vector3d::Zero(), R, h})) {
    out.push_back(c + P * k);
  }
  return out;
}

bool AllInside(const ConvexRegion& region, const std::vector<Eigen::Vector3d>& points,
               double tolerance) {
  for (const auto& p : points) {
    if (!region.Contains(p, tolerance)) return false;
  }
  return true;
}

struct Counts {
  int inside = 0, outside = 0;
};

// Compares erosion with brute force at random centres, skipping a 1e-7 m boundary band.
Counts CompareWithBruteForce(const ConvexRegion& region, const Eigen::Matrix3d& P,
                             const std::vector<Eigen::Vector3d>& centres, Rng& rng) {
  Counts counts;
  const Eigen::Matrix3d R = RandomRotation(rng);
  const Eigen::Vector3d h = RandomVector(rng, 0.0, 0.3);
  const ConvexRegion eroded = ErodeByBox(region, R, h);
  for (const Eigen::Vector3d& c : centres) {
    const auto corners = Corners(c, R, h, P);
    if (AllInside(region, corners, -1e-7) && region.Contains(c, -1e-7)) {
      EXPECT_TRUE(eroded.Contains(c)) << region.Describe();
      EXPECT_TRUE(region.ContainsBox({c, R, h}));
      ++counts.inside;
    } else if (!AllInside(region, corners, 1e-7) || !region.Contains(c, 1e-7)) {
      EXPECT_FALSE(eroded.Contains(c)) << region.Describe();
      EXPECT_FALSE(region.ContainsBox({c, R, h}));
      ++counts.outside;
    }
  }
  return counts;
}

std::vector<ConvexRegion> Make3DRegions(Rng& rng) {
  std::vector<ConvexRegion> regions;
  regions.push_back(ConvexRegion::MakeCuboid({0.1, 0.2, 0.3}, RandomRotation(rng), 1.2, 0.8, 0.9));
  std::vector<HalfSpace> hs;  // a random polyhedron around the origin
  for (int i = 0; i < 10; ++i) {
    hs.push_back({RandomVector(rng, -1, 1), rng.Uniform(0.4, 0.7)});
  }
  regions.push_back(ConvexRegion::MakeConvexPolyhedron(hs));
  regions.push_back(ConvexRegion::MakeSphere({0, 0, 0}, 0.8));
  regions.push_back(Intersect(ConvexRegion::MakeSphere({0, 0, 0}, 0.8),
                              ConvexRegion::MakeHalfSpace({0, 0, -0.2}, {0.2, 0.1, 1})));
  return regions;
}

TEST(ErosionTest, MatchesBruteForceIn3D) {
  Rng rng(31);
  Counts total;
  for (int trial = 0; trial < testing::Scaled(40); ++trial) {
    for (const ConvexRegion& region : Make3DRegions(rng)) {
      std::vector<Eigen::Vector3d> centres;
      for (int i = 0; i < 300; ++i) centres.push_back(RandomVector(rng, -0.8, 0.8));
      const Counts c = CompareWithBruteForce(region, Eigen::Matrix3d::Identity(), centres, rng);
      total.inside += c.inside;
      total.outside += c.outside;
    }
  }
  EXPECT_GT(total.inside, 500);
  EXPECT_GT(total.outside, 500);
}

TEST(ErosionTest, RotatedRectUsesFootprint) {
  Rng rng(32);
  Counts total;
  for (int trial = 0; trial < testing::Scaled(100); ++trial) {
    const Eigen::Matrix3d R_table = CalcRotationFromYawPitchRoll(rng.Uniform(-3, 3),
                                                                 rng.Uniform(-0.5, 0.5), 0);
    const Eigen::Vector3d p_table = RandomVector(rng, -1, 1);
    const ConvexRegion top = ConvexRegion::MakeRect3D(p_table, R_table, 1.2, 0.7);
    const Eigen::Matrix3d P = R_table.leftCols<2>() * R_table.leftCols<2>().transpose();
    std::vector<Eigen::Vector3d> centres;
    for (int i = 0; i < 200; ++i) {
      centres.push_back(p_table + R_table * Eigen::Vector3d(rng.Uniform(-0.7, 0.7),
                                                            rng.Uniform(-0.45, 0.45), 0));
    }
    const Counts c = CompareWithBruteForce(top, P, centres, rng);
    total.inside += c.inside;
    total.outside += c.outside;
  }
  EXPECT_GT(total.inside, 500);
  EXPECT_GT(total.outside, 500);
}

TEST(ErosionTest, CubeCompletelyOnStripGivesSegment) {
  const ConvexRegion strip = ConvexRegion::MakeRect3D({0, 0, 1}, Eigen::Matrix3d::Identity(), 0.1, 2.0);
  const ConvexRegion centres = ErodeByBox(strip, Eigen::Matrix3d::Identity(), {0.05, 0.05, 0.05});
  ASSERT_FALSE(centres.IsEmpty());
  EXPECT_EQ(centres.dimension(), 1);
  EXPECT_NEAR(centres.CalcMeasure(), 1.9, 1e-9);
  // Turned 45°, the cube no longer fits.
  EXPECT_TRUE(ErodeByBox(strip, CalcRotationZ(std::numbers::pi / 4), {0.05, 0.05, 0.05}).IsEmpty());
}

TEST(ErosionTest, ExactOrientationDependence) {
  // A 0.2 × 0.1 footprint on a 0.3 × 0.3 table: the centre range is exact for each yaw.
  const ConvexRegion top = ConvexRegion::MakeRect3D({0, 0, 0}, Eigen::Matrix3d::Identity(), 0.3, 0.3);
  for (double yaw : {0.0, 0.3, std::numbers::pi / 2}) {
    const ConvexRegion c = ErodeByBox(top, CalcRotationZ(yaw), {0.1, 0.05, 0.2});
    const double wx = 0.3 - 2 * (0.1 * std::abs(std::cos(yaw)) + 0.05 * std::abs(std::sin(yaw)));
    const double wy = 0.3 - 2 * (0.1 * std::abs(std::sin(yaw)) + 0.05 * std::abs(std::cos(yaw)));
    EXPECT_NEAR(c.CalcMeasure(), wx * wy, 1e-9) << yaw;
  }
}

TEST(ErosionTest, DegenerateErosions) {
  const ConvexRegion cube = ConvexRegion::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  EXPECT_NEAR(ErodeByBox(cube, Eigen::Matrix3d::Identity(), {0, 0, 0}).CalcMeasure(), 1.0, 1e-9);
  EXPECT_TRUE(ErodeByBox(cube, Eigen::Matrix3d::Identity(), {0.6, 0.1, 0.1}).IsEmpty());
  const ConvexRegion exact = ErodeByBox(cube, Eigen::Matrix3d::Identity(), {0.5, 0.5, 0.5});
  EXPECT_EQ(exact.dimension(), 0);  // only the centre fits
  EXPECT_TRUE(ErodeByBox(ConvexRegion::Empty(), Eigen::Matrix3d::Identity(), {1, 1, 1}).IsEmpty());
  EXPECT_FALSE(ErodeByBox(ConvexRegion::All(), Eigen::Matrix3d::Identity(), {1, 1, 1}).IsBounded());
  EXPECT_THROW(ErodeByBox(cube, Eigen::Matrix3d::Identity(), {-1, 0, 0}), std::invalid_argument);
  const ConvexRegion ball = ErodeByBox(ConvexRegion::MakeSphere({0, 0, 0}, 1), Eigen::Matrix3d::Identity(),
                                       {0.5, 0.5, 0.5});
  EXPECT_TRUE(ball.Contains({0, 0, 0}));
  EXPECT_FALSE(ball.Contains({0.3, 0, 0}));  // corner (0.8, .5, .5) is outside the ball
}

// ErodeByRound: exact for polytopes (a disk or ball inside the region at every accepted
// centre, and poking out at every refused one), and a superset of the box erosion for every
// turn about the disk's axis, which is what sampling with an open yaw relies on.
TEST(ErosionTest, RoundErosionIsExactForPolytopesAndHoldsEveryTurn) {
  Rng rng(42);
  const ConvexRegion top = ConvexRegion::MakeRect3D({0.1, -0.2, 0.8}, CalcRotationZ(0.4), 0.6, 0.4);
  const ConvexRegion solid =
      ConvexRegion::MakeCuboid({0, 0, 0}, RandomRotation(rng), 0.5, 0.4, 0.3);
  const double r = 0.07;
  const ConvexRegion disk_centres = ErodeByRound(top, Eigen::Vector3d::UnitZ(), r);
  const ConvexRegion ball_centres = ErodeByRound(solid, Eigen::Vector3d::Zero(), r);
  EXPECT_NEAR(disk_centres.CalcMeasure(), (0.6 - 2 * r) * (0.4 - 2 * r), 1e-9);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d c = RandomVector(rng, -0.4, 0.4);
    // Ball: its farthest point past each face of the solid, outside a 1 mm boundary band.
    bool ball_inside = true, ball_outside = false;
    for (const HalfSpace& h : solid.half_spaces()) {
      const double past = h.normal.dot(c + h.normal * r) - h.offset;
      ball_inside = ball_inside && past < -1e-3;
      ball_outside = ball_outside || past > 1e-3;
    }
    if (ball_inside) {
      EXPECT_TRUE(ball_centres.Contains(c));
    }
    if (ball_outside) {
      EXPECT_FALSE(ball_centres.Contains(c));
    }
    // Disk on the tabletop: the centre moved into the plane; a box of any yaw whose largest
    // horizontal inscribed disk has radius r fits only where the disk does.
    const Eigen::Vector3d p(c.x() + 0.1, c.y() - 0.2, 0.8);
    const double yaw = rng.Uniform(0, 2 * std::numbers::pi);
    const Eigen::Vector3d half(r, r + 0.03, 0.05);  // inscribed horizontal disk: radius r
    if (ErodeByBox(top, CalcRotationZ(yaw), half).Contains(p)) {
      EXPECT_TRUE(disk_centres.Contains(p)) << yaw;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_THROW(ErodeByRound(top, Eigen::Vector3d::UnitZ(), -1), std::invalid_argument);
  // Balls in the region are kept as they are: a superset that holds every valid centre.
  const ConvexRegion sphere = ConvexRegion::MakeSphere({0, 0, 0}, 1);
  EXPECT_TRUE(ErodeByRound(sphere, Eigen::Vector3d::Zero(), 0.5).Contains({0.9, 0, 0}));
}

// A box's eight corners erode exactly as the box does; a random point cloud's erosion holds a
// centre iff every point placed there is inside (balls included, one per point).
TEST(ErosionTest, ErodeByPointsMatchesCornersAndBruteForce) {
  Rng rng(47);
  int inside = 0, outside = 0;
  for (const ConvexRegion& region : Make3DRegions(rng)) {
    const Eigen::Matrix3d R = RandomRotation(rng);
    const Eigen::Vector3d h = RandomVector(rng, 0.01, 0.2);
    const auto box_corners = CalcBoxCorners({Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), h});
    const std::vector<Eigen::Vector3d> corners(box_corners.begin(), box_corners.end());
    const ConvexRegion by_box = ErodeByBox(region, R, h);
    const ConvexRegion by_corners = ErodeByPoints(region, R, corners);
    std::vector<Eigen::Vector3d> cloud;
    for (int i = 0; i < 30; ++i) cloud.push_back(RandomVector(rng, -0.15, 0.15));
    const ConvexRegion by_cloud = ErodeByPoints(region, R, cloud);
    for (int i = 0; i < 3000; ++i) {
      const Eigen::Vector3d c = RandomVector(rng, -1, 1);
      if (by_box.Contains(c, -1e-7)) {
        EXPECT_TRUE(by_corners.Contains(c));
      }
      if (!by_box.Contains(c, 1e-7)) {
        EXPECT_FALSE(by_corners.Contains(c));
      }
      bool all_in = true, one_out = false;
      for (const Eigen::Vector3d& p : cloud) {
        all_in = all_in && region.Contains(c + R * p, -1e-7);
        one_out = one_out || !region.Contains(c + R * p, 1e-7);
      }
      if (all_in) {
        EXPECT_TRUE(by_cloud.Contains(c));
        ++inside;
      }
      if (one_out) {
        EXPECT_FALSE(by_cloud.Contains(c));
        ++outside;
      }
    }
  }
  EXPECT_GT(inside, 300);
  EXPECT_GT(outside, 300);
  // On a rectangle (a plane region), only the footprint counts: a tall thin cloud standing on
  // the tabletop fits where its horizontal extent does.
  const ConvexRegion top = ConvexRegion::MakeRect3D({0, 0, 0.8}, Eigen::Matrix3d::Identity(), 1.0, 0.5);
  const ConvexRegion centres = ErodeByPoints(top, Eigen::Matrix3d::Identity(),
                                             {{-0.1, 0, -0.5}, {0.1, 0, 0.5}, {0, 0.05, 0}});
  EXPECT_TRUE(centres.Contains({0.39, 0.2, 0.8}));
  EXPECT_FALSE(centres.Contains({0.41, 0.2, 0.8}));
  EXPECT_FALSE(centres.Contains({0, 0.21, 0.8}));
  EXPECT_THROW(ErodeByPoints(top, Eigen::Matrix3d::Identity(), {}), std::invalid_argument);
}

}  // namespace
}  // namespace prs::geometry
