// Tests of ConvexRegion: measures of known shapes, canonical form, and every degenerate
// case (parallel planes, slivers, crossings, empty, unbounded, zero sizes, bad input).
#include "geometry/region.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

#include "geometry/rotation.h"

namespace prs::geometry {
namespace {

constexpr double kPi = std::numbers::pi;
using Region = ConvexRegion;

TEST(RegionMeasureTest, RotatedRectangle) {
  const Region rect = Region::MakeRect3D({1, 2, 0.8}, CalcRotationFromYawPitchRoll(0.4, 0.3, -0.2),
                                         0.24, 0.45);
  EXPECT_EQ(rect.dimension(), 2);
  EXPECT_NEAR(rect.CalcMeasure(), 0.24 * 0.45, 1e-9);
  EXPECT_EQ(rect.CalcVertices().size(), 4u);
  EXPECT_TRUE(rect.IsBounded());
}

TEST(RegionMeasureTest, Triangle) {
  const Region tri = Region::MakeConvexPolygon3D({{0, 0, 1}, {2, 0, 1}, {0.5, 1.5, 1}});
  EXPECT_EQ(tri.dimension(), 2);
  EXPECT_NEAR(tri.CalcMeasure(), 0.5 * 2 * 1.5, 1e-9);
  EXPECT_NEAR(tri.CalcPlaneNormal().z(), 1.0, 1e-15);
}

TEST(RegionMeasureTest, RotatedCuboid) {
  const Region box = Region::MakeCuboid({0.1, -0.3, 2}, CalcRotationFromEulerVector({0.3, 0.7, -1.2}),
                                        0.3, 0.5, 0.7);
  EXPECT_EQ(box.dimension(), 3);
  EXPECT_NEAR(box.CalcMeasure(), 0.3 * 0.5 * 0.7, 1e-9);
  EXPECT_EQ(box.CalcVertices().size(), 8u);
  EXPECT_TRUE(box.Contains(box.CalcInteriorPoint(), -0.1));
}

TEST(RegionMeasureTest, RegularPolygon) {
  for (int n : {3, 5, 8, 12, 31}) {
    std::vector<Eigen::Vector3d> pts;
    const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.2, 1.0, 0.5);
    for (int i = 0; i < n; ++i) {
      const double t = 2 * kPi * i / n;
      pts.push_back(Eigen::Vector3d(1, 1, 1) + R * Eigen::Vector3d(0.7 * std::cos(t), 0.7 * std::sin(t), 0));
    }
    const Region poly = Region::MakeConvexPolygon3D(pts);
    EXPECT_NEAR(poly.CalcMeasure(), 0.5 * n * 0.49 * std::sin(2 * kPi / n), 1e-9) << n;
    EXPECT_EQ(poly.CalcVertices().size(), static_cast<size_t>(n));
  }
}

TEST(RegionMeasureTest, TetrahedronFromHalfSpaces) {
  const Eigen::Vector3d v[4] = {{0, 0, 0}, {1, 0.2, 0}, {0.3, 0.9, 0.1}, {0.8, 0.5, 0.7}};
  std::vector<HalfSpace> hs;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d &a = v[(i + 1) % 4], &b = v[(i + 2) % 4], &c = v[(i + 3) % 4];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.dot(v[i] - a) > 0) n = -n;  // outward, away from the opposite vertex
    hs.push_back({n, n.dot(a)});
  }
  const Region tet = Region::MakeConvexPolyhedron(hs);
  const double volume = std::abs((v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0]))) / 6;
  EXPECT_NEAR(tet.CalcMeasure(), volume, 1e-9);
  EXPECT_EQ(tet.CalcVertices().size(), 4u);
}

