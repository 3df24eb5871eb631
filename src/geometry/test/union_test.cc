// Tests of unions of convex pieces: moving regions between frames, the grid index against a
// scan, exact piecewise intersection (slices on shared facets counted once), and uniform
// sampling across pieces by measure (chi-squared), with and without balls.
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/test/test_util.h"
#include "geometry/union.h"

namespace prs::geometry {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using testing::RandomRotation;
using testing::RandomVector;

ConvexRegion Box(const Vector3d& lo, const Vector3d& hi) {
  return ConvexRegion::MakeCuboid(0.5 * (lo + hi), Eigen::Matrix3d::Identity(), hi.x() - lo.x(),
                                  hi.y() - lo.y(), hi.z() - lo.z());
}

RegionUnion MakeUnion(std::vector<ConvexRegion> pieces, const Isometry3d& X_WL = Isometry3d::Identity()) {
  return RegionUnion(std::make_shared<const PieceSet>(std::move(pieces)), X_WL);
}

Isometry3d RandomPose(Rng& rng) {
  Isometry3d X = Isometry3d::Identity();
  X.linear() = RandomRotation(rng);
  X.translation() = RandomVector(rng, -2, 2);
  return X;
}

// Pearson's statistic of observed counts against expected probabilities.
double ChiSquared(const std::vector<int>& counts, const std::vector<double>& probabilities) {
  int n = 0;
  for (int c : counts) n += c;
  double chi2 = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    const double expected = n * probabilities[i];
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
  }
  return chi2;
}

// The index of the piece containing p (in the union's frame), or -1; fails if several do.
int FindPiece(const RegionUnion& u, const Vector3d& p_W) {
  const Vector3d p_L = u.X_WL().inverse() * p_W;
  int found = -1;
  for (int i = 0; i < u.num_pieces(); ++i) {
    if (!u.piece_set().pieces()[i].Contains(p_L, 1e-9)) continue;
    EXPECT_EQ(found, -1) << "point " << p_W.transpose() << " in pieces " << found << " and " << i;
    found = i;
  }
  return found;
}

TEST(TransformRegionTest, MovesEveryKindOfConstraint) {
  Rng rng(11, 0);
  for (int trial = 0; trial < 50; ++trial) {
    const Isometry3d X_BA = RandomPose(rng);
    ConvexRegion a = Box(Vector3d(-0.5, -0.3, -0.2), Vector3d(0.4, 0.6, 0.3));
    if (trial % 3 == 1) a = Intersect(a, ConvexRegion::MakePlane(Vector3d(0, 0, 0.1), Vector3d(0, 0.2, 1)));
    if (trial % 3 == 2) a = Intersect(a, ConvexRegion::MakeSphere(Vector3d(0.1, 0, 0), 0.35));
    const ConvexRegion b = TransformRegion(a, X_BA);
    for (int i = 0; i < 200; ++i) {
      const Vector3d p_A = RandomVector(rng, -0.7, 0.7);
      ASSERT_EQ(a.Contains(p_A, 0), b.Contains(X_BA * p_A, 1e-12)) << "trial " << trial;
    }
    if (trial % 3 == 0) {
      EXPECT_NEAR(a.CalcMeasure(), b.CalcMeasure(), 1e-9);
    }
  }
}

TEST(PieceSetTest, IndexFindsWhatAScanFinds) {
  Rng rng(12, 0);
  std::vector<ConvexRegion> pieces;
  for (int i = 0; i < 300; ++i) {
    const Vector3d lo = RandomVector(rng, -3, 3);
    pieces.push_back(Box(lo, lo + RandomVector(rng, 0.01, 0.5)));
  }
  pieces.push_back(ConvexRegion::MakeHalfSpace(Vector3d(10, 0, 0), Vector3d(1, 0, 0)));  // unbounded
  const PieceSet set(pieces);
  ASSERT_EQ(set.size(), 301);
  for (int q = 0; q < 200; ++q) {
    const Vector3d lo = RandomVector(rng, -3.5, 3.5);
    const Eigen::AlignedBox3d query(lo, lo + RandomVector(rng, 0, 1.5));
    std::vector<int> found, expected;
    set.FindPiecesNear(query, &found);
    for (int i = 0; i < set.size(); ++i) {
      if (set.bounds(i).intersects(query)) expected.push_back(i);
    }
    ASSERT_EQ(found, expected) << "query " << q;
  }
}

