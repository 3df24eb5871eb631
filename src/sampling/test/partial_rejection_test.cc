// --sampler partial-rejection: its scenes follow the program's law exactly (two-sample tests
// against whole-scene rejection, 3,000 scenes a side in the Release build: eight cubes in a
// bin; cubes and gears together; a fixed obstacle and a requirement), scenes are the same for
// any thread count, its Poisson counts are right, and programs outside its reach are refused
// with a located message.
#include "sampling/partial_rejection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geometry/random.h"
#include "sampling/gibbs.h"
#include "sampling/test/law_comparison.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using testing_checks::CompileOrDie;
using testing_law::BinProgram;
using testing_law::ChiSquareRatio;
using testing_law::Compare;
using testing_law::Comparison;
using testing_law::Cubes;
using testing_law::kLawScenes;
using testing_law::SampleAll;

SampleOptions PartialRejection() {
  SampleOptions options;
  options.partial_rejection = std::make_shared<PartialRejectionRequest>();
  return options;
}

void ExpectNoOverlaps(const std::vector<SampledScene>& scenes) {
  for (const SampledScene& s : scenes) {
    const auto moving = Cubes(s.scene);
    for (size_t a = 0; a < moving.size(); ++a) {
      for (size_t b = a + 1; b < moving.size(); ++b) {
        ASSERT_FALSE(lang::DoObjectsCollide(*moving[a], *moving[b], nullptr)) << s.index;
      }
    }
  }
}

// Both tests at level 0.001 on independent scenes: Kolmogorov-Smirnov on each statistic and
// chi-square on the first and last object's cell.
void ExpectSameLaw(const std::vector<SampledScene>& rejection,
                   const std::vector<SampledScene>& exact) {
  const Comparison c = Compare(rejection, exact, static_cast<double>(exact.size()));
  EXPECT_LT(c.ratio, 1) << c.worst;
  const double chi2 = ChiSquareRatio(rejection, exact);
  EXPECT_LT(chi2, 1);
  std::printf("KS / critical at 0.001: %.2f (%s); chi-square / critical: %.2f\n", c.ratio,
              c.worst.c_str(), chi2);
}

TEST(PartialRejectionTest, PoissonCountsHaveTheirMeanAndVariance) {
  for (const double mean : {0.7, 3.5, 150.0}) {
    geometry::Rng rng(11, 0);
    constexpr int kDraws = 20000;
    double sum = 0, sum2 = 0;
    int zeros = 0;
    for (int i = 0; i < kDraws; ++i) {
      const auto n = static_cast<double>(DrawPoisson(rng, mean));
      sum += n;
      sum2 += n * n;
      zeros += n == 0 ? 1 : 0;
    }
    const double m = sum / kDraws, var = sum2 / kDraws - m * m;
    // The sample mean's standard error is sqrt(mean / draws); the variance's about
    // mean * sqrt(2 / draws) (plus a kurtosis term of order mean / draws): five of each.
    EXPECT_NEAR(m, mean, 5 * std::sqrt(mean / kDraws)) << mean;
    EXPECT_NEAR(var, mean, 5 * (mean * std::sqrt(2.0 / kDraws) + std::sqrt(mean / kDraws))) << mean;
    const double p0 = std::exp(-mean);
    EXPECT_NEAR(zeros / double{kDraws}, p0, 5 * std::sqrt(p0 * (1 - p0) / kDraws) + 1e-12) << mean;
  }
}

TEST(PartialRejectionTest, EightCubesInABinFollowTheProgramsLaw) {
  const auto program = CompileOrDie(BinProgram(8));
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 1, kLawScenes, 2);
  SampleOptions partial = PartialRejection();
  const auto exact = SampleAll(*program, partial, 1, kLawScenes, 2);
  const PartialRejectionPlan plan = *partial.partial_rejection->plan();
  ASSERT_EQ(plan.sites.size(), 1u) << "one site, in the loop";
  EXPECT_EQ(plan.sites[0].ordinals.size(), 8u);
  EXPECT_EQ(plan.sites[0].coordinates, 3) << "yaw and position";
  EXPECT_EQ(plan.dimension, 24);
  EXPECT_GT(plan.count_acceptance, 0.05);
  ExpectSameLaw(rejection, exact);
  ExpectNoOverlaps(exact);
}