TEST(RegionMeasureTest, SphereDiscChordAndSegment) {
  const Region ball = Region::MakeSphere({1, 0, 0}, 0.5);
  EXPECT_NEAR(ball.CalcMeasure(), 4.0 / 3 * kPi * 0.125, 1e-9);
  const Region disc = Intersect(ball, Region::MakePlane({0, 0, 0.3}, {0, 0, 1}));
  EXPECT_NEAR(disc.CalcMeasure(), kPi * (0.25 - 0.09), 1e-9);
  const Region chord = Intersect(disc, Region::MakePlane({0, 0, 0}, {0, 1, 0}));
  EXPECT_EQ(chord.dimension(), 1);
  EXPECT_NEAR(chord.CalcMeasure(), 2 * 0.4, 1e-9);
  EXPECT_NEAR(Region::MakeSegment({0, 0, 0}, {1, 2, 2}).CalcMeasure(), 3.0, 1e-9);
  // A ball inside a big box is not cut: still exact.
  const Region boxed = Intersect(ball, Region::MakeCuboid({1, 0, 0}, Eigen::Matrix3d::Identity(), 2, 2, 2));
  EXPECT_NEAR(boxed.CalcMeasure(), 4.0 / 3 * kPi * 0.125, 1e-9);
  // A cut ball is not supported.
  const Region cut = Intersect(ball, Region::MakeHalfSpace({1, 0, 0}, {1, 0, 0}));
  EXPECT_THROW(cut.CalcMeasure(), std::domain_error);
  EXPECT_TRUE(cut.Contains(cut.CalcInteriorPoint()));
}

TEST(RegionDegenerateTest, DuplicateAndParallelPlanes) {
  const Region plane = Region::MakePlane({0, 0, 1}, {0, 0, 2});
  EXPECT_EQ(Intersect(plane, plane).dimension(), 2);
  EXPECT_EQ(Intersect(plane, Region::MakePlane({3, 4, 1}, {0, 0, -1})).dimension(), 2);
  EXPECT_TRUE(Intersect(plane, Region::MakePlane({0, 0, 1.001}, {0, 0, 1})).IsEmpty());
  // Closer than the tolerance: the same plane.
  EXPECT_EQ(Intersect(plane, Region::MakePlane({0, 0, 1 + 5e-10}, {0, 0, 1})).dimension(), 2);
  // Duplicate half-spaces are harmless.
  const Region cube = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  EXPECT_NEAR(Intersect(cube, cube).CalcMeasure(), 1.0, 1e-9);
  // Opposite half-spaces that coincide: a plane slice of the cube.
  const Region slab = Intersect(Region::MakeHalfSpace({0, 0, 0.2}, {0, 0, 1}),
                                Region::MakeHalfSpace({0, 0, 0.2}, {0, 0, -1}));
  const Region slice = Intersect(cube, slab);
  EXPECT_EQ(slice.dimension(), 2);
  EXPECT_NEAR(slice.CalcMeasure(), 1.0, 1e-9);
}

TEST(RegionDegenerateTest, SliverThinnerThanToleranceCollapses) {
  const Region cube = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, 0.2, 1).normalized();
  const Region slab = Region::FromHalfSpaces({{n, 0.1 + 5e-10}, {-n, -0.1}});
  const Region sliver = Intersect(cube, slab);
  ASSERT_FALSE(sliver.IsEmpty());
  EXPECT_EQ(sliver.dimension(), 2);
  EXPECT_GT(sliver.CalcMeasure(), 0.5);
  EXPECT_NEAR(std::abs(sliver.CalcPlaneNormal().dot(n)), 1.0, 1e-9);
  for (const auto& v : sliver.CalcVertices()) EXPECT_TRUE(sliver.Contains(v));
  // Two thin directions: a segment; three: a point.
  const Region needle = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 3e-10, 4e-10);
  EXPECT_EQ(needle.dimension(), 1);
  EXPECT_NEAR(needle.CalcMeasure(), 1.0, 1e-9);
  EXPECT_EQ(Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1e-10, 3e-10, 4e-10).dimension(), 0);
  // A thickness just above the tolerance stays 3D.
  EXPECT_EQ(Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 3e-9).dimension(), 3);
}

