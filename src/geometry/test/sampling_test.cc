// Tests of the exact region sampler: containment, chi-square uniformity on hard shapes,
// and a short hit-and-run chain failing where the exact sampler passes.
#include "geometry/sampling.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/rotation.h"
#include "geometry/test/test_util.h"

namespace prs::geometry {
namespace {

using testing::CalcChiSquare;
using testing::ChiSquareQuantile999;

constexpr int kDraws = 30000;

// Grid cells in a frame (origin, axes), each clipped to the region by the region code.
struct Grid {
  Eigen::Vector3d p_origin;
  Eigen::Matrix3d axes;     // columns: grid directions (orthonormal)
  Eigen::Vector3i counts;   // cells per direction (1 for an unused direction)
  Eigen::Vector3d step;     // cell size per direction

  int CellOf(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d u = axes.transpose() * (p - p_origin);
    int index = 0;
    for (int i = 2; i >= 0; --i) {
      const int k = std::clamp(static_cast<int>(std::floor(u[i] / step[i])), 0, counts[i] - 1);
      index = index * counts[i] + k;
    }
    return index;
  }
  ConvexRegion Cell(int index) const {
    std::vector<HalfSpace> hs;
    for (int i = 0; i < 3; ++i) {
      const int k = index % counts[i];
      index /= counts[i];
      if (counts[i] == 1) continue;
      const Eigen::Vector3d a = axes.col(i);
      const double lo = a.dot(p_origin) + k * step[i];
      hs.push_back({a, lo + step[i]});
      hs.push_back({-a, -lo});
    }
    return ConvexRegion::FromHalfSpaces(hs);
  }
  int size() const { return counts.prod(); }
};

// Expected counts from exact cell measures; checks the cells tile the region.
std::vector<double> CalcExpected(const ConvexRegion& region, const Grid& grid, int draws) {
  std::vector<double> expected(grid.size());
  double sum = 0;
  const double total = region.CalcMeasure();
  for (int i = 0; i < grid.size(); ++i) {
    const ConvexRegion cell = Intersect(region, grid.Cell(i));
    const double m = cell.IsEmpty() || cell.dimension() < region.dimension() ? 0 : cell.CalcMeasure();
    sum += m;
    expected[i] = draws * m / total;
  }
  EXPECT_NEAR(sum, total, 1e-9 * total + 1e-10) << "the grid cells must tile the region";
  return expected;
}

template <typename Draw>
testing::ChiSquareResult RunChiSquare(const ConvexRegion& region, const Grid& grid, Draw draw) {
  const std::vector<double> expected = CalcExpected(region, grid, kDraws);
  std::vector<double> observed(grid.size(), 0);
  for (int i = 0; i < kDraws; ++i) {
    const Eigen::Vector3d p = draw();
    EXPECT_TRUE(region.Contains(p)) << p.transpose();
    observed[grid.CellOf(p)] += 1;
  }
  return CalcChiSquare(expected, observed);
}

void ExpectUniform(const ConvexRegion& region, const Grid& grid, uint64_t seed) {
  const RegionSampler sampler(region);
  Rng rng(seed);
  const auto result = RunChiSquare(region, grid, [&] { return sampler.Sample(rng); });
  ASSERT_GE(result.degrees_of_freedom, 5);
  EXPECT_LT(result.statistic, ChiSquareQuantile999(result.degrees_of_freedom))
      << "df " << result.degrees_of_freedom;
}

const Eigen::Matrix3d kYaw30 = CalcRotationZ(std::numbers::pi / 6);

ConvexRegion ThinSliver() {
  return ConvexRegion::MakeRect3D({0.2, 0.1, 0.5}, kYaw30, 1.0, 0.002);
}

Grid SliverGrid() {
  const Eigen::Vector3d corner = Eigen::Vector3d(0.2, 0.1, 0.5) + kYaw30 * Eigen::Vector3d(-0.5, -0.001, 0);
  return {corner, kYaw30, {20, 2, 1}, {0.05, 0.001, 1}};
}

TEST(SamplingUniformityTest, LongRectangle) {
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.7, 0.2, 0.1);
  const Eigen::Vector3d center(1, -1, 0.7);
  const ConvexRegion rect = ConvexRegion::MakeRect3D(center, R, 1.8, 0.1);
  const Grid grid{center + R * Eigen::Vector3d(-0.9, -0.05, 0), R, {18, 4, 1}, {0.1, 0.025, 1}};
  // Independent check of the cell measures: all equal to 0.1 × 0.025.
  for (double e : CalcExpected(rect, grid, 72)) EXPECT_NEAR(e, 1.0, 1e-9);
  ExpectUniform(rect, grid, 101);
}

TEST(SamplingUniformityTest, ThinRotatedSliver) { ExpectUniform(ThinSliver(), SliverGrid(), 102); }

TEST(SamplingUniformityTest, SkewedTetrahedron) {
  const ConvexRegion tet = Intersect(
      ConvexRegion::FromHalfSpaces({{{0, 0, -1}, 0}, {{-1, 0.2, 0}, 0}}),
      ConvexRegion::FromHalfSpaces({{{0.1, -1, 0.3}, 0}, {{1, 1, 1}, 1.2}}));
  ASSERT_TRUE(tet.IsBounded());
  ASSERT_EQ(tet.CalcVertices().size(), 4u);
  const std::vector<Eigen::Vector3d> v = tet.CalcVertices();
  Eigen::Vector3d lo = v[0], hi = v[0];
  for (const auto& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Grid grid{lo, Eigen::Matrix3d::Identity(), {5, 5, 5}, (hi - lo) / 5};
  ExpectUniform(tet, grid, 103);
}

TEST(SamplingUniformityTest, PolygonCutByTwelveHalfPlanes) {
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.3, 0.4, 0);
  const Eigen::Vector3d center(0, 0, 1);
  ConvexRegion region = ConvexRegion::MakeRect3D(center, R, 1.2, 1.2);
  for (int k = 0; k < 12; ++k) {
    const double t = 2 * std::numbers::pi * k / 12 + 0.1;
    const Eigen::Vector3d n = R * Eigen::Vector3d(std::cos(t), std::sin(t), 0);
    region = Intersect(region, ConvexRegion::FromHalfSpaces({{n, n.dot(center) + 0.45 + 0.01 * k}}));
  }
  ASSERT_EQ(region.CalcVertices().size(), 12u);
  const Grid grid{center + R * Eigen::Vector3d(-0.6, -0.6, 0), R, {8, 8, 1}, {0.15, 0.15, 1}};
  ExpectUniform(region, grid, 104);
}

TEST(SamplingUniformityTest, ShortHitAndRunFailsWhereExactPasses) {
  const ConvexRegion sliver = ThinSliver();
  const Eigen::Vector3d corner = sliver.CalcVertices()[0];
  const Eigen::Vector3d start = corner + 1e-4 * (sliver.CalcInteriorPoint() - corner);
  Rng rng(105);
  const auto chain = RunChiSquare(sliver, SliverGrid(),
                                  [&] { return SampleHitAndRun(sliver, start, 5, rng); });
  EXPECT_GT(chain.statistic, ChiSquareQuantile999(chain.degrees_of_freedom));
  ExpectUniform(sliver, SliverGrid(), 105);
}

TEST(SamplingTest, PointsAlwaysInside) {
  Rng rng(106);
  const Eigen::Matrix3d R = testing::RandomRotation(rng);
  const ConvexRegion cube = ConvexRegion::MakeCuboid({0, 0, 0}, R, 0.5, 0.4, 0.3);
  const std::vector<ConvexRegion> regions = {
      ConvexRegion::MakeRect3D({1, 2, 3}, R, 0.3, 0.2),
      cube,
      Intersect(cube, ConvexRegion::MakeHalfSpace({0.05, 0, 0}, {1, 1, 0})),
      ConvexRegion::MakeConvexPolygon3D({{0, 0, 0}, {1, 0, 0.5}, {0.4, 1, 0.2}}),
      ConvexRegion::MakeSegment({0, 0, 0}, {1, -1, 2}),
      ConvexRegion::MakePoint({1, 2, 3}),
      ConvexRegion::MakeSphere({0, 1, 0}, 0.3),
      Intersect(ConvexRegion::MakeSphere({0, 1, 0}, 0.3), ConvexRegion::MakePlane({0, 0, 0.1}, {0, 0.3, 1})),
      Intersect(ConvexRegion::MakeSphere({0, 1, 0}, 0.3), ConvexRegion::MakeHalfSpace({0, 1, 0}, {1, 0, 0})),
      Intersect(cube, ConvexRegion::FromHalfSpaces({{R.col(0), 0.0}, {-R.col(0), 5e-10}})),  // sliver
      Intersect(cube, ConvexRegion::FromHalfSpaces({{R.col(0), 0.0}, {-R.col(0), -5e-10}})),  // crossing
      ErodeByBox(cube, testing::RandomRotation(rng), {0.05, 0.1, 0.02}),
  };
  for (const ConvexRegion& region : regions) {
    const RegionSampler sampler(region);
    EXPECT_EQ(sampler.dimension(), region.dimension()) << region.Describe();
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3d p = sampler.Sample(rng);
      ASSERT_TRUE(region.Contains(p)) << region.Describe() << " at " << p.transpose();
    }
  }
}