TEST(PartialRejectionTest, TwoKindsTogetherFollowTheProgramsLaw) {
  // Four cubes then two 10 cm gears (meshes) in a 0.6 x 0.5 m bin: two sites, each its own
  // Poisson process, the gears' collisions by FCL.
  const auto program = CompileOrDie(
      "from model import *\n"
      "bin = Table on V3D(0, 0, 0), with width 0.6, with length 0.5\n"
      "for i in range(4):\n"
      "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"
      "for i in range(2):\n"
      "    Gear completely on bin, with yaw Range(0, 2 * math.pi)\n");
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 3, kLawScenes, 2);
  SampleOptions partial = PartialRejection();
  const auto exact = SampleAll(*program, partial, 3, kLawScenes, 2);
  EXPECT_EQ(partial.partial_rejection->plan()->sites.size(), 2u);
  ExpectSameLaw(rejection, exact);
  ExpectNoOverlaps(exact);
}

TEST(PartialRejectionTest, ARequirementAndAFixedObstacleKeepTheLaw) {
  // A fixed robot base in the bin, turned, and the first two cubes at least 0.2 m apart: the
  // robot enters every probe, the requirement only the whole run.
  const auto program = CompileOrDie(testing_law::kObstacleAndRequirementProgram);
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 2, kLawScenes, 2);
  SampleOptions partial = PartialRejection();
  const auto exact = SampleAll(*program, partial, 2, kLawScenes, 2);
  EXPECT_EQ(partial.partial_rejection->plan()->sites.size(), 1u)
      << "a, b and the loop's cubes are made by the same text: one site of six objects";
  ExpectSameLaw(rejection, exact);
  testing_law::ExpectRequirementAndObstacleHold(exact);
  ExpectNoOverlaps(exact);
}

TEST(PartialRejectionTest, ScenesAreTheSameForAnyThreadCountAndReplayAtTheirCoordinates) {
  const auto program = CompileOrDie(BinProgram(10));
  ASSERT_TRUE(program);
  const auto one = SampleAll(*program, PartialRejection(), 7, 40, 1);
  const auto two = SampleAll(*program, PartialRejection(), 7, 40, 2, 0);
  const auto tail = SampleAll(*program, PartialRejection(), 7, 20, 2, 20);
  ASSERT_EQ(one.size(), 40u);
  for (size_t i = 0; i < one.size(); ++i) {
    const auto a = Cubes(one[i].scene), b = Cubes(two[i].scene);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k]->p_WO, b[k]->p_WO) << i;
    if (i >= 20) {
      ASSERT_EQ(Cubes(tail[i - 20].scene)[0]->p_WO, a[0]->p_WO) << i;
    }
    // The scene is the program run at its coordinates.
    lang::RunOptions run;
    run.coordinates = {one[i].coordinates.data(), static_cast<int>(one[i].coordinates.size())};
    geometry::Rng rng(0, 0);
    const lang::AttemptResult again = lang::RunAttempt(*program, rng, run);
    ASSERT_TRUE(std::holds_alternative<lang::Scene>(again)) << i;
    ASSERT_EQ(Cubes(std::get<lang::Scene>(again))[3]->p_WO, a[3]->p_WO) << i;
  }
}

TEST(PartialRejectionTest, ProbeRunsLeaveOutObjectsChecksAndTheRestOfTheProgram) {
  // Creation ordinals: 0 the bin, 1 to 3 the cubes, 4 the robot.
  const auto program = CompileOrDie(
      "from model import *\n"
      "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
      "for i in range(3):\n"
      "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"
      "Robot at V3D(1, 0, 0.85)\n"
      "require False\n");
  ASSERT_TRUE(program);
  const std::vector<double> u = {0.1, 0.5, 0.5, 0.1, 0.5, 0.5, 0.1, 0.5, 0.5};  // one pose, thrice
  auto run = [&](const lang::RunOptions& options) {
    geometry::Rng rng(1, 0);
    return lang::RunAttempt(*program, rng, options);
  };
  lang::RunOptions options;
  options.coordinates = {u.data(), static_cast<int>(u.size())};
  const auto whole = run(options);
  ASSERT_TRUE(std::holds_alternative<lang::Rejection>(whole));
  EXPECT_EQ(std::get<lang::Rejection>(whole).kind, lang::RejectionKind::kCollision);
  // Collisions between objects left out: the requirement rejects.
  options.check_collisions = false;
  const auto overlapping = run(options);
  ASSERT_TRUE(std::holds_alternative<lang::Rejection>(overlapping));
  EXPECT_EQ(std::get<lang::Rejection>(overlapping).kind, lang::RejectionKind::kRequirement);
  // And requirements too: every object is made.
  options.check_requirements = false;
  const auto all = run(options);
  ASSERT_TRUE(std::holds_alternative<lang::Scene>(all));
  EXPECT_EQ(std::get<lang::Scene>(all).objects.size(), 5u);
  // Two cubes left out: the first cube between the bin and the robot.
  options.check_collisions = true;
  const std::vector<bool> skip = {false, false, true, true, false};
  options.skip_objects = &skip;
  const auto probe = run(options);
  ASSERT_TRUE(std::holds_alternative<lang::Scene>(probe));
  const lang::Scene& probed = std::get<lang::Scene>(probe);
  ASSERT_EQ(probed.objects.size(), 3u);
  EXPECT_EQ(probed.objects[1].cls->name, "Cube");
  EXPECT_EQ(probed.objects[2].cls->name, "Robot");
  // Ended after the cube: no robot, and the requirement is never reached.
  options.stop_after_object = 1;
  options.check_requirements = true;
  const auto stopped = run(options);
  ASSERT_TRUE(std::holds_alternative<lang::Scene>(stopped));
  ASSERT_EQ(std::get<lang::Scene>(stopped).objects.size(), 2u);
  EXPECT_EQ(std::get<lang::Scene>(stopped).objects[1].p_WO, probed.objects[1].p_WO);
}

