// `completely on X, facing toward Y` (and side specifiers with `facing toward`): the position is
// drawn from a yaw-independent superset, the orientation computed, and the attempt rejected when
// the turned box does not fit (spec §7). Checked with plain arithmetic: every corner on the
// support, every object facing its target, and the accepted positions distributed as a
// brute-force rejection sampler's (two-sample chi-square, fixed seeds).
#include <gtest/gtest.h>

#include <random>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using namespace testing_checks;

constexpr double kBoardWidth = 0.5, kBoardLength = 0.3, kBoardHeight = 0.02;
constexpr double kMugWidth = 0.12, kMugLength = 0.06, kMugHeight = 0.1;
const Vector3d kTarget(1.0, 0.6, 0.0);

const char* kPrologue = R"(
class Board:
    width: 0.5
    length: 0.3
    height: 0.02
class Mug:
    width: 0.12
    length: 0.06
    height: 0.1
board = Board at Vector3D(0, 0, 0.01)
)";

// +y (the object's forward) points horizontally at the target, and the object is upright.
void ExpectFacing(const SceneObject& o, const Vector3d& target) {
  const Matrix3d R = o.R_WO.toRotationMatrix();
  Vector3d to_target = target - o.p_WO;
  to_target.z() = 0;
  EXPECT_NEAR(R.col(1).dot(to_target.normalized()), 1.0, 1e-9);
  EXPECT_NEAR(R.col(2).z(), 1.0, 1e-9);
}

// A mug's centre (x, y) on the board, accepted by brute force: uniform over the whole board
// top, turned to face the target, kept when all four footprint corners are on the board.
std::vector<Vector3d> BruteForceCentres(int count) {
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> x(-kBoardWidth / 2, kBoardWidth / 2);
  std::uniform_real_distribution<double> y(-kBoardLength / 2, kBoardLength / 2);
  std::vector<Vector3d> accepted;
  while (static_cast<int>(accepted.size()) < count) {
    const Vector3d p(x(rng), y(rng), 0);
    const Vector3d forward = Vector3d(kTarget.x() - p.x(), kTarget.y() - p.y(), 0).normalized();
    const Vector3d right(forward.y(), -forward.x(), 0);
    bool inside = true;
    for (int sx : {-1, 1}) {
      for (int sy : {-1, 1}) {
        const Vector3d corner = p + right * (sx * kMugWidth / 2) + forward * (sy * kMugLength / 2);
        inside = inside && std::abs(corner.x()) <= kBoardWidth / 2 &&
                 std::abs(corner.y()) <= kBoardLength / 2;
      }
    }
    if (inside) accepted.push_back(p);
  }
  return accepted;
}

// Counts of points in a 5 x 5 grid over the board.
std::vector<double> GridCounts(const std::vector<Vector3d>& points) {
  std::vector<double> counts(25, 0);
  for (const Vector3d& p : points) {
    const int i = std::clamp(int((p.x() / kBoardWidth + 0.5) * 5), 0, 4);
    const int j = std::clamp(int((p.y() / kBoardLength + 0.5) * 5), 0, 4);
    counts[5 * i + j] += 1;
  }
  return counts;
}