TEST(SamplingTest, MeasureAndDeterminism) {
  const ConvexRegion rect = ConvexRegion::MakeRect3D({0, 0, 0}, kYaw30, 2, 3);
  const RegionSampler sampler(rect);
  EXPECT_NEAR(sampler.measure(), 6.0, 1e-9);
  EXPECT_TRUE(sampler.measure_is_exact());
  Rng a(7), b(7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(sampler.Sample(a), SampleUniform(rect, b));
}

TEST(SamplingTest, FailuresThrow) {
  Rng rng(107);
  EXPECT_THROW(RegionSampler{ConvexRegion::Empty()}, std::domain_error);
  EXPECT_THROW(RegionSampler(ConvexRegion::MakeHalfSpace({0, 0, 0}, {0, 0, 1})), std::domain_error);
  // Two balls meeting in a lens 1e-6 m thick: the bounding-box part is almost all rejected.
  const ConvexRegion lens = Intersect(ConvexRegion::MakeSphere({0, 0, 0}, 1),
                                      ConvexRegion::MakeSphere({2 - 1e-6, 0, 0}, 1));
  ASSERT_FALSE(lens.IsEmpty());
  EXPECT_THROW(RegionSampler(lens).Sample(rng), std::domain_error);
  const ConvexRegion cube = ConvexRegion::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 1, 1);
  EXPECT_THROW(SampleHitAndRun(cube, {2, 0, 0}, 3, rng), std::invalid_argument);
  EXPECT_THROW(SampleHitAndRun(cube, {0, 0, 0}, -1, rng), std::invalid_argument);
  EXPECT_TRUE(cube.Contains(SampleHitAndRun(cube, {0, 0, 0}, 50, rng)));
}