std::string RefusalOf(const std::string& text) {
  const auto program = CompileOrDie(text);
  if (!program) return "did not compile";
  try {
    SampleScene(*program, 1, 0, PartialRejection());
  } catch (const lang::ScenarioError& error) {
    return error.diagnostic().id + ": " + error.diagnostic().message;
  }
  return "sampled";
}

TEST(PartialRejectionTest, ProgramsOutsideItsReachAreRefused) {
  const std::string bin =
      "from model import *\n"
      "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n";
  // A cube on a tray that lies anywhere: the cube reads another random object.
  const std::string tray = RefusalOf(
      "from model import *\nt = Table on V3D(0, 0, 0)\ntray = Tray completely on t\n"
      "Cube completely on tray\n");
  EXPECT_NE(tray.find("partial-rejection-unsupported: --sampler partial-rejection cannot sample "
                      "this program: Cube#2 is not made from its own draws alone"),
            std::string::npos)
      << tray;
  // A draw of no object.
  const std::string free_draw = RefusalOf(bin + "x = Range(0, 1)\nCube completely on bin\n");
  EXPECT_NE(free_draw.find("draws numbers outside its random objects (Range at"), std::string::npos)
      << free_draw;
  // Line of sight depends on every object.
  const std::string sight = RefusalOf(bin +
                                      "cam = Camera at V3D(0, 0, 2), facing toward V3D(0, 0, 0)\n"
                                      "Cube completely on bin, visible from cam\n");
  EXPECT_NE(sight.find("a line-of-sight specifier"), std::string::npos) << sight;
  const std::string none = RefusalOf(bin);
  EXPECT_NE(none.find("it makes no random objects"), std::string::npos) << none;
  // Given points.
  const auto program = CompileOrDie(BinProgram(2));
  ASSERT_TRUE(program);
  SampleOptions options = PartialRejection();
  options.gibbs = std::make_shared<GibbsRequest>();
  EXPECT_THROW(SceneSampler(*program, options), lang::ScenarioError);
}

TEST(PartialRejectionTest, TooDenseClutterEndsWithAMessage) {
  // Forty cubes cannot lie in the bin's middle 0.2 x 0.2 m without touching often: a draw's
  // rounds run out, and the error says what to use instead.
  const auto program = CompileOrDie(BinProgram(40, "Cube", "0.25, with length 0.25"));
  ASSERT_TRUE(program);
  PartialRejectionSettings settings;
  settings.max_rounds = 50;
  SampleOptions options;
  options.partial_rejection = std::make_shared<PartialRejectionRequest>(settings);
  try {
    SampleScene(*program, 1, 0, options);
    FAIL() << "sampled";
  } catch (const lang::ScenarioError& error) {
    EXPECT_EQ(error.diagnostic().id, "partial-rejection-too-dense");
    EXPECT_NE(
        error.diagnostic().message.find("rounds of redrawing overlapping objects: 40 Cube at "),
        std::string::npos)
        << error.diagnostic().message;
    EXPECT_EQ(
        program->sources.CalcLineColumn(error.diagnostic().span.file, error.diagnostic().span.begin)
            .line,
        4u)
        << "at the cubes' creation";
    EXPECT_NE(error.diagnostic().notes.back().message.find("--sampler gibbs"), std::string::npos);
  }
}

}  // namespace
}  // namespace prs::sampling
