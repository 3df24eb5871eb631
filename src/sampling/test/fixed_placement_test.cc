// Fixed placements cut fixed obstacles out of an object's region instead of rejecting scenes.
// That must leave the law of scenes unchanged: compared here with naive mode (positions from
// the workspace, every relation and collision checked afterwards), an independent path, by
// two-sample Kolmogorov-Smirnov tests with fixed seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

constexpr char kTrayBesideRobot[] = R"(from model import *
t = Table at Vector3D(0, 0, 0.4)
r = Robot on (top back t) - Vector3D(0.4, 0, 0)
tr = Tray completely on t, ahead of r, left of t
)";

TEST(FixedPlacementTest, NoRejectionsAndNoCollisionInRegionMode) {
  auto program = CompileOrDie(kTrayBesideRobot);
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int near_robot = 0;
  for (uint64_t i = 0; i < 2000; ++i) {
    const SampledScene s = sampler.Sample(5, i);
    EXPECT_EQ(s.attempts, 1);
    const SceneObject& tr = Find(s.scene, "tr");
    const SceneObject& r = Find(s.scene, "r");
    EXPECT_FALSE(BoxesOverlapByPoints(tr, r));
    near_robot += std::abs(tr.p_WO.x() - r.p_WO.x()) < 0.2 && tr.p_WO.y() < 0;
  }
  EXPECT_GT(near_robot, 0);  // the cut leaves the room beside the robot usable
}

TEST(FixedPlacementTest, SameLawAsNaiveRejection) {
  auto program = CompileOrDie(kTrayBesideRobot);
  ASSERT_NE(program, nullptr);
  SampleOptions naive;
  naive.run.mode = lang::SamplingMode::kNaive;
  naive.max_attempts = 1'000'000;
  SceneSampler region_sampler(*program), naive_sampler(*program, naive);
  std::vector<double> region_x, region_y, naive_x, naive_y;
  for (uint64_t i = 0; i < 2000; ++i) {
    const Scene region_scene = region_sampler.Sample(11, i).scene;
    const SceneObject& a = Find(region_scene, "tr");
    region_x.push_back(a.p_WO.x());
    region_y.push_back(a.p_WO.y());
    const Scene naive_scene = naive_sampler.Sample(12, i).scene;
    const SceneObject& b = Find(naive_scene, "tr");
    naive_x.push_back(b.p_WO.x());
    naive_y.push_back(b.p_WO.y());
  }
  // Critical value of the two-sample test at alpha = 0.001 for n = m = 2000.
  const double critical = 1.949 * std::sqrt(2.0 / 2000);
  EXPECT_LT(KolmogorovSmirnov(region_x, naive_x), critical);
  EXPECT_LT(KolmogorovSmirnov(region_y, naive_y), critical);
}

TEST(FixedPlacementTest, ResultDoesNotDependOnTheCache) {
  auto program = CompileOrDie(kTrayBesideRobot);
  ASSERT_NE(program, nullptr);
  SceneSampler warm(*program);
  for (uint64_t i = 0; i < 50; ++i) {
    const Scene cached = warm.Sample(9, i).scene;
    const Scene fresh = SampleScene(*program, 9, i).scene;  // a new cache every call
    EXPECT_EQ(Find(cached, "tr").p_WO, Find(fresh, "tr").p_WO);
  }
}

TEST(FixedPlacementTest, RandomObstacleIsNotCutButStillAvoided) {
  // The first tray is random, so the second may not cut it out: collisions are rejected.
  auto program = CompileOrDie(R"(from model import *
t = Table at Vector3D(0, 0, 0.4)
a = Tray completely on t
b = Tray completely on t
)");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int64_t rejections = 0;
  for (uint64_t i = 0; i < 300; ++i) {
    const SampledScene s = sampler.Sample(2, i);
    rejections += s.rejections.total;
    EXPECT_FALSE(BoxesOverlapByPoints(Find(s.scene, "a"), Find(s.scene, "b")));
  }
  EXPECT_GT(rejections, 0);
}

}  // namespace
}  // namespace prs::sampling