TEST(RegionDegenerateTest, CrossingConstraints) {
  // x <= 0 and x >= 5e-10 cross by less than 1e-9: a collapsed face, not empty.
  const Region cube = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  const Region near = Intersect(cube, Region::FromHalfSpaces({{{1, 0, 0}, 0}, {{-1, 0, 0}, -5e-10}}));
  ASSERT_FALSE(near.IsEmpty());
  EXPECT_EQ(near.dimension(), 2);
  EXPECT_TRUE(near.Contains(near.CalcInteriorPoint()));
  // Crossing by 2e-9: empty.
  const Region far = Intersect(cube, Region::FromHalfSpaces({{{1, 0, 0}, 0}, {{-1, 0, 0}, -2e-9}}));
  EXPECT_TRUE(far.IsEmpty());
  EXPECT_EQ(far.dimension(), -1);
  EXPECT_FALSE(far.Contains({0, 0, 0}));
  // The same in a plane.
  const Region rect = Region::MakeRect3D({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1);
  EXPECT_EQ(Intersect(rect, Region::FromHalfSpaces({{{1, 0, 0}, 0}, {{-1, 0, 0}, -5e-10}})).dimension(), 1);
  EXPECT_TRUE(Intersect(rect, Region::FromHalfSpaces({{{1, 0, 0}, 0}, {{-1, 0, 0}, -2e-9}})).IsEmpty());
}

// ContainsAll is Contains for every point, on solids, a collapsed sliver, crossing (empty)
// constraints and a ball, with points inside, on and just beyond the boundary.
TEST(RegionQueryTest, ContainsAllIsContainsForEachPoint) {
  const Region cube = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, 0.2, 1).normalized();
  const Region regions[] = {
      cube,
      Intersect(cube, Region::FromHalfSpaces({{n, 0.1 + 5e-10}, {-n, -0.1}})),  // a sliver
      Intersect(cube, Region::FromHalfSpaces({{{1, 0, 0}, 0}, {{-1, 0, 0}, -2e-9}})),  // empty
      Region::MakeSphere({0, 0, 0}, 0.5),
      Region::Empty(),
  };
  std::vector<Eigen::Vector3d> candidates;
  for (double x : {-0.5 - 3e-9, -0.5, 0.0, 0.1 / n.z(), 0.3, 0.5, 0.5 + 3e-9}) {
    for (double z : {0.0, 0.1 / n.z(), 0.1 / n.z() + 2e-9, 0.5}) candidates.emplace_back(x, 0, z);
  }
  for (const Region& region : regions) {
    for (size_t i = 0; i < candidates.size(); ++i) {
      for (size_t j = i; j < candidates.size(); ++j) {
        const std::vector<Eigen::Vector3d> points{candidates[i], candidates[j]};
        EXPECT_EQ(region.ContainsAll(points), region.Contains(points[0]) && region.Contains(points[1]))
            << region.Describe() << " " << points[0].transpose() << " / " << points[1].transpose();
      }
    }
  }
}

TEST(RegionDegenerateTest, EmptyRegion) {
  const Region e = Region::Empty();
  EXPECT_TRUE(e.IsEmpty());
  EXPECT_TRUE(e.IsBounded());
  EXPECT_EQ(e.dimension(), -1);
  EXPECT_EQ(e.CalcMeasure(), 0.0);
  EXPECT_TRUE(e.CalcVertices().empty());
  EXPECT_FALSE(e.Contains({0, 0, 0}));
  EXPECT_THROW(e.CalcInteriorPoint(), std::domain_error);
  EXPECT_EQ(e.hull().basis.cols(), 0);
  EXPECT_TRUE(Intersect(e, Region::All()).IsEmpty());
  const Region disjoint = Intersect(Region::MakeSphere({0, 0, 0}, 1), Region::MakeSphere({2.5, 0, 0}, 1));
  EXPECT_TRUE(disjoint.IsEmpty());
  EXPECT_FALSE(Intersect(Region::MakeSphere({0, 0, 0}, 1), Region::MakeSphere({1.5, 0, 0}, 1)).IsEmpty());
}

