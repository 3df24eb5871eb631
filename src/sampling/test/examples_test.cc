// Every bundled example, sampled in region mode (and Table-Cube in naive mode too): each scene
// satisfies the relations its program states, checked with plain arithmetic independent of the
// sampler's regions; the cube on the tray is uniform relative to the tray (chi-square); and
// naive and region sampling agree in distribution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "sampling/gibbs.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

std::unique_ptr<lang::CompiledProgram> CompileExample(const std::string& name) {
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile(RepoPath("examples/" + name), {}, diagnostics);
  std::string rendered;
  for (const auto& d : diagnostics.diagnostics()) rendered += d.message + "\n";
  EXPECT_FALSE(diagnostics.has_errors()) << rendered;
  return diagnostics.has_errors() ? nullptr : std::move(program);
}

// The paper's baseline, with room for its rejections (about 85 per Table-Cube scene).
SampleOptions NaiveOptions() {
  SampleOptions naive;
  naive.run.mode = lang::SamplingMode::kNaive;
  naive.max_attempts = 100'000;
  return naive;
}

// The x and y of tr_1, tr_2 and the cube, appended to six lists.
void RecordTrayAndCubeXY(const Scene& scene, std::vector<std::vector<double>>& into) {
  const Vector3d p[] = {Find(scene, "tr_1").p_WO, Find(scene, "tr_2").p_WO,
                        FindClass(scene, "Cube").p_WO};
  for (int k = 0; k < 3; ++k) {
    into[2 * k].push_back(p[k].x());
    into[2 * k + 1].push_back(p[k].y());
  }
}

// The two-sample Kolmogorov-Smirnov critical value at alpha = 0.001 for n = m = SCENES (six
// tests per comparison, so a family-wise alpha under 0.006).
double KsCritical(int scenes) { return 1.949 * std::sqrt(2.0 / scenes); }

// What every scene of every example must satisfy: no two boxes overlap (unless an object allows
// collisions) and every box lies in the 3 m x 3 m x 3 m workspace of examples/model.prs.
void ExpectNoCollisionsAndInsideWorkspace(const Scene& scene) {
  for (size_t a = 0; a < scene.objects.size(); ++a) {
    for (const Vector3d& corner : Corners(scene.objects[a])) {
      EXPECT_LE(std::abs(corner.x()), 1.5 + kTol);
      EXPECT_LE(std::abs(corner.y()), 1.5 + kTol);
      EXPECT_GE(corner.z(), -kTol);
      EXPECT_LE(corner.z(), 3 + kTol);
    }
    for (size_t b = a + 1; b < scene.objects.size(); ++b) {
      if (scene.objects[a].allow_collisions || scene.objects[b].allow_collisions) continue;
      // Meshes may overlap each other's bounding boxes; mesh_test.cc checks them with FCL.
      if (scene.objects[a].mesh || scene.objects[b].mesh) continue;
      EXPECT_FALSE(BoxesOverlapByPoints(scene.objects[a], scene.objects[b]))
          << scene.objects[a].DisplayName(a) << " overlaps " << scene.objects[b].DisplayName(b);
    }
  }
}

// examples/table_cube.prs, the paper's Figure 1, statement by statement.
void ExpectTableCubeRelations(const Scene& scene) {
  ASSERT_EQ(scene.objects.size(), 7u);
  const SceneObject& t = Find(scene, "t");
  const SceneObject& r1 = Find(scene, "r1");
  const SceneObject& r2 = Find(scene, "r2");
  const SceneObject& tr_1 = Find(scene, "tr_1");
  const SceneObject& tr_2 = Find(scene, "tr_2");
  EXPECT_NEAR(t.p_WO.z(), t.dimensions.z() / 2, kTol);  // on V3D(0,0,0)
  for (const auto& [robot, x] : {std::pair{&r1, -0.4}, std::pair{&r2, 0.4}}) {
    EXPECT_NEAR(robot->p_WO.x(), x, kTol);  // on (top back t) -/+ V3D(0.4, 0, 0)
    EXPECT_NEAR(robot->p_WO.y(), -t.dimensions.y() / 2, kTol);
    EXPECT_NEAR(robot->p_WO.z(), t.dimensions.z() + robot->dimensions.z() / 2, kTol);
  }
  ExpectCompletelyOn(tr_1, t);
  ExpectCompletelyOn(tr_2, t);
  ExpectBeyond(tr_1, r1.p_WO, Vector3d::UnitY());  // ahead of r1
  ExpectBeyond(tr_2, r2.p_WO, Vector3d::UnitY());  // ahead of r2
  ExpectBeyond(tr_1, t.p_WO, -Vector3d::UnitX());  // left of t
  ExpectBeyond(tr_2, t.p_WO, Vector3d::UnitX());   // right of t
  const SceneObject& cube = FindClass(scene, "Cube");
  EXPECT_FALSE(cube.name.has_value());
  ExpectCompletelyOn(cube, tr_1);
  const SceneObject& camera = FindClass(scene, "Camera");
  EXPECT_LE(std::abs(camera.p_WO.x()), 0.1 + kTol);
  EXPECT_LE(std::abs(camera.p_WO.y()), 0.1 + kTol);
  EXPECT_GE(camera.p_WO.z(), 1.9 - kTol);
  EXPECT_LE(camera.p_WO.z(), 2.1 + kTol);
  EXPECT_TRUE((camera.R_WO * Vector3d::UnitY()).isApprox(-Vector3d::UnitZ(), 1e-9));  // facing
}

