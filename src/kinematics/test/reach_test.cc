// Reachable sets: points sampled from the cells pass an independent IK check (the Panda with
// the default, approach and margin options, a URDF arm, a chain without the symmetry), cells
// are disjoint, the set covers most of what is truly reachable, the cache round-trips and
// recovers from a corrupt file, and bad options throw.
#include "kinematics/reach.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "geometry/random.h"
#include "geometry/sampling.h"
#include "kinematics/panda.h"
#include "kinematics/urdf.h"

namespace prs::kinematics {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;
constexpr int kCheckRestarts = 30;

// The Panda's sets are computed once per test program and shared through the disk cache in
// the build tree (ctest runs each test in its own process).
std::shared_ptr<const ReachableSet> LoadPandaSet(const ReachOptions& options) {
  return LoadOrComputeReachableSet(MakePandaChain(), options, PRS_KINEMATICS_TEST_CACHE).set;
}

const ReachableSet& PandaDefault() {
  static const std::shared_ptr<const ReachableSet> set = LoadPandaSet({});
  return *set;
}

// Picks a cell by volume, then a uniform point in it.
class SetSampler {
 public:
  explicit SetSampler(const ReachableSet& set) : set_(set) {
    for (const auto& cell : set.cells_Base) samplers_.emplace_back(cell);
  }
  Eigen::Vector3d Sample(geometry::Rng& rng) const {
    double u = rng.Uniform(0, set_.volume_m3);
    for (size_t c = 0; c + 1 < samplers_.size(); ++c) {
      if (u < set_.cell_volumes_m3[c]) return samplers_[c].Sample(rng);
      u -= set_.cell_volumes_m3[c];
    }
    return samplers_.back().Sample(rng);
  }

 private:
  const ReachableSet& set_;
  std::vector<geometry::RegionSampler> samplers_;
};

int CountContainingCells(const ReachableSet& set, const Eigen::Vector3d& p) {
  int count = 0;
  for (const auto& cell : set.cells_Base) count += cell.Contains(p, -1e-9);
  return count;
}

// Samples `count` points of the set; returns those that fail the independent IK check.
std::vector<Eigen::Vector3d> FindUnreachableSamples(const Chain& chain, const ReachableSet& set,
                                                    Grasp grasp, int count, uint64_t seed) {
  SetSampler sampler(set);
  geometry::Rng rng(seed, 0);
  std::vector<Eigen::Vector3d> failed;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d p = sampler.Sample(rng);
    if (!IsReachable(chain, p, grasp, kCheckRestarts, i + 1)) failed.push_back(p);
  }
  return failed;
}

Chain LoadTestArm(const std::string& file) {
  std::ifstream in(std::string(PRS_KINEMATICS_TEST_DATA) + "/" + file);
  std::stringstream text;
  text << in.rdbuf();
  return LoadUrdfChain(text.str(), file);
}

std::string Describe(const std::vector<Eigen::Vector3d>& points) {
  std::ostringstream text;
  for (const auto& p : points) text << "(" << p.transpose() << ") ";
  return text.str();
}

TEST(ReachTest, PandaDefaultIsSmallAndPlausible) {
  const ReachableSet& set = PandaDefault();
  EXPECT_TRUE(set.stats.symmetric);
  EXPECT_GT(set.cells_Base.size(), 100u);
  EXPECT_LT(set.cells_Base.size(), 5000u);
  ASSERT_EQ(set.cell_volumes_m3.size(), set.cells_Base.size());
  double sum = 0;
  for (double v : set.cell_volumes_m3) sum += v;
  EXPECT_NEAR(sum, set.volume_m3, 1e-9);
  // The hand pointing down reaches a shell around the shoulder: well under the 0.855 m ball's
  // 2.6 m³, well over a tenth of it.
  EXPECT_GT(set.volume_m3, 0.3);
  EXPECT_LT(set.volume_m3, 2.6);
  // Straight below the flange's ready position is reachable; behind the base at 1.2 m is not.
  EXPECT_EQ(CountContainingCells(set, {0.5, 0.1, 0.2}), 1);
  EXPECT_EQ(CountContainingCells(set, {-1.2, 0, 0.3}), 0);
  EXPECT_EQ(CountContainingCells(set, {0, 0, 1.5}), 0);
}