TEST(RegionDegenerateTest, UnboundedRegions) {
  for (const Region& r : {Region::All(), Region::MakeHalfSpace({0, 0, 0}, {0, 1, 0}),
                          Region::MakePlane({0, 0, 0}, {1, 1, 0}),
                          Intersect(Region::MakePlane({0, 0, 0}, {0, 0, 1}),
                                    Region::FromHalfSpaces({{{1, 0, 0}, 1}, {{-1, 0, 0}, 1}}))}) {
    EXPECT_FALSE(r.IsEmpty()) << r.Describe();
    EXPECT_FALSE(r.IsBounded()) << r.Describe();
    EXPECT_EQ(r.CalcMeasure(), INFINITY);
    EXPECT_THROW(r.CalcVertices(), std::domain_error);
    EXPECT_TRUE(r.Contains(r.CalcInteriorPoint()));
  }
  // Bounded but large is still bounded.
  EXPECT_TRUE(Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1e4, 1e4, 1e4).IsBounded());
}

TEST(RegionDegenerateTest, ZeroSizesAndPoints) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_EQ(Region::MakeCuboid({0, 0, 0}, I, 1, 1, 0).dimension(), 2);
  EXPECT_EQ(Region::MakeCuboid({0, 0, 0}, I, 1, 0, 0).dimension(), 1);
  EXPECT_EQ(Region::MakeCuboid({0, 0, 0}, I, 0, 0, 0).dimension(), 0);
  EXPECT_EQ(Region::MakeRect3D({0, 0, 0}, I, 0, 0).dimension(), 0);
  const Region p = Region::MakeSphere({1, 2, 3}, 0);
  EXPECT_EQ(p.dimension(), 0);
  EXPECT_EQ(p.CalcMeasure(), 0.0);
  EXPECT_TRUE(p.Contains({1, 2, 3}));
  EXPECT_FALSE(p.Contains({1, 2, 3.001}));
  EXPECT_EQ(Region::MakePoint({1, 2, 3}).CalcVertices()[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(Region::MakeSegment({1, 1, 1}, {1, 1, 1}).dimension(), 0);
  EXPECT_THROW(Region::MakeSphere({0, 0, 0}, -1), std::invalid_argument);
  EXPECT_THROW(Region::MakeCuboid({0, 0, 0}, I, -1, 1, 1), std::invalid_argument);
  EXPECT_THROW(Region::MakeCuboid({0, 0, NAN}, I, 1, 1, 1), std::invalid_argument);
}

TEST(RegionDegenerateTest, PolygonInputs) {
  EXPECT_THROW(Region::MakeConvexPolygon3D({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e-6}}),
               std::invalid_argument);
  const Region seg = Region::MakeConvexPolygon3D({{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0.5, 0.5, 0}});
  EXPECT_EQ(seg.dimension(), 1);
  EXPECT_NEAR(seg.CalcMeasure(), 2 * std::sqrt(2.0), 1e-9);
  EXPECT_EQ(Region::MakeConvexPolygon3D({{1, 1, 1}, {1, 1, 1 + 1e-12}}).dimension(), 0);
  EXPECT_TRUE(Region::MakeConvexPolygon3D({}).IsEmpty());
  // Interior points and duplicates are ignored; coplanar within 1e-9 m is accepted.
  const Region square = Region::MakeConvexPolygon3D(
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-10}, {0, 1, 0}, {0.5, 0.5, 0}, {1, 0, 0}});
  EXPECT_NEAR(square.CalcMeasure(), 1.0, 1e-9);
}