// examples/constructs.prs, the language tour.
void ExpectConstructsRelations(const Scene& scene) {
  const SceneObject& table = Find(scene, "table");
  const SceneObject& r = Find(scene, "r");
  EXPECT_NEAR(r.p_WO.x(), table.p_WO.x() - 0.4, kTol);
  const SceneObject& cup_1 = Find(scene, "cup_1");
  const SceneObject& cup_2 = Find(scene, "cup_2");
  ExpectCompletelyOn(cup_1, table);
  ExpectCompletelyOn(cup_2, table);
  EXPECT_NEAR(cup_1.p_WO.y(), cup_2.p_WO.y(), kTol);         // aligned with cup_1 by "y"
  ExpectBeyond(cup_1, table.p_WO, -Vector3d::UnitX(), 0.2);  // left of table by 0.2
  ExpectBeyond(cup_2, table.p_WO, Vector3d::UnitX());        // right of table
  const SceneObject& rotated = Find(scene, "rotated");
  ExpectCompletelyOn(rotated, table);
  ExpectBeyond(rotated, table.p_WO, Vector3d::UnitX(), 0.3);  // right of table by 0.3
  const SceneObject& c1 = Find(scene, "c1");
  const SceneObject& c2 = Find(scene, "c2");
  EXPECT_EQ(c1.dimensions.x(), 0.3);                          // with width 0.3
  ExpectBeyond(c1, Vector3d(0, 0, 2.5), -Vector3d::UnitZ());  // below V
  // in Cuboid(spot, ...): the centre (spec §5: position uniform over the region).
  EXPECT_LE(std::abs(c1.p_WO.x() - 1.1), 0.3 + kTol);
  EXPECT_LE(std::abs(c1.p_WO.y() - 1.0), 0.3 + kTol);
  EXPECT_LE(std::abs(c1.p_WO.z() - 0.0), 0.5 + kTol);
  ExpectBeyond(c2, c1.p_WO, Vector3d::UnitX(), 0.2);  // right of c1 by 0.2
  ExpectBeyond(c2, c1.p_WO, Vector3d::UnitZ(), 0.2);  // above c1 by 0.2
  ExpectBeyond(c2, c1.p_WO, Vector3d::UnitY(), 0.1);  // ahead of c1 by 0.1
  const SceneObject& cube_2 = Find(scene, "cube_2");
  EXPECT_NEAR(cube_2.p_WO.z(), c2.p_WO.z() + 0.05, kTol);  // a stack: cube_2 on c2
  const SceneObject& plate = Find(scene, "plate");
  EXPECT_NEAR(plate.p_WO.y(), table.p_WO.y() - 0.75, kTol);
  EXPECT_LT(cup_1.p_WO.x() + 0.04 + 0.01, cup_2.p_WO.x());  // require (right cup_1).x + 0.01 < ...
  EXPECT_GT((cup_1.p_WO - cup_2.p_WO).norm(), 0.1);         // require distance ... > 0.1
  const SceneObject& chair = Find(scene, "chair");
  EXPECT_TRUE((chair.R_WO * Vector3d::UnitY()).isApprox(Vector3d::UnitX(), 1e-9));
  EXPECT_NEAR(chair.p_WO.z(), chair.dimensions.z() / 2, kTol);  // on floor
  ExpectBeyond(chair, table.p_WO, -Vector3d::UnitY(), 0.3);     // behind table by 0.3
  int gears = 0;
  for (const SceneObject& o : scene.objects) {
    if (o.cls->name != "Gear") continue;
    ++gears;
    ExpectCompletelyOn(o, table);
    ExpectBeyond(o, r.p_WO, Vector3d::UnitY());  // ahead of r
  }
  EXPECT_GE(gears, 1);  // range(DiscreteRange(1, clutter + 1)) with clutter = 2
  EXPECT_LE(gears, 3);
}