TEST(ReachTest, PandaDefaultSampledPointsAreReachable) {
  const std::vector<Eigen::Vector3d> failed =
      FindUnreachableSamples(MakePandaChain(), PandaDefault(), Grasp::kDown, 1000, 1);
  EXPECT_TRUE(failed.empty()) << failed.size() << " of 1000 unreachable: " << Describe(failed);
}

TEST(ReachTest, PandaDefaultCellsAreDisjoint) {
  const ReachableSet& set = PandaDefault();
  SetSampler sampler(set);
  geometry::Rng rng(2, 0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d p = sampler.Sample(rng);
    ASSERT_EQ(CountContainingCells(set, p), 1) << p.transpose();
  }
}

TEST(ReachTest, PandaDefaultCoversMostOfTheTrulyReachablePoints) {
  const Chain chain = MakePandaChain();
  const ReachableSet& set = PandaDefault();
  geometry::Rng rng(3, 0);
  int reachable = 0, covered = 0;
  while (reachable < 300) {
    // A cylinder around the base holding everything the arm can reach pointing down.
    const Eigen::Vector3d p(rng.Uniform(-1.0, 1.0), rng.Uniform(-1.0, 1.0), rng.Uniform(-0.5, 1.2));
    if (p.head<2>().norm() > 1.0) continue;
    if (!IsReachable(chain, p, Grasp::kDown, 10, reachable + 1)) continue;
    ++reachable;
    covered += CountContainingCells(set, p) > 0;
  }
  EXPECT_GE(static_cast<double>(covered) / reachable, 0.9) << covered << " of " << reachable;
}

TEST(ReachTest, PandaApproachKeepsTheWayUpReachable) {
  ReachOptions options;
  options.approach_m = 0.15;
  options.resolution_m = 0.01;  // a coarser map: quicker, and the property is the same
  const std::shared_ptr<const ReachableSet> set = LoadPandaSet(options);
  EXPECT_LT(set->volume_m3, 0.9 * PandaDefault().volume_m3);
  const Chain chain = MakePandaChain();
  SetSampler sampler(*set);
  geometry::Rng rng(4, 0);
  for (int i = 0; i < 150; ++i) {
    const Eigen::Vector3d p = sampler.Sample(rng);
    for (double up : {0.0, 0.05, 0.1, 0.15}) {
      EXPECT_TRUE(
          IsReachable(chain, p + Eigen::Vector3d(0, 0, up), Grasp::kDown, kCheckRestarts, i + 1))
          << p.transpose() << " raised by " << up;
    }
  }
}

TEST(ReachTest, PandaMarginKeepsTheBallReachable) {
  ReachOptions options;
  options.margin_m = 0.05;
  options.resolution_m = 0.01;
  const std::shared_ptr<const ReachableSet> set = LoadPandaSet(options);
  EXPECT_LT(set->volume_m3, 0.8 * PandaDefault().volume_m3);
  const Chain chain = MakePandaChain();
  SetSampler sampler(*set);
  geometry::Rng rng(5, 0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p = sampler.Sample(rng);
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d d;
      do {
        d = {rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1)};
      } while (d.norm() > 1);
      if (k == 0) d = d.normalized();  // one point on the ball's surface
      const Eigen::Vector3d p_ball = p + 0.05 * d;
      EXPECT_TRUE(IsReachable(chain, p_ball, Grasp::kDown, kCheckRestarts, 100 * i + k))
          << p.transpose() << " + " << (0.05 * d).transpose();
    }
  }
}

TEST(ReachTest, UrdfSixJointArmSampledPointsAreReachable) {
  const Chain chain = LoadTestArm("six_joint_arm.urdf");
  ReachOptions options;
  options.resolution_m = 0.01;
  const std::shared_ptr<const ReachableSet> set =
      LoadOrComputeReachableSet(chain, options, PRS_KINEMATICS_TEST_CACHE).set;
  EXPECT_TRUE(set->stats.symmetric);
  EXPECT_GT(set->volume_m3, 0.3);
  const std::vector<Eigen::Vector3d> failed =
      FindUnreachableSamples(chain, *set, Grasp::kDown, 300, 6);
  EXPECT_TRUE(failed.empty()) << failed.size() << " of 300 unreachable: " << Describe(failed);
}