TEST(UnionIntersectTest, PiecesAreIntersectedExactly) {
  Rng rng(13, 0);
  // Four unit cubes in a row, placed somewhere in the world.
  std::vector<ConvexRegion> cubes;
  for (int i = 0; i < 4; ++i) cubes.push_back(Box(Vector3d(i, 0, 0), Vector3d(i + 1, 1, 1)));
  const Isometry3d X_WL = RandomPose(rng);
  const RegionUnion u = MakeUnion(cubes, X_WL);
  EXPECT_NEAR(u.CalcMeasure(), 4.0, 1e-9);
  const ConvexRegion ball_box = TransformRegion(Box(Vector3d(0.5, 0.2, 0.1), Vector3d(2.5, 0.9, 0.6)), X_WL);
  const RegionUnion cut = Intersect(u, ball_box);
  EXPECT_EQ(cut.num_pieces(), 3);
  EXPECT_NEAR(cut.CalcMeasure(), 2.0 * 0.7 * 0.5, 1e-9);
  for (int i = 0; i < 2000; ++i) {
    const Vector3d p_W = X_WL * RandomVector(rng, -0.5, 4.5);
    ASSERT_EQ(cut.Contains(p_W, 0), u.Contains(p_W, 0) && ball_box.Contains(p_W, 0));
  }
}

TEST(UnionIntersectTest, ASliceOnASharedFacetIsCountedOnce) {
  // Two boxes stacked in z, and a third beside them; the plane z = 1 is their shared facet.
  const RegionUnion u = MakeUnion({Box(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                                   Box(Vector3d(0, 0, 1), Vector3d(1, 1, 2)),
                                   Box(Vector3d(1, 0, 0), Vector3d(2, 1, 2))});
  const RegionUnion slice = Intersect(u, ConvexRegion::MakePlane(Vector3d(0, 0, 1), Vector3d(0, 0, 1)));
  EXPECT_EQ(slice.dimension(), 2);
  EXPECT_EQ(slice.num_pieces(), 2);  // the lower box's top, and the side box's cut
  EXPECT_NEAR(slice.CalcMeasure(), 2.0, 1e-9);
  // The plane tilted slightly about x = 0.5 cuts three pieces (both stacked boxes and the side
  // box), and the area is that of the tilted cut.
  const RegionUnion tilted =
      Intersect(u, ConvexRegion::MakePlane(Vector3d(0.5, 0, 1), Vector3d(0.01, 0, 1)));
  EXPECT_EQ(tilted.num_pieces(), 3);
  EXPECT_NEAR(tilted.CalcMeasure(), 2.0 * std::sqrt(1 + 1e-4), 1e-9);
}

TEST(UnionIntersectTest, APlanarRegionsSlicesAgreeWithTheGeneralIntersection) {
  // A planar region's slices are made by clipping its polygon (union.cc); each must be the
  // set the general intersection gives: same area, same vertices, same membership. Planes
  // parallel to the pieces' faces (horizontal against a grid of boxes) and tilted ones.
  Rng rng(16, 0);
  std::vector<ConvexRegion> grid;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 2; ++k) {
        const Vector3d lo(0.3 * i, 0.3 * j, 0.4 * k);
        grid.push_back(Box(lo, lo + Vector3d(0.3, 0.3, 0.4)));
      }
    }
  }
  const RegionUnion u = MakeUnion(grid);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d normal = trial % 2 == 0 ? Vector3d::UnitZ() : RandomVector(rng, -1, 1);
    // The first table lies on the boxes' shared facets z = 0.4.
    const Vector3d p_on = trial == 0 ? Vector3d(0.45, 0.45, 0.4) : RandomVector(rng, 0.1, 0.8);
    const ConvexRegion table = Intersect(ConvexRegion::MakePlane(p_on, normal),
                                         Box(RandomVector(rng, -0.2, 0.4), RandomVector(rng, 0.5, 1.1)));
    if (table.IsEmpty() || table.dimension() != 2) continue;
    const RegionUnion cut = Intersect(u, table);
    double general_area = 0;
    for (const ConvexRegion& piece : grid) {
      const ConvexRegion slice = Intersect(piece, table);
      if (!slice.IsEmpty() && slice.dimension() == 2) general_area += slice.CalcMeasure();
    }
    // (On the shared facets both boxes' general slices are whole faces; the union counts one.)
    if (trial > 0) {
      ASSERT_NEAR(cut.CalcMeasure(), general_area, 1e-9) << "trial " << trial;
    }
    // The boxes tile [0, 0.9]² × [0, 0.8]: the slices' area is the table's within that.
    const ConvexRegion inside = Intersect(table, Box(Vector3d::Zero(), Vector3d(0.9, 0.9, 0.8)));
    ASSERT_NEAR(cut.CalcMeasure(), inside.IsEmpty() || inside.dimension() < 2 ? 0.0 : inside.CalcMeasure(), 1e-9)
        << "trial " << trial;
    for (int p = 0; p < cut.num_pieces(); ++p) {
      const ConvexRegion& slice = cut.piece_set().pieces()[p];
      for (const Vector3d& v : slice.CalcVertices()) {
        ASSERT_TRUE(table.Contains(v, 1e-9) && u.Contains(v, 1e-9)) << "trial " << trial;
      }
      const Vector3d p_in = slice.CalcInteriorPoint();
      ASSERT_TRUE(table.Contains(p_in, 1e-9) && slice.Contains(p_in, 0)) << "trial " << trial;
    }
    if (cut.IsEmpty()) continue;
    const UnionSampler sampler(cut);
    for (int i = 0; i < 50; ++i) {
      const Vector3d p = sampler.Sample(rng);
      ASSERT_TRUE(table.Contains(p, 1e-9) && u.Contains(p, 1e-9)) << "trial " << trial;
    }
  }
}