TEST(OpenTurnTest, CompletelyOnFacingTowardIsExactAndUniform) {
  auto program = CompileOrDie(std::string(kPrologue) +
                              "m = Mug completely on board, facing toward Vector3D(1.0, 0.6, 0)\n");
  ASSERT_NE(program, nullptr);
  const int kScenes = 6000;
  std::vector<Vector3d> sampled;
  int64_t rejections = 0;
  SceneSampler sampler(*program);
  for (int i = 0; i < kScenes; ++i) {
    const SampledScene s = sampler.Sample(7, i);
    rejections += s.rejections.total;
    const SceneObject& board = Find(s.scene, "board");
    const SceneObject& mug = Find(s.scene, "m");
    ExpectCompletelyOn(mug, board);
    ExpectFacing(mug, kTarget);
    sampled.push_back(mug.p_WO);
    if (HasFailure()) FAIL() << "scene " << i;
  }
  // The superset is strictly larger than the valid set here, so some attempts are rejected,
  // each as containment by the mug's specifier.
  EXPECT_GT(rejections, 0);
  const std::vector<Vector3d> reference = BruteForceCentres(4 * kScenes);
  const std::vector<double> a = GridCounts(sampled), b = GridCounts(reference);
  // Two-sample chi-square for unequal sample sizes; empty cells in both samples carry nothing.
  const double n = kScenes, m = reference.size();
  double chi_square = 0;
  int cells = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    if (a[k] + b[k] == 0) continue;
    const double d = std::sqrt(m / n) * a[k] - std::sqrt(n / m) * b[k];
    chi_square += d * d / (a[k] + b[k]);
    ++cells;
  }
  ASSERT_GE(cells, 15);
  EXPECT_LT(chi_square,
            51.18);  // below the 0.999 quantile for 24 degrees of freedom (fewer cells: stricter)
  // The superset's edge is where a wrong erosion shows: the distance to the nearest board
  // edge, by a two-sample Kolmogorov-Smirnov test at alpha = 0.001.
  auto edge_distances = [](const std::vector<Vector3d>& points) {
    std::vector<double> d;
    for (const Vector3d& p : points) {
      d.push_back(std::min(kBoardWidth / 2 - std::abs(p.x()), kBoardLength / 2 - std::abs(p.y())));
    }
    return d;
  };
  EXPECT_LT(KolmogorovSmirnov(edge_distances(sampled), edge_distances(reference)),
            1.95 * std::sqrt((n + m) / (n * m)));
}

TEST(OpenTurnTest, RejectionsNameTheContainmentSpecifier) {
  auto program = CompileOrDie(std::string(kPrologue) +
                              "m = Mug completely on board, facing toward Vector3D(1.0, 0.6, 0)\n");
  ASSERT_NE(program, nullptr);
  RejectionCounts all;
  for (int i = 0; i < 300; ++i) all.Merge(SampleScene(*program, 3, i).rejections);
  ASSERT_GT(all.total, 0);
  EXPECT_EQ(all.by_kind[lang::RejectionKind::kContainment], all.total);
  EXPECT_EQ(all.by_culprit.begin()->first.second, "m 'completely on board'");
}

// Compiles the prologue plus `creation`, then calls `check` on scenes 0..499 of `seed`,
// stopping at the first scene that fails.
template <typename Check>
void CheckScenes(const std::string& creation, uint64_t seed, Check check) {
  auto program = CompileOrDie(std::string(kPrologue) + creation);
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  for (int i = 0; i < 500; ++i) {
    check(sampler.Sample(seed, i).scene);
    if (testing::Test::HasFailure()) FAIL() << "scene " << i;
  }
}

TEST(OpenTurnTest, SideSpecifierWithFacingTowardHoldsForTheTurnedBox) {
  CheckScenes(
      "m = Mug completely on board, ahead of Vector3D(0, 0, 0.02) by 0.01, "
      "facing toward Vector3D(-1.0, 2.0, 0)\n",
      5, [](const Scene& scene) {
        const SceneObject& mug = Find(scene, "m");
        ExpectCompletelyOn(mug, Find(scene, "board"));
        ExpectBeyond(mug, Vector3d(0, 0, 0.02), Vector3d::UnitY(), 0.01);
        ExpectFacing(mug, Vector3d(-1.0, 2.0, 0));
      });
}

// A yaw that reads the position (through a class default) takes the same path.
TEST(OpenTurnTest, YawFromThePositionWithCompletelyOn) {
  CheckScenes(
      "class Spinner(Mug):\n    yaw: self.position.x * 20\ns = Spinner completely on board\n", 9,
      [](const Scene& scene) {
        const SceneObject& spinner = Find(scene, "s");
        ExpectCompletelyOn(spinner, Find(scene, "board"));
        const Matrix3d R = spinner.R_WO.toRotationMatrix();
        const double yaw = std::atan2(-R(0, 1), R(1, 1));
        EXPECT_NEAR(std::remainder(yaw - spinner.p_WO.x() * 20, 2 * M_PI), 0, 1e-9);
      });
}

}  // namespace
}  // namespace prs::sampling