// SampleAt with i.i.d. uniform u must be exactly uniform too (the same chi-square tests).
void ExpectUniformAt(const ConvexRegion& region, const Grid& grid, uint64_t seed) {
  const RegionSampler sampler(region);
  Rng rng(seed), fallback(seed + 1000);
  const auto result = RunChiSquare(region, grid, [&] {
    const double u[3] = {rng.Uniform01(), rng.Uniform01(), rng.Uniform01()};
    return sampler.SampleAt(u, fallback);
  });
  ASSERT_GE(result.degrees_of_freedom, 5);
  EXPECT_LT(result.statistic, ChiSquareQuantile999(result.degrees_of_freedom))
      << "df " << result.degrees_of_freedom;
}

TEST(SampleAtTest, UniformOnPolygonsAndPolyhedra) {
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.7, 0.2, 0.1);
  const Eigen::Vector3d center(1, -1, 0.7);
  ExpectUniformAt(ConvexRegion::MakeRect3D(center, R, 1.8, 0.1),
                  {center + R * Eigen::Vector3d(-0.9, -0.05, 0), R, {18, 4, 1}, {0.1, 0.025, 1}},
                  201);
  ExpectUniformAt(ThinSliver(), SliverGrid(), 202);
  // A 12-gon, and a skewed tetrahedron.
  ConvexRegion polygon = ConvexRegion::MakeRect3D({0, 0, 1}, kYaw30, 1.2, 1.2);
  for (int k = 0; k < 12; ++k) {
    const double t = 2 * std::numbers::pi * k / 12 + 0.1;
    const Eigen::Vector3d n = kYaw30 * Eigen::Vector3d(std::cos(t), std::sin(t), 0);
    polygon = Intersect(polygon, ConvexRegion::FromHalfSpaces({{n, n.z() + 0.45 + 0.01 * k}}));
  }
  ExpectUniformAt(polygon,
                  {Eigen::Vector3d(0, 0, 1) + kYaw30 * Eigen::Vector3d(-0.6, -0.6, 0), kYaw30,
                   {8, 8, 1}, {0.15, 0.15, 1}},
                  203);
  const ConvexRegion cube = ConvexRegion::MakeCuboid({0, 0, 0}, Eigen::Matrix3d::Identity(), 1, 2, 1);
  const ConvexRegion cut = Intersect(cube, ConvexRegion::MakeHalfSpace({0, 0, 0}, {1, 1, 1}));
  ExpectUniformAt(cut, {{-0.5, -1, -0.5}, Eigen::Matrix3d::Identity(), {4, 8, 4}, {0.25, 0.25, 0.25}},
                  204);
}

