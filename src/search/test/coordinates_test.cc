// Scene coordinates: attempts run at i.i.d. uniform points give the program's distribution
// (chi-square against the stream), the sampler is a deterministic map from a point to a scene,
// names come from the program, and programs whose draws vary or reject still sample exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "geometry/test/test_util.h"
#include "sampling/batch.h"
#include "sampling/test/scene_checks.h"

namespace prs::search {
namespace {

using sampling::testing_checks::CompileExample;
using sampling::testing_checks::CompileOrDie;

// I.i.d. uniform points from a stream of their own (the baseline a search's "random" uses).
class IidPoints : public sampling::AttemptPoints {
 public:
  explicit IidPoints(int dimension) : dimension_(dimension) {}
  int dimension() const override { return dimension_; }
  bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const override {
    geometry::Rng rng(seed * 1000003 + static_cast<uint64_t>(attempt), index + (1ULL << 40));
    for (int j = 0; j < dimension_; ++j) u[j] = rng.Uniform01();
    return true;
  }

 private:
  int dimension_;
};

// One fixed point for every scene and attempt.
class FixedPoint : public sampling::AttemptPoints {
 public:
  explicit FixedPoint(std::vector<double> u) : u_(std::move(u)) {}
  int dimension() const override { return static_cast<int>(u_.size()); }
  bool Point(uint64_t, uint64_t, int64_t, double* u) const override {
    std::copy(u_.begin(), u_.end(), u);
    return true;
  }