// Every example file, including ones added later, compiles and keeps the scene-wide rules.
TEST(ExamplesTest, EveryExampleFileKeepsTheSceneWideRules) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(RepoPath("examples"))) {
    if (entry.path().extension() != ".prs" || entry.path().filename() == "model.prs") continue;
    ++files;
    auto program = CompileExample(entry.path().filename().string());
    ASSERT_NE(program, nullptr) << entry.path();
    // Clutter beyond whole-scene rejection is drawn by a Gibbs chain (sampling/gibbs.h).
    SampleOptions options;
    if (entry.path().filename() == "bin_clutter.prs")
      options.gibbs = std::make_shared<GibbsRequest>();
    SceneSampler sampler(*program, options);
    for (uint64_t i = 0; i < 50; ++i)
      ExpectNoCollisionsAndInsideWorkspace(sampler.Sample(4, i).scene);
  }
  EXPECT_GE(files, 3);
}

TEST(ExamplesTest, TableCubeHoldsInEverySceneWithoutRejection) {
  auto program = CompileExample("table_cube.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  for (uint64_t i = 0; i < 500; ++i) {
    const SampledScene sampled = sampler.Sample(1, i);
    EXPECT_EQ(sampled.attempts, 1);
    ExpectTableCubeRelations(sampled.scene);
    ExpectNoCollisionsAndInsideWorkspace(sampled.scene);
  }
}