// A lift and a two-link horizontal arm (first joint prismatic: no rotational symmetry), so the
// 3-D grid of boxes. Its reachable set is an annulus r in [0.18, 0.55] m times the lift.
Chain MakeScara() {
  Chain chain;
  chain.name = "scara";
  chain.joints.push_back({"lift", JointType::kPrismatic, Eigen::Isometry3d::Identity(),
                          Eigen::Vector3d::UnitZ(), 0, 0.3});
  Joint shoulder{"shoulder",
                 JointType::kRevolute,
                 Eigen::Isometry3d::Identity(),
                 Eigen::Vector3d::UnitZ(),
                 -kPi,
                 kPi};
  shoulder.X_PJ.translation() << 0, 0, 0.2;
  Joint elbow{
      "elbow", JointType::kRevolute, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), -2.5,
      2.5};
  elbow.X_PJ.translation() << 0.3, 0, 0;
  chain.joints.push_back(shoulder);
  chain.joints.push_back(elbow);
  chain.X_LastTool.translation() << 0.25, 0, 0;
  return chain;
}

TEST(ReachTest, ChainWithoutSymmetryUsesBoxes) {
  const Chain chain = MakeScara();
  ReachOptions options;
  options.grasp = Grasp::kAny;
  options.resolution_m = 0.03;
  const ReachableSet set = ComputeReachableSet(chain, options);
  EXPECT_FALSE(set.stats.symmetric);
  const double inner = std::sqrt(0.3 * 0.3 + 0.25 * 0.25 + 2 * 0.3 * 0.25 * std::cos(2.5));
  const double exact = kPi * (0.55 * 0.55 - inner * inner) * 0.3;
  EXPECT_LT(set.volume_m3, exact);
  EXPECT_GT(set.volume_m3, 0.6 * exact);
  EXPECT_TRUE(FindUnreachableSamples(chain, set, Grasp::kAny, 300, 7).empty());
  SetSampler sampler(set);
  geometry::Rng rng(8, 0);
  for (int i = 0; i < 300; ++i) ASSERT_EQ(CountContainingCells(set, sampler.Sample(rng)), 1);
}

TEST(ReachTest, CacheRoundTripsExactlyAndRecoversFromACorruptFile) {
  const fs::path dir =
      fs::path(PRS_KINEMATICS_TEST_CACHE) / "round_trip" / std::to_string(::getpid());
  fs::remove_all(dir);
  const Chain chain = LoadTestArm("toy_arm.urdf");  // small: quick
  ReachOptions options;
  options.grasp = Grasp::kAny;
  options.resolution_m = 0.01;
  const ReachLoad first = LoadOrComputeReachableSet(chain, options, dir.string());
  EXPECT_FALSE(first.from_cache);
  EXPECT_EQ(first.warning, "");
  const ReachLoad second = LoadOrComputeReachableSet(chain, options, dir.string());
  ASSERT_TRUE(second.from_cache) << second.warning;
  ASSERT_EQ(second.set->cells_Base.size(), first.set->cells_Base.size());
  ASSERT_GT(first.set->cells_Base.size(), 0u);
  for (size_t c = 0; c < first.set->cells_Base.size(); ++c) {
    const auto& a = first.set->cells_Base[c].half_spaces();
    const auto& b = second.set->cells_Base[c].half_spaces();
    ASSERT_EQ(a.size(), b.size());
    for (size_t h = 0; h < a.size(); ++h) {
      EXPECT_EQ(a[h].normal, b[h].normal) << c;
      EXPECT_EQ(a[h].offset, b[h].offset) << c;
    }
    EXPECT_EQ(first.set->cell_volumes_m3[c], second.set->cell_volumes_m3[c]);
  }
  EXPECT_EQ(second.set->volume_m3, first.set->volume_m3);
  EXPECT_EQ(second.set->key, first.set->key);
  EXPECT_EQ(second.set->stats.nodes_tested, first.set->stats.nodes_tested);

  const fs::path file = dir / ("reach-" + CalcReachKey(chain, options) + ".txt");
  ASSERT_TRUE(fs::exists(file));
  {
    // The file's first lines (header and cell count), then a cell that does not parse.
    std::ifstream in(file);
    std::string header, count;
    std::getline(in, header);
    std::getline(in, count);
    in.close();
    std::ofstream(file, std::ios::trunc) << header << "\n" << count << "\ncell 6 oops\n";
  }
  const ReachLoad corrupt = LoadOrComputeReachableSet(chain, options, dir.string());
  EXPECT_FALSE(corrupt.from_cache);
  EXPECT_NE(corrupt.warning.find("ignored the reachable-set cache file"), std::string::npos)
      << corrupt.warning;
  EXPECT_NE(corrupt.warning.find("malformed"), std::string::npos) << corrupt.warning;
  EXPECT_EQ(corrupt.set->cells_Base.size(), first.set->cells_Base.size());
  EXPECT_TRUE(LoadOrComputeReachableSet(chain, options, dir.string()).from_cache);  // rewritten

  // Another arm's file under this key's name.
  ReachOptions other = options;
  other.grasp = Grasp::kDown;
  const fs::path other_file = dir / ("reach-" + CalcReachKey(chain, other) + ".txt");
  fs::copy_file(file, other_file, fs::copy_options::overwrite_existing);
  const ReachLoad mismatch = LoadOrComputeReachableSet(chain, other, dir.string());
  EXPECT_FALSE(mismatch.from_cache);
  EXPECT_NE(mismatch.warning.find("another arm"), std::string::npos) << mismatch.warning;
  fs::remove_all(dir);
}

