// --sampler gibbs: its scenes follow the program's law (two-sample tests against whole-scene
// rejection on instances small enough for rejection: cubes in a bin, with and without a
// requirement and a fixed obstacle), the tests can tell a wrong law (the chain's start, a
// sequential placement, fails them), scenes are the same for any thread count and order, the
// autocorrelation estimator is right on a series of known correlation, and programs it cannot
// sample are refused with a message.
#include "sampling/gibbs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "geometry/random.h"
#include "sampling/batch.h"
#include "sampling/test/law_comparison.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using testing_checks::CompileOrDie;
using testing_law::BinProgram;
using testing_law::Compare;
using testing_law::Comparison;
using testing_law::Cubes;
using testing_law::SampleAll;

SampleOptions Gibbs(GibbsSettings settings = {}) {
  SampleOptions options;
  options.gibbs = std::make_shared<GibbsRequest>(settings);
  return options;
}

TEST(GibbsTest, EightCubesInABinFollowTheProgramsLaw) {
  const auto program = CompileOrDie(BinProgram(8));
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 1, 3000, 2);
  SampleOptions gibbs = Gibbs();
  const auto chain = SampleAll(*program, gibbs, 1, 3000, 2);
  const GibbsPlan plan = *gibbs.gibbs->plan();
  EXPECT_EQ(plan.blocks, 8) << "one block per cube (its yaw and position)";
  EXPECT_EQ(plan.dimension, 24);
  EXPECT_GE(plan.thin_sweeps, 1);
  EXPECT_LT(plan.tau_sweeps, 5) << "8 cubes cover a tenth of the bin: the chain mixes fast";
  const Comparison c = Compare(rejection, chain, plan.CalcEffectiveScenes(3000));
  EXPECT_LT(c.ratio, 1) << c.worst;
  std::printf("KS / critical at 0.001: %.2f (%s)\n", c.ratio, c.worst.c_str());
  for (const SampledScene& s : chain) {
    const auto cubes = Cubes(s.scene);
    ASSERT_EQ(cubes.size(), 8u);
    for (size_t a = 0; a < cubes.size(); ++a) {
      for (size_t b = a + 1; b < cubes.size(); ++b) {
        ASSERT_FALSE(testing_checks::BoxesOverlapByPoints(*cubes[a], *cubes[b])) << s.index;
      }
    }
  }
}

TEST(GibbsTest, ARequirementAndAFixedObstacleKeepTheLaw) {
  // A fixed robot base in the bin, turned, and the first two cubes at least 0.2 m apart.
  const auto program = CompileOrDie(testing_law::kObstacleAndRequirementProgram);
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 2, 3000, 2);
  SampleOptions gibbs = Gibbs();
  const auto chain = SampleAll(*program, gibbs, 2, 3000, 2);
  const GibbsPlan plan = *gibbs.gibbs->plan();
  const Comparison c = Compare(rejection, chain, plan.CalcEffectiveScenes(3000));
  EXPECT_LT(c.ratio, 1) << c.worst;
  std::printf("KS / critical at 0.001: %.2f (%s)\n", c.ratio, c.worst.c_str());
  testing_law::ExpectRequirementAndObstacleHold(chain);
}

TEST(GibbsTest, TheStartAloneFailsTheComparison) {
  // Without burn-in and with one scene a chain, every scene is a sequential placement: each
  // object uniform where the ones before it left room. That is another law, and the comparison
  // must see it, or passing it would mean nothing. (Ten cubes in the bin are too sparse for
  // 3,000 scenes to tell the two apart; three 10 cm gears in a 0.4 x 0.3 m bin are not.)
  const auto program = CompileOrDie(BinProgram(3, "Gear", "0.4, with length 0.3"));
  ASSERT_TRUE(program);
  const auto rejection = SampleAll(*program, {}, 1, 3000, 2);
  GibbsSettings settings;
  settings.burn_in_sweeps = 0;
  settings.scenes_per_chain = 1;
  const auto start = SampleAll(*program, Gibbs(settings), 1, 3000, 2);
  const Comparison c = Compare(rejection, start, 3000);
  EXPECT_GT(c.ratio, 1) << c.worst;
  // The chain itself passes on the same instance.
  SampleOptions gibbs = Gibbs();
  const auto chain = SampleAll(*program, gibbs, 1, 3000, 2);
  const Comparison chain_c =
      Compare(rejection, chain, gibbs.gibbs->plan()->CalcEffectiveScenes(3000));
  EXPECT_LT(chain_c.ratio, 1) << chain_c.worst;
  std::printf("KS / critical at 0.001: sequential placement %.2f (%s), chain %.2f (%s)\n", c.ratio,
              c.worst.c_str(), chain_c.ratio, chain_c.worst.c_str());
}