 private:
  std::vector<double> u_;
};

std::vector<sampling::SampledScene> SampleMany(const lang::CompiledProgram& program, uint64_t seed,
                                               int64_t count,
                                               const sampling::AttemptPoints* points) {
  sampling::BatchOptions options;
  options.seed = seed;
  options.count = count;
  options.threads = 2;
  options.sample.points = points;
  std::vector<sampling::SampledScene> scenes;
  sampling::SampleBatch(program, options, {.prepare = {}, .consume = [&](sampling::BatchScene&& s) {
                                             scenes.push_back(std::move(s.sampled));
                                           }});
  return scenes;
}

// Two-sample chi-square homogeneity test on bin counts of equal-size samples; true when the
// samples look alike at the 0.1 % level.
void ExpectSameDistribution(const std::map<int, int>& a, const std::map<int, int>& b,
                            const std::string& what) {
  std::set<int> bins;
  for (const auto& [k, n] : a) bins.insert(k);
  for (const auto& [k, n] : b) bins.insert(k);
  double statistic = 0;
  for (int k : bins) {
    const double x = a.count(k) ? a.at(k) : 0, y = b.count(k) ? b.at(k) : 0;
    if (x + y > 0) statistic += (x - y) * (x - y) / (x + y);
  }
  const int df = static_cast<int>(bins.size()) - 1;
  ASSERT_GE(df, 3) << what;
  EXPECT_LT(statistic, geometry::testing::ChiSquareQuantile999(df)) << what << ", df " << df;
}

int Bin(double x, double lo, double hi, int bins) {
  return std::clamp(static_cast<int>(std::floor((x - lo) / (hi - lo) * bins)), 0, bins - 1);
}

TEST(SceneCoordinatesTest, IidPointsGiveTheDistributionOfTheStream) {
  const auto program = CompileExample("table_cube.prs");
  const int d = static_cast<int>(sampling::DescribeCoordinates(*program).size());
  ASSERT_EQ(d, 11);
  const IidPoints points(d);
  constexpr int64_t kScenes = 20000;
  const auto stream = SampleMany(*program, 11, kScenes, nullptr);
  const auto at_points = SampleMany(*program, 12, kScenes, &points);
  // Cube (x, y) on an 8 x 8 grid, tray 2 (x, y) on 6 x 6, camera height in 10 bins.
  std::map<int, int> cube[2], tray[2], camera[2];
  for (int which = 0; which < 2; ++which) {
    for (const auto& s : which == 0 ? stream : at_points) {
      if (which == 1) {
        ASSERT_EQ(s.coordinates.size(), static_cast<size_t>(d));
      }
      const auto& c = sampling::testing_checks::FindClass(s.scene, "Cube").p_WO;
      const auto& t = sampling::testing_checks::Find(s.scene, "tr_2").p_WO;
      const auto& k = sampling::testing_checks::FindClass(s.scene, "Camera").p_WO;
      ++cube[which][Bin(c.x(), -0.9, 0, 8) * 8 + Bin(c.y(), -0.4, 0.4, 8)];
      ++tray[which][Bin(t.x(), 0, 0.9, 6) * 6 + Bin(t.y(), -0.4, 0.4, 6)];
      ++camera[which][Bin(k.z(), 1.9, 2.1, 10)];
    }
  }
  ExpectSameDistribution(cube[0], cube[1], "cube position");
  ExpectSameDistribution(tray[0], tray[1], "tray position");
  ExpectSameDistribution(camera[0], camera[1], "camera height");
}

TEST(SceneCoordinatesTest, VaryingDrawsAndRejectionsStillSampleTheProgram) {
  // Random loop counts, a random branch, Normal, Discrete, require[p] and hard requirements.
  const auto program = CompileExample("constructs.prs");
  const auto coordinates = sampling::DescribeCoordinates(*program);
  ASSERT_GT(coordinates.size(), 10u);
  const IidPoints points(static_cast<int>(coordinates.size()));
  constexpr int64_t kScenes = 4000;
  const auto stream = SampleMany(*program, 21, kScenes, nullptr);
  const auto at_points = SampleMany(*program, 22, kScenes, &points);
  std::map<int, int> joint[2];
  for (int w = 0; w < 2; ++w) {
    for (const auto& s : w == 0 ? stream : at_points) {
      int n_gears = 0, n_bowls = 0;
      for (const auto& o : s.scene.objects) {
        n_gears += o.cls->name == "Gear";
        n_bowls += o.cls->name == "Bowl";
      }
      ++joint[w][n_gears * 2 + n_bowls];
    }
  }
  ExpectSameDistribution(joint[0], joint[1], "gears and bowls");
}

TEST(SceneCoordinatesTest, ASceneIsAFunctionOfItsPoint) {
  const auto program = CompileExample("table_cube.prs");
  const FixedPoint point({0.3, 0.2, 0.9, 0.6, 0.4, 0.5, 0.1, 0.95, 0.5, 0.5, 0.5});
  sampling::SampleOptions options;
  options.points = &point;
  // Every draw fits in the point, so the seed and index (the stream) change nothing.
  const auto a = sampling::SampleScene(*program, 1, 0, options);
  const auto b = sampling::SampleScene(*program, 2, 99, options);
  ASSERT_EQ(a.scene.objects.size(), b.scene.objects.size());
  for (size_t i = 0; i < a.scene.objects.size(); ++i) {
    EXPECT_EQ(a.scene.objects[i].p_WO, b.scene.objects[i].p_WO) << i;
  }
  EXPECT_EQ(a.coordinates,
            std::vector<double>({0.3, 0.2, 0.9, 0.6, 0.4, 0.5, 0.1, 0.95, 0.5, 0.5, 0.5}));
  // The cube's two coordinates move the cube within its tray: the far corner of its square
  // puts it far from the near corner.
  FixedPoint near({0.3, 0.2, 0.9, 0.6, 0.4, 0.5, 0.01, 0.01, 0.5, 0.5, 0.5});
  FixedPoint far({0.3, 0.2, 0.9, 0.6, 0.4, 0.5, 0.99, 0.99, 0.5, 0.5, 0.5});
  options.points = &near;
  const auto n = sampling::SampleScene(*program, 1, 0, options);
  options.points = &far;
  const auto f = sampling::SampleScene(*program, 1, 0, options);
  const auto& tray_n = sampling::testing_checks::Find(n.scene, "tr_1");
  const auto& tray_f = sampling::testing_checks::Find(f.scene, "tr_1");
  EXPECT_EQ(tray_n.p_WO, tray_f.p_WO);  // the tray's coordinates did not change
  const double moved = (sampling::testing_checks::FindClass(n.scene, "Cube").p_WO -
                        sampling::testing_checks::FindClass(f.scene, "Cube").p_WO)
                           .norm();
  EXPECT_GT(moved, 0.3);  // nearly the diagonal of the tray's 0.19 x 0.4 m free area
}

TEST(SceneCoordinatesTest, NamesComeFromTheProgram) {
  const auto program = CompileExample("table_cube.prs");
  const auto coordinates = sampling::DescribeCoordinates(*program);
  std::vector<std::string> names;
  for (const auto& c : coordinates) names.push_back(c.name);
  EXPECT_EQ(names[0], "tr_1.position piece");
  EXPECT_EQ(names[1], "tr_1.position[0]");
  EXPECT_EQ(names[6], "Cube#5.position[0]");
  EXPECT_EQ(names[7], "Cube#5.position[1]");
  EXPECT_EQ(coordinates[7].draw, "position");
  EXPECT_EQ(names[8].rfind("Camera#6.position (", 0), 0u) << names[8];
  const auto fixed =
      CompileOrDie("from model import *\nTable on V3D(0, 0, 0)\n", "examples/fixed.prs");
  EXPECT_TRUE(sampling::DescribeCoordinates(*fixed).empty());
  const auto widths = CompileOrDie(
      "from model import *\nt = Table on V3D(0, 0, 0), with width Range(1, 2)\n"
      "x = Normal(0, 1)\n",
      "examples/widths.prs");
  const auto described = sampling::DescribeCoordinates(*widths);
  ASSERT_EQ(described.size(), 2u);
  EXPECT_EQ(described[0].name, "t.width");
  EXPECT_EQ(described[0].draw, "Range");
  EXPECT_EQ(described[1].name, "Normal at widths.prs:3:5");
}

TEST(SceneCoordinatesTest, LongDrawSequencesAreCappedAndReadTheStreamPastThePoint) {
  const auto program = CompileOrDie(
      "total = 0\nfor i in range(3000):\n    total = total + Range(0, 1)\nrequire total > 0\n",
      "examples/long.prs");
  const auto coordinates = sampling::DescribeCoordinates(*program);
  ASSERT_EQ(coordinates.size(), static_cast<size_t>(sampling::kMaxCoordinates));
  const IidPoints points(sampling::kMaxCoordinates);
  sampling::SampleOptions options;
  options.points = &points;
  const auto scene = sampling::SampleScene(*program, 1, 0, options);
  EXPECT_EQ(scene.coordinates.size(), static_cast<size_t>(sampling::kMaxCoordinates));
}

TEST(SceneCoordinatesTest, DistributionsMapTheirCoordinateExactly) {
  // Range, Normal and TruncatedNormal at a point: the quantiles they should be.
  const auto program = CompileOrDie(
      "a = Range(2, 4)\nb = Normal(1, 2)\nc = TruncatedNormal(0, 1, 0.5, 3)\n"
      "d = DiscreteRange(1, 4)\nrequire a + b + c + d > -100\n",
      "examples/maps.prs");
  ASSERT_EQ(sampling::DescribeCoordinates(*program).size(), 4u);
  EXPECT_NEAR(geometry::MapUniform(0.25, 2, 4), 2.5, 1e-15);
  EXPECT_NEAR(geometry::MapNormal(0.975), 1.959963984540054, 1e-9);
  EXPECT_NEAR(geometry::MapNormal(0.5), 0.0, 1e-12);
  // Truncated to [0.5, 3]: the median solves Q(z) = (Q(0.5) + Q(3)) / 2.
  const double q = 0.5 * (0.5 * std::erfc(0.5 / std::sqrt(2)) + 0.5 * std::erfc(3 / std::sqrt(2)));
  const double median = geometry::MapTruncatedNormal(0.5, 0, 1, 0.5, 3);
  EXPECT_NEAR(0.5 * std::erfc(median / std::sqrt(2)), q, 1e-12);
  EXPECT_GE(geometry::MapTruncatedNormal(0.0, 0, 1, 0.5, 3), 0.5);
  EXPECT_LE(geometry::MapTruncatedNormal(0.9999999, 0, 1, 0.5, 3), 3.0);
  // Far in the lower tail (mirrored) and out of reach of doubles.
  const double low = geometry::MapTruncatedNormal(0.5, 0, 1, -12, -11);
  EXPECT_TRUE(low >= -12 && low <= -11) << low;
  EXPECT_TRUE(std::isnan(geometry::MapTruncatedNormal(0.5, 0, 1, 40, 41)));
  EXPECT_EQ(geometry::MapUniformInt(0.0, 1, 4), 1);
  EXPECT_EQ(geometry::MapUniformInt(0.2499, 1, 4), 1);
  EXPECT_EQ(geometry::MapUniformInt(0.25, 1, 4), 2);
  EXPECT_EQ(geometry::MapUniformInt(0.9999999999, 1, 4), 4);
}

}  // namespace
}  // namespace prs::search