TEST(RegionDegenerateTest, ZeroNormals) {
  EXPECT_FALSE(Region::FromHalfSpaces({{{0, 0, 0}, 1.0}}).IsEmpty());
  EXPECT_TRUE(Region::FromHalfSpaces({{{0, 0, 0}, -1.0}}).IsEmpty());
  EXPECT_THROW(Region::MakeHalfSpace({0, 0, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(Region::MakePlane({0, 0, 0}, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(Region::FromHalfSpaces({{{NAN, 0, 0}, 1.0}}), std::invalid_argument);
}

TEST(RegionQueryTest, HalfSpaceSideAndContains) {
  const Region ahead = Region::MakeHalfSpace({0, 1, 0}, {0, 2, 0});
  EXPECT_TRUE(ahead.Contains({5, 1.5, -3}));
  EXPECT_FALSE(ahead.Contains({5, 0.5, -3}));
  EXPECT_TRUE(ahead.Contains({0, 1 - 5e-10, 0}));
  EXPECT_FALSE(ahead.Contains({0, 1 + 1e-3, 0}, -2e-3));  // not 2 mm inside
  EXPECT_FALSE(ahead.Contains({NAN, 2, 0}));
}

TEST(RegionQueryTest, ContainsBoxUsesFootprintForPlanarRegions) {
  const Region table = Region::MakeRect3D({0, 0, 0.8}, Eigen::Matrix3d::Identity(), 1.0, 0.6);
  OrientedBox cup{{0.3, 0.1, 0.8}, CalcRotationZ(0.3), {0.05, 0.05, 0.1}};
  EXPECT_TRUE(table.ContainsBox(cup));
  cup.p_center.x() = 0.48;  // footprint crosses the edge
  EXPECT_FALSE(table.ContainsBox(cup));
  cup.p_center = {0.3, 0.1, 0.9};  // off the plane
  EXPECT_FALSE(table.ContainsBox(cup));
  const Region room = Region::MakeCuboid({0, 0, 1}, Eigen::Matrix3d::Identity(), 2, 2, 2);
  EXPECT_TRUE(room.ContainsBox({{0, 0, 1}, CalcRotationZ(0.7), {0.5, 0.5, 0.5}}));
  EXPECT_FALSE(room.ContainsBox({{0, 0, 1}, CalcRotationZ(0.7), {0.9, 0.9, 0.5}}));
}

TEST(RegionQueryTest, HullAndPlaneNormal) {
  const Region tilted = Region::MakeRect3D({1, 2, 3}, CalcRotationFromYawPitchRoll(0.3, 2.5, 0), 1, 1);
  const AffineHull& h = tilted.hull();
  ASSERT_EQ(h.basis.cols(), 2);
  EXPECT_LT((h.basis.transpose() * h.basis - Eigen::Matrix2d::Identity()).norm(), 1e-9);
  EXPECT_TRUE(tilted.Contains(h.p_origin + h.basis * tilted.hull().basis.transpose() *
                                                (tilted.CalcInteriorPoint() - h.p_origin)));
  EXPECT_GE(tilted.CalcPlaneNormal().z(), 0.0);
  const Region wall = Region::MakePlane({0, 0, 0}, {-1, 0, 0});
  EXPECT_LT((wall.CalcPlaneNormal() - Eigen::Vector3d(1, 0, 0)).norm(), 1e-9);
  const Region wall_y = Region::MakePlane({0, 0, 0}, {0, -1, 0});
  EXPECT_LT((wall_y.CalcPlaneNormal() - Eigen::Vector3d(0, 1, 0)).norm(), 1e-9);
  EXPECT_THROW(Region::All().CalcPlaneNormal(), std::domain_error);
}

TEST(RegionQueryTest, DescribeNamesKindAndSize) {
  const Region rect = Region::MakeRect3D({0, 0, 0.8}, Eigen::Matrix3d::Identity(), 0.24, 0.45);
  EXPECT_EQ(rect.Describe(), "rectangle 0.24 m × 0.45 m at (0, 0, 0.8)");
  EXPECT_NE(Region::MakeSphere({0, 0, 0}, 2).Describe().find("sphere of radius 2 m"), std::string::npos);
  EXPECT_NE(Intersect(rect, Region::MakeHalfSpace({0, 0, 0}, {1, 0, 0})).Describe().find("dimension 2"),
            std::string::npos);
  EXPECT_NE(Region::MakeHalfSpace({0, 0, 0}, {1, 0, 0}).Describe().find("half-space"), std::string::npos);
  EXPECT_EQ(Region::Empty().Describe(), "empty region");
}

TEST(RegionQueryTest, CopiesShareTheCacheAndIntersectIsLazy) {
  const Region a = Region::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  a.Finalize();
  const Region b = a;
  EXPECT_EQ(&a.canon(), &b.canon());
  const Region c = Intersect(a, Region::MakeHalfSpace({0, 0, 0}, {1, 0, 0}));
  EXPECT_EQ(c.half_spaces().size(), 7u);
  EXPECT_NEAR(c.CalcMeasure(), 0.5, 1e-9);
}

}  // namespace
}  // namespace prs::geometry