TEST(GibbsTest, SameScenesForAnyThreadCountAndRange) {
  const auto program = CompileOrDie(BinProgram(10));
  ASSERT_TRUE(program);
  GibbsSettings settings;
  settings.scenes_per_chain = 8;
  const auto one = SampleAll(*program, Gibbs(settings), 5, 40, 1);
  const auto two = SampleAll(*program, Gibbs(settings), 5, 40, 2);
  const auto tail = SampleAll(*program, Gibbs(settings), 5, 19, 2, 21);
  ASSERT_EQ(one.size(), 40u);
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].coordinates, two[i].coordinates) << i;
    EXPECT_EQ(one[i].attempts, two[i].attempts) << i;
    if (i >= 21) {
      EXPECT_EQ(one[i].coordinates, tail[i - 21].coordinates) << i;
    }
  }
  EXPECT_NE(one[0].coordinates, one[1].coordinates) << "consecutive scenes move";
}

TEST(GibbsTest, AutocorrelationTimeOfAKnownSeries) {
  // AR(1) with rho = 0.8: tau = (1 + rho) / (1 - rho) = 9.
  geometry::Rng rng(3);
  std::vector<double> series(50'000);
  double x = 0;
  for (double& v : series) {
    x = 0.8 * x + rng.Normal();
    v = x;
  }
  EXPECT_NEAR(CalcAutocorrelationTime(series), 9, 1.0);
  std::vector<double> noise(50'000);
  for (double& v : noise) v = rng.Normal();
  EXPECT_NEAR(CalcAutocorrelationTime(noise), 1, 0.1);
  EXPECT_EQ(CalcAutocorrelationTime(std::vector<double>(100, 2.0)), 1);
}

TEST(GibbsTest, ProgramsItCannotSampleAreRefused) {
  const auto expect_refused = [](const lang::CompiledProgram& program, SampleOptions options,
                                 const std::string& words) {
    try {
      SampleScene(program, 0, 0, options);
      ADD_FAILURE() << "accepted";
    } catch (const lang::ScenarioError& e) {
      EXPECT_EQ(e.diagnostic().id, "gibbs-unsupported");
      EXPECT_NE(e.diagnostic().message.find(words), std::string::npos) << e.diagnostic().message;
    }
  };
  // A random number of cubes: a move may draw more numbers than the scene has coordinates.
  const auto varying = CompileOrDie(
      "from model import *\n"
      "bin = Table on V3D(0, 0, 0)\n"
      "for i in range(DiscreteRange(1, 6)):\n"
      "    Cube completely on bin\n");
  ASSERT_TRUE(varying);
  expect_refused(*varying, Gibbs(), "drew more numbers");
  // Located at the count, the draw whose redraw changed how many numbers a run draws (not at
  // the file's start).
  try {
    SampleScene(*varying, 0, 0, Gibbs());
  } catch (const lang::ScenarioError& e) {
    const lang::Diagnostic& d = e.diagnostic();
    ASSERT_TRUE(d.has_span);
    const lang::LineColumn at = varying->sources.CalcLineColumn(d.span.file, d.span.begin);
    EXPECT_EQ(at.line, 3u);
    EXPECT_EQ(at.column, 16u);
    EXPECT_EQ(varying->sources.text(d.span.file).substr(d.span.begin, d.span.end - d.span.begin),
              "DiscreteRange(1, 6)");
    EXPECT_NE(d.message.find("when DiscreteRange at "), std::string::npos) << d.message;
  }

  struct OnePoint : AttemptPoints {
    int dimension() const override { return 1; }
    bool Point(uint64_t, uint64_t, int64_t, double* u) const override {
      u[0] = 0.5;
      return true;
    }
  } point;
  const auto bin = CompileOrDie(BinProgram(2));
  SampleOptions at_points = Gibbs();
  at_points.points = &point;
  expect_refused(*bin, at_points, "cannot draw scenes at given points");

  // Two cubes that never fit side by side: the chain finds no start, and says so with the
  // rejection sampler's counts and culprit.
  const auto cramped = CompileOrDie(BinProgram(2, "Cube", "0.07, with length 0.07"));
  SampleOptions few = Gibbs();
  few.max_attempts = 300;
  try {
    SampleScene(*cramped, 0, 0, few);
    ADD_FAILURE() << "a start was found";
  } catch (const lang::ScenarioError& e) {
    EXPECT_EQ(e.diagnostic().id, "sampling-failed");
    EXPECT_NE(
        e.diagnostic().message.find("found no starting scene for its chain in 300 program runs"),
        std::string::npos)
        << e.diagnostic().message;
    EXPECT_NE(e.diagnostic().message.find("collision"), std::string::npos)
        << e.diagnostic().message;
  }
}

}  // namespace
}  // namespace prs::sampling