TEST(ExamplesTest, TableCubeHoldsInEveryNaiveScene) {
  auto program = CompileExample("table_cube.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program, NaiveOptions());
  int64_t rejections = 0;
  for (uint64_t i = 0; i < 100; ++i) {
    const SampledScene sampled = sampler.Sample(1, i);
    rejections += sampled.rejections.total;
    ExpectTableCubeRelations(sampled.scene);
    ExpectNoCollisionsAndInsideWorkspace(sampled.scene);
  }
  EXPECT_GT(rejections, 100);  // the baseline does reject: about 80 per scene
}

TEST(ExamplesTest, ConstructsHoldsInEveryScene) {
  auto program = CompileExample("constructs.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  for (uint64_t i = 0; i < 200; ++i) {
    const Scene scene = sampler.Sample(3, i).scene;
    ExpectConstructsRelations(scene);
    ExpectNoCollisionsAndInsideWorkspace(scene);
  }
}

// The cube's centre relative to the tray, on a 5 x 5 grid of equal cells over the rectangle
// where the cube fits: uniform, by Pearson's chi-square test at alpha = 0.001.
TEST(ExamplesTest, CubeIsUniformOverTheTrayRelativeToTheTray) {
  auto program = CompileExample("table_cube.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  constexpr int kCells = 5, kScenes = 5000;
  std::vector<int> counts(kCells * kCells, 0);
  for (uint64_t i = 0; i < kScenes; ++i) {
    const Scene scene = sampler.Sample(2, i).scene;
    const SceneObject& tray = Find(scene, "tr_1");
    const SceneObject& cube = FindClass(scene, "Cube");
    const Vector3d p_TC = tray.R_WO.inverse() * (cube.p_WO - tray.p_WO);
    const Vector3d room = tray.dimensions - cube.dimensions;  // where the centre can be
    const int cx = static_cast<int>((p_TC.x() / room.x() + 0.5) * kCells);
    const int cy = static_cast<int>((p_TC.y() / room.y() + 0.5) * kCells);
    ASSERT_TRUE(cx >= 0 && cx < kCells && cy >= 0 && cy < kCells) << p_TC.transpose();
    ++counts[cy * kCells + cx];
  }
  const double expected = double(kScenes) / counts.size();
  double chi_square = 0;
  for (int c : counts) chi_square += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi_square, 51.18);  // the 0.999 quantile of chi-square with 24 degrees of freedom
}

// Both modes are exact, so the trays' and the cube's coordinates have the same law.
TEST(ExamplesTest, NaiveAndRegionSamplingAgreeInDistributionOnTableCube) {
  auto program = CompileExample("table_cube.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler region_sampler(*program), naive_sampler(*program, NaiveOptions());
  constexpr int kScenes = 400;
  std::vector<std::vector<double>> region(6), baseline(6);
  for (uint64_t i = 0; i < kScenes; ++i) {
    RecordTrayAndCubeXY(region_sampler.Sample(21, i).scene, region);
    RecordTrayAndCubeXY(naive_sampler.Sample(22, i).scene, baseline);
  }
  for (int k = 0; k < 6; ++k) {
    EXPECT_LT(KolmogorovSmirnov(region[k], baseline[k]), KsCritical(kScenes)) << k;
  }
}

// examples/table_cube_naive.prs states Figure 1 as requirements: its scenes keep every relation,
// naive mode counts its failed requirements as the paper does, and region mode as requirements.
TEST(ExamplesTest, TableCubeNaiveFileCountsRequirementsAsThePaperDoes) {
  auto program = CompileExample("table_cube_naive.prs");
  ASSERT_NE(program, nullptr);
  for (const bool naive : {true, false}) {
    SceneSampler sampler(*program, naive ? NaiveOptions() : SampleOptions{});
    RejectionCounts counts;
    for (uint64_t i = 0; i < 100; ++i) {
      const SampledScene sampled = sampler.Sample(1, i);
      counts.Merge(sampled.rejections);
      const Scene& scene = sampled.scene;
      const SceneObject& t = Find(scene, "t");
      const SceneObject& tr_1 = Find(scene, "tr_1");
      const SceneObject& tr_2 = Find(scene, "tr_2");
      ExpectCompletelyOn(tr_1, t);
      ExpectCompletelyOn(tr_2, t);
      ExpectBeyond(tr_1, Find(scene, "r1").p_WO, Vector3d::UnitY());
      ExpectBeyond(tr_2, Find(scene, "r2").p_WO, Vector3d::UnitY());
      ExpectBeyond(tr_1, t.p_WO, -Vector3d::UnitX());
      ExpectBeyond(tr_2, t.p_WO, Vector3d::UnitX());
      ExpectCompletelyOn(Find(scene, "cube"), tr_1);
      ExpectNoCollisionsAndInsideWorkspace(scene);
    }
    const auto count = [&](lang::RejectionKind kind) {
      auto it = counts.by_kind.find(kind);
      return it == counts.by_kind.end() ? int64_t{0} : it->second;
    };
    SCOPED_TRACE(naive ? "naive" : "region");
    EXPECT_GT(count(lang::RejectionKind::kCollision), 0);
    EXPECT_EQ(count(lang::RejectionKind::kRequirement) > 0, !naive);
    EXPECT_EQ(count(lang::RejectionKind::kRelativePosition) > 0, naive);
    EXPECT_EQ(count(lang::RejectionKind::kContainment) > 0, naive);
  }
}

// As in the paper's tool, naive mode checks relative-position specifiers before containment
// ones: a scene breaking both counts as relative position, whichever specifier is written first.
TEST(ExamplesTest, NaiveModeCountsRelativePositionBeforeContainment) {
  std::map<lang::RejectionKind, int64_t> by_order[2];
  const char* specifiers[2] = {"completely on t, left of t", "left of t, completely on t"};
  for (int order = 0; order < 2; ++order) {
    auto program = CompileOrDie(std::string("from model import *\nt = Table on floor\n"
                                            "c = Tray ") +
                                specifiers[order] + "\n");
    ASSERT_NE(program, nullptr);
    SceneSampler sampler(*program, NaiveOptions());
    for (uint64_t i = 0; i < 300; ++i) {
      for (const auto& [kind, n] : sampler.Sample(5, i).rejections.by_kind)
        by_order[order][kind] += n;
    }
  }
  EXPECT_EQ(by_order[0], by_order[1]);
  EXPECT_GT(by_order[0][lang::RejectionKind::kRelativePosition], 0);
  EXPECT_GT(by_order[0][lang::RejectionKind::kContainment], 0);
}

// The hand-written naive file and Figure 1 with the same objects give the same scenes in law.
TEST(ExamplesTest, TableCubeNaiveFileAgreesInDistributionWithFigureOne) {
  auto naive_file = CompileExample("table_cube_naive.prs");
  auto figure_one = CompileExample("table_cube_paper_model.prs");
  ASSERT_NE(naive_file, nullptr);
  ASSERT_NE(figure_one, nullptr);
  SceneSampler naive_sampler(*naive_file), figure_sampler(*figure_one);
  constexpr int kScenes = 400;
  std::vector<std::vector<double>> naive(6), figure(6);
  for (uint64_t i = 0; i < kScenes; ++i) {
    RecordTrayAndCubeXY(naive_sampler.Sample(31, i).scene, naive);
    RecordTrayAndCubeXY(figure_sampler.Sample(32, i).scene, figure);
  }
  for (int k = 0; k < 6; ++k) {
    EXPECT_LT(KolmogorovSmirnov(naive[k], figure[k]), KsCritical(kScenes)) << k;
  }
}

}  // namespace
}  // namespace prs::sampling