TEST(ReachTest, UnwritableCacheWarnsAndStillComputes) {
  const fs::path blocker =
      fs::path(PRS_KINEMATICS_TEST_CACHE) / ("blocker-" + std::to_string(::getpid()));
  fs::create_directories(blocker.parent_path());
  std::ofstream(blocker) << "a file where the cache directory should be";
  ReachOptions options;
  options.grasp = Grasp::kAny;
  options.resolution_m = 0.02;
  const ReachLoad load =
      LoadOrComputeReachableSet(LoadTestArm("toy_arm.urdf"), options, (blocker / "cache").string());
  EXPECT_FALSE(load.from_cache);
  EXPECT_NE(load.warning.find("could not write"), std::string::npos) << load.warning;
  EXPECT_GT(load.set->cells_Base.size(), 0u);
  fs::remove(blocker);
}

TEST(ReachTest, KeyDependsOnTheArmAndTheOptions) {
  const Chain panda = MakePandaChain();
  const std::string key = CalcReachKey(panda, {});
  EXPECT_EQ(key.size(), 16u);
  EXPECT_EQ(key, CalcReachKey(MakePandaChain(), {}));
  ReachOptions side;
  side.grasp = Grasp::kSide;
  EXPECT_NE(key, CalcReachKey(panda, side));
  Chain moved = panda;
  moved.joints[3].upper -= 1e-12;
  EXPECT_NE(key, CalcReachKey(moved, {}));
}

TEST(ReachTest, BadOptionsThrow) {
  const Chain panda = MakePandaChain();
  ReachOptions o;
  o.margin_m = -0.01;
  EXPECT_THROW(ComputeReachableSet(panda, o), KinematicsError);
  o = {};
  o.grasp = Grasp::kAny;
  o.approach_m = 0.1;
  EXPECT_THROW(ComputeReachableSet(panda, o), KinematicsError);
  o = {};
  o.resolution_m = 0;
  EXPECT_THROW(ComputeReachableSet(panda, o), KinematicsError);
  o = {};
  o.max_sector_rad = 3;
  EXPECT_THROW(ComputeReachableSet(panda, o), KinematicsError);
  o = {};
  o.grasp = Grasp::kSide;
  o.approach_m = 0.1;
  EXPECT_THROW(ComputeReachableSet(MakeScara(), o), KinematicsError);
}

TEST(ReachTest, IsReachableAgreesWithForwardKinematics) {
  const Chain panda = MakePandaChain();
  // Where the ready pose puts the tool (pointing down) is reachable pointing down.
  const Eigen::Vector3d p_ready = CalcToolPose(panda, ToVector(kPandaReadyPose_rad)).translation();
  EXPECT_TRUE(IsReachable(panda, p_ready, Grasp::kDown, 0));
  EXPECT_TRUE(IsReachable(panda, Eigen::Vector3d(-0.3, -0.3, 0.4), Grasp::kAny, 5));
  EXPECT_FALSE(IsReachable(panda, Eigen::Vector3d(1.2, 0, 0.3), Grasp::kAny, 5));
  EXPECT_FALSE(IsReachable(panda, Eigen::Vector3d(0, 0, 0.5), Grasp::kSide, 5));  // on the axis
  // Pointing away from the base at shoulder height, beside the arm.
  EXPECT_TRUE(IsReachable(panda, Eigen::Vector3d(0.4, 0.5, 0.5), Grasp::kSide, 10));
}

}  // namespace
}  // namespace prs::kinematics