TEST(SampleAtTest, PointsInsideAndNearbyCoordinatesGiveNearbyPoints) {
  Rng rng(205);
  const ConvexRegion triangle =
      ConvexRegion::MakeConvexPolygon3D({{0, 0, 0}, {1, 0, 0.5}, {0.4, 1, 0.2}});
  const ConvexRegion segment = ConvexRegion::MakeSegment({0, 0, 0}, {1, -1, 2});
  const ConvexRegion ball = ConvexRegion::MakeSphere({0, 1, 0}, 0.3);
  for (const ConvexRegion* region : {&triangle, &segment, &ball}) {
    const RegionSampler sampler(*region);
    for (int i = 0; i < 2000; ++i) {
      const double u[3] = {rng.Uniform01(), rng.Uniform01(), rng.Uniform01()};
      ASSERT_TRUE(region->Contains(sampler.SampleAt(u, rng))) << region->Describe();
    }
  }
  // A polygon's map is continuous: a step of 1e-6 in u moves the point by micrometres.
  const RegionSampler sampler(triangle);
  for (int i = 0; i < 500; ++i) {
    double u[3] = {0.001 + 0.998 * rng.Uniform01(), rng.Uniform01(), 0};
    const Eigen::Vector3d p = sampler.SampleAt(u, rng);
    u[0] += 1e-6;
    u[1] = std::min(u[1] + 1e-6, 0.999999);
    EXPECT_LT((sampler.SampleAt(u, rng) - p).norm(), 1e-4);
  }
  // The corners of the unit square map to the polygon's extremes along its first axis.
  const double u_lo[3] = {0, 0.5, 0}, u_hi[3] = {0.999999999, 0.5, 0};
  const double extent = (sampler.SampleAt(u_hi, rng) - sampler.SampleAt(u_lo, rng)).norm();
  EXPECT_GT(extent, 0.5);
}

}  // namespace
}  // namespace prs::geometry