TEST(UnionIntersectTest, LowerDimensionalResultsOfOtherPiecesAreDropped) {
  const RegionUnion u = MakeUnion({Box(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                                   Box(Vector3d(2, 0, 0), Vector3d(3, 1, 1))});
  // Meets the first box in an edge (x = 1, y = 1) and the second in half its face y = 1: the
  // intersection is that face, and the edge is dropped.
  const ConvexRegion touching = Box(Vector3d(1, 1, 0), Vector3d(2.5, 2, 1));
  const RegionUnion cut = Intersect(u, touching);
  EXPECT_EQ(cut.dimension(), 2);
  EXPECT_EQ(cut.num_pieces(), 1);
  EXPECT_NEAR(cut.CalcMeasure(), 0.5, 1e-9);
  const ConvexRegion overlapping = Box(Vector3d(0.5, 0.5, 0), Vector3d(2.5, 2, 1));
  const RegionUnion both = Intersect(u, overlapping);
  EXPECT_EQ(both.num_pieces(), 2);
  EXPECT_EQ(both.dimension(), 3);
}

TEST(UnionIntersectTest, TwoUnionsIntersectPieceByPiece) {
  Rng rng(14, 0);
  const RegionUnion a = MakeUnion({Box(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                                   Box(Vector3d(1, 0, 0), Vector3d(2, 1, 1))});
  const RegionUnion b = MakeUnion({Box(Vector3d(0.5, 0.5, 0), Vector3d(1.5, 1.5, 1)),
                                   Box(Vector3d(1.5, 0.5, 0), Vector3d(3, 1.5, 1))},
                                  Isometry3d::Identity());
  const RegionUnion ab = Intersect(a, b);
  EXPECT_EQ(ab.num_pieces(), 3);
  EXPECT_NEAR(ab.CalcMeasure(), 1.5 * 0.5, 1e-9);
  for (int i = 0; i < 2000; ++i) {
    const Vector3d p = RandomVector(rng, -0.5, 3.5);
    ASSERT_EQ(ab.Contains(p, 0), a.Contains(p, 0) && b.Contains(p, 0));
  }
}

TEST(UnionSamplerTest, PiecesAreDrawnInProportionToTheirMeasure) {
  Rng rng(15, 0);
  const Isometry3d X_WL = RandomPose(rng);
  // Volumes 1, 2 and 0.5: a piece by measure, then a point in it.
  const RegionUnion u = MakeUnion({Box(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                                   Box(Vector3d(1, 0, 0), Vector3d(3, 1, 1)),
                                   Box(Vector3d(0, 1, 0), Vector3d(1, 1.5, 1))},
                                  X_WL);
  const UnionSampler sampler(u);
  EXPECT_NEAR(sampler.measure(), 3.5, 1e-9);
  std::vector<int> counts(3, 0);
  std::array<int, 10> slab{};  // x coordinate over [0, 3) in the frame: uniform by volume
  const int n = 35000;
  for (int i = 0; i < n; ++i) {
    const Vector3d p_W = sampler.Sample(rng);
    const int piece = FindPiece(u, p_W);
    ASSERT_GE(piece, 0);
    ++counts[piece];
    ++slab[std::min(9, static_cast<int>((X_WL.inverse() * p_W).x() / 0.3))];
  }
  // Chi-squared with 2 degrees of freedom: 13.8 is its 0.999 quantile.
  EXPECT_LT(ChiSquared(counts, {1 / 3.5, 2 / 3.5, 0.5 / 3.5}), 13.8);
  // Within the first piece the density is that of the others: x in [0, 0.9) holds 1.35/3.5.
  const int first = slab[0] + slab[1] + slab[2];
  EXPECT_NEAR(first / static_cast<double>(n), 1.35 / 3.5, 4 * std::sqrt(0.25 / n));
}

TEST(UnionSamplerTest, BallsRestartTheWholeDrawSoTheLawStaysExact) {
  Rng rng(16, 0);
  // A ball of radius 0.5 centred at x = 0.8 over two unit cubes meeting at x = 1: the part in
  // the second cube is a cap of height 0.3, volume π h² (3r − h) / 3.
  const RegionUnion cubes = MakeUnion({Box(Vector3d(0, 0, 0), Vector3d(1, 1, 1)),
                                       Box(Vector3d(1, 0, 0), Vector3d(2, 1, 1))});
  const RegionUnion u = Intersect(cubes, ConvexRegion::MakeSphere(Vector3d(0.8, 0.5, 0.5), 0.5));
  ASSERT_EQ(u.num_pieces(), 2);
  const UnionSampler sampler(u);
  EXPECT_TRUE(sampler.has_balls());
  const double pi = std::numbers::pi;
  const double cap = pi * 0.09 * (1.5 - 0.3) / 3, ball = 4 * pi * 0.125 / 3;
  std::vector<int> counts(2, 0);
  for (int i = 0; i < 30000; ++i) {
    const Vector3d p = sampler.Sample(rng);
    ASSERT_LE((p - Vector3d(0.8, 0.5, 0.5)).norm(), 0.5 + 1e-12);
    ++counts[p.x() < 1 ? 0 : 1];
  }
  // Chi-squared with 1 degree of freedom: 10.8 is its 0.999 quantile. (Picking the piece by
  // its polytope part and retrying inside it would give the cube 1/2, far off.)
  EXPECT_LT(ChiSquared(counts, {1 - cap / ball, cap / ball}), 10.8);
}

TEST(UnionSamplerTest, RefusesEmptyAndUnboundedUnions) {
  EXPECT_THROW(UnionSampler{RegionUnion{}}, std::domain_error);
  EXPECT_THROW(UnionSampler(MakeUnion({ConvexRegion::MakeHalfSpace(Vector3d::Zero(), Vector3d::UnitZ())})),
               std::domain_error);
  EXPECT_TRUE(RegionUnion().IsEmpty());
  EXPECT_NE(MakeUnion({Box(Vector3d::Zero(), Vector3d::Ones())}).Describe().find("one convex piece"),
            std::string::npos);
}

}  // namespace
}  // namespace prs::geometry
