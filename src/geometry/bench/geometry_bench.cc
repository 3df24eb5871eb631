// Benchmarks of the geometry hot paths (docs/benchmarks.md): build a region and draw one
// point in 2D and 3D, one box-pair overlap test, and one erosion with canonicalisation.
#include <cmath>
#include <numbers>
#include <vector>

#include <benchmark/benchmark.h>

#include "geometry/geometry.h"

namespace prs::geometry {
namespace {

// n half-spaces tangent to a sphere (or, with planar = true, a circle in z = 0), at
// directions spread by the golden angle so that every one cuts the region.
std::vector<HalfSpace> MakeTangentHalfSpaces(int n, bool planar) {
  std::vector<HalfSpace> hs;
  for (int k = 0; k < n; ++k) {
    const double phi = k * std::numbers::pi * (3 - std::sqrt(5.0));
    const double z = planar ? 0.0 : 1 - 2 * (k + 0.5) / n;
    const double r = std::sqrt(1 - z * z);
    hs.push_back({{r * std::cos(phi), r * std::sin(phi), z}, 0.5 + 0.01 * k});
  }
  return hs;
}

void BM_Build2DRegionAndSample(benchmark::State& state) {
  const std::vector<HalfSpace> hs = MakeTangentHalfSpaces(8, true);
  const ConvexRegion plane = ConvexRegion::MakePlane({0, 0, 0.75}, {0, 0, 1});
  Rng rng(1);
  for (auto _ : state) {
    const ConvexRegion region = Intersect(plane, ConvexRegion::FromHalfSpaces(hs));
    benchmark::DoNotOptimize(SampleUniform(region, rng));
  }
}
BENCHMARK(BM_Build2DRegionAndSample);

void BM_Build3DRegionAndSample(benchmark::State& state) {
  const std::vector<HalfSpace> hs = MakeTangentHalfSpaces(12, false);
  Rng rng(2);
  for (auto _ : state) {
    const ConvexRegion region = ConvexRegion::FromHalfSpaces(hs);
    benchmark::DoNotOptimize(SampleUniform(region, rng));
  }
}
BENCHMARK(BM_Build3DRegionAndSample);

void BM_SampleOnly3D(benchmark::State& state) {
  const RegionSampler sampler(ConvexRegion::FromHalfSpaces(MakeTangentHalfSpaces(12, false)));
  Rng rng(3);
  for (auto _ : state) benchmark::DoNotOptimize(sampler.Sample(rng));
}
BENCHMARK(BM_SampleOnly3D);

void BM_BoxOverlap(benchmark::State& state) {
  Rng rng(4);
  std::vector<OrientedBox> boxes(64);
  for (auto& b : boxes) {
    b.p_center = {rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5)};
    b.R_WB = CalcRotationFromYawPitchRoll(rng.Uniform(-3, 3), rng.Uniform(-1.5, 1.5),
                                          rng.Uniform(-3, 3));
    b.half_extents = {rng.Uniform(0.05, 0.3), rng.Uniform(0.05, 0.3), rng.Uniform(0.05, 0.3)};
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(DoBoxesOverlap(boxes[i % 64], boxes[(i * 7 + 1) % 64]));
    ++i;
  }
}
BENCHMARK(BM_BoxOverlap);

void BM_ErodeTableTopAndCanonicalise(benchmark::State& state) {
  const ConvexRegion top = ConvexRegion::MakeRect3D({0, 0, 0.8}, CalcRotationZ(0.3), 1.2, 0.7);
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.7, 0, 0);
  for (auto _ : state) {
    const ConvexRegion eroded = ErodeByBox(top, R, {0.05, 0.08, 0.1});
    benchmark::DoNotOptimize(eroded.CalcMeasure());
  }
}
BENCHMARK(BM_ErodeTableTopAndCanonicalise);

void BM_ErodeCuboidAndCanonicalise(benchmark::State& state) {
  const ConvexRegion room = ConvexRegion::MakeCuboid({0, 0, 1}, CalcRotationZ(0.3), 3, 2, 2);
  const Eigen::Matrix3d R = CalcRotationFromYawPitchRoll(0.7, 0.2, 0.1);
  for (auto _ : state) {
    const ConvexRegion eroded = ErodeByBox(room, R, {0.05, 0.08, 0.1});
    benchmark::DoNotOptimize(eroded.CalcMeasure());
  }
}
BENCHMARK(BM_ErodeCuboidAndCanonicalise);

}  // namespace
}  // namespace prs::geometry
