// What makes the Gibbs sampler's runs cheap never changes a scene: the analysis that marks
// creation sites whose object is a function of its own draws (only those whose specifiers and
// defaults read fixed names), objects reused between runs (the same chains with and without),
// and the collision checks' grid (the same scenes and the same rejections, culprits included,
// for every example, with the grid from the first object on and with it off).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "lang/run_cache.h"
#include "sampling/gibbs.h"
#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using testing_checks::CompileOrDie;
using testing_checks::Fingerprint;
using testing_checks::RepoPath;

// The own-draws flag of the site whose class name is on `line`.
std::map<int, bool> OwnDrawFlags(const lang::CompiledProgram& program) {
  std::map<int, bool> flags;
  for (const auto& [create, plan] : program.plans) {
    const auto where =
        program.sources.CalcLineColumn(create->class_name.span.file, create->class_name.span.begin);
    flags[where.line] = plan.own_draws_only;
  }
  return flags;
}

TEST(ReuseTest, OnlySitesThatReadFixedNamesAreOwnDraws) {
  const auto program = CompileOrDie(
      "from model import *\n"                                           // 1
      "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"  // 2
      "tray = Tray completely on bin, with yaw Range(0, 1)\n"           // 3
      "for i in range(3):\n"                                            // 4
      "    Cube completely on bin, with yaw Range(0, 6)\n"              // 5 yes
      "    Cube completely on tray\n"                                   // 6 no: tray varies
      "    Cube at V3D(i * 0.1, 0, 0.85)\n"                             // 7 no: i
      "def make():\n"                                                   // 8
      "    return Cube completely on bin\n"                             // 9 no: a function
      "make()\n"                                                        // 10
      "Cup completely on bin, facing toward tray\n"                     // 11 no: tray
      "Cup in Cuboid(V3D(0, 0, 1), V3D(0, 0, 0), 0.5, 0.5, 0.5)\n"      // 12 yes
      "Cup completely on bin, with color Options(['red', 'blue'])\n"    // 13 yes
      "Cup completely on bin, visible from tray\n"                      // 14 no: a view
      "spot = V3D(0.1, 0, 0.85)\n"                                      // 15
      "Cube at spot\n"                                                  // 16 no: rebound later
      "spot = V3D(0.2, 0, 0.85)\n"                                      // 17
      "Cube at spot\n"                                                  // 18 yes: fixed from here
      "for i in range(2):\n"                                            // 19
      "    place = V3D(i * 0.1, 0, 0.85)\n"                             // 20
      "Cube at place\n");                                               // 21 no: bound in a loop
  ASSERT_TRUE(program);
  const std::map<int, bool> flags = OwnDrawFlags(*program);
  const std::map<int, bool> expected = {{3, true},   {5, true},   {6, false}, {7, false},
                                        {9, false},  {11, false}, {12, true}, {13, true},
                                        {14, false}, {16, false}, {18, true}, {21, false}};
  for (const auto& [line, own] : expected) {
    ASSERT_TRUE(flags.count(line)) << "no site on line " << line;
    EXPECT_EQ(flags.at(line), own) << "line " << line;
  }
  // A workspace drawn anew in every scene bounds every position region: no site qualifies.
  const auto moving = CompileOrDie(
      "from model import *\n"
      "workspace = Cuboid(V3D((0, 0.5), 0, 1.5), V3D(0, 0, 0), 5, 5, 3)\n"
      "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
      "Cube completely on bin, with yaw Range(0, 6)\n");
  ASSERT_TRUE(moving);
  EXPECT_FALSE(OwnDrawFlags(*moving).at(4));
  // A fixed workspace of the program's own after `from model import *` (which binds one too):
  // sites after it qualify, a site before it does not.
  const auto widened = CompileOrDie(
      "from model import *\n"
      "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
      "Cube completely on bin, with yaw Range(0, 6)\n"
      "workspace = Cuboid(V3D(0, 0, 1.5), V3D(0, 0, 0), 5, 5, 3)\n"
      "Cube completely on bin, with yaw Range(0, 6)\n");
  ASSERT_TRUE(widened);
  EXPECT_FALSE(OwnDrawFlags(*widened).at(3));
  EXPECT_TRUE(OwnDrawFlags(*widened).at(5));
}

// The objects of qualifying sites are kept for the next run (and not those of others), so
// that reuse happens at all: the chains' equality below holds without it too.
TEST(ReuseTest, ARunKeepsTheObjectsOfQualifyingSites) {
  const auto program = CompileOrDie(
      "from model import *\n"
      "workspace = Cuboid(V3D(0, 0, 1.5), V3D(0, 0, 0), 5, 5, 3)\n"
      "t = Table on V3D(0, 0, 0), with width 4, with length 4\n"
      "for i in range(6):\n"
      "    Cube completely on t, with yaw Range(0, 2 * math.pi)\n"
      "    Cube at V3D(-1.5 + 0.5 * i, -1.5, 0.85)\n");  // reads i: not kept
  ASSERT_TRUE(program);
  std::vector<double> u(64);
  for (size_t i = 0; i < u.size(); ++i) u[i] = std::fmod(0.137 + 0.618 * double(i), 1.0);
  lang::RunCache cache;
  lang::RunOptions options;
  options.cache = &cache;
  options.coordinates.values = u.data();
  options.coordinates.size = static_cast<int>(u.size());
  options.reuse_objects = true;
  geometry::Rng rng(1);
  const lang::AttemptResult first = lang::RunAttempt(*program, rng, options);
  ASSERT_TRUE(std::holds_alternative<lang::Scene>(first));
  EXPECT_EQ(cache.reusable.size(), 7u);  // the table (no draws) and the six drawn cubes
  for (const auto& [key, kept] : cache.reusable) EXPECT_TRUE(key.first->own_draws_only);
  geometry::Rng again(1);
  const lang::AttemptResult second = lang::RunAttempt(*program, again, options);
  ASSERT_TRUE(std::holds_alternative<lang::Scene>(second));
  sampling::SampledScene a, b;
  a.scene = std::get<lang::Scene>(first);
  b.scene = std::get<lang::Scene>(second);
  EXPECT_EQ(Fingerprint(a), Fingerprint(b));
}

TEST(ReuseTest, ReusedObjectsGiveTheSameChains) {
  for (const std::string& program_text :
       {std::string("from model import *\n"
                    "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
                    "for i in range(10):\n"
                    "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n"),
        // Named objects, a requirement, sites that cannot be reused beside ones that can.
        std::string("from model import *\n"
                    "bin = Table on V3D(0, 0, 0), with width 0.6, with length 0.5\n"
                    "tray = Tray completely on bin, with yaw Range(0, 0.5)\n"
                    "a = Cube completely on bin, with yaw Range(0, 6)\n"
                    "for i in range(4):\n"
                    "    Cube completely on bin, with yaw Range(0, 6)\n"
                    "    Gear completely on tray\n"
                    "require (distance from a to tray) > 0.1\n")}) {
    const auto program = CompileOrDie(program_text);
    ASSERT_TRUE(program);
    GibbsSettings settings;
    settings.scenes_per_chain = 8;
    GibbsSettings plain_settings = settings;
    plain_settings.reuse_objects = false;
    SampleOptions reusing, plain;
    reusing.gibbs = std::make_shared<GibbsRequest>(settings);
    plain.gibbs = std::make_shared<GibbsRequest>(plain_settings);
    SceneSampler a(*program, reusing), b(*program, plain);
    for (uint64_t i = 0; i < 24; ++i) {
      ASSERT_EQ(Fingerprint(a.Sample(3, i)), Fingerprint(b.Sample(3, i))) << i;
    }
  }
}

TEST(ReuseTest, TheCollisionGridChangesNoSceneAndNoRejection) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(RepoPath("examples"))) {
    if (entry.path().extension() != ".prs" || entry.path().filename() == "model.prs") continue;
    lang::DiagnosticEngine diagnostics;
    auto program = lang::CompileFile(entry.path().string(), {}, diagnostics);
    ASSERT_TRUE(program) << entry.path();
    ++files;
    SampleOptions grid, none;
    if (entry.path().filename() == "bin_clutter.prs") {
      grid.gibbs = std::make_shared<GibbsRequest>();
      none.gibbs = std::make_shared<GibbsRequest>();
    }
    grid.run.collision_grid_from = 1;
    none.run.collision_grid_from = 1 << 30;
    SceneSampler with_grid(*program, grid), without(*program, none);
    for (uint64_t i = 0; i < 10; ++i) {
      ASSERT_EQ(Fingerprint(with_grid.Sample(2, i)), Fingerprint(without.Sample(2, i)))
          << entry.path() << " scene " << i;
    }
  }
  EXPECT_GE(files, 8);
  // Sixty cubes on a 1.2 x 1 m table: collisions are common, and none is missed.
  const auto crowded = CompileOrDie(
      "from model import *\n"
      "t = Table on V3D(0, 0, 0), with width 1.2, with length 1\n"
      "for i in range(60):\n"
      "    Cube completely on t, with yaw Range(0, 2 * math.pi)\n");
  ASSERT_TRUE(crowded);
  SampleOptions grid = {}, none = {};
  grid.gibbs = std::make_shared<GibbsRequest>();
  none.gibbs = std::make_shared<GibbsRequest>();
  grid.run.collision_grid_from = 1;
  none.run.collision_grid_from = 1 << 30;
  SceneSampler with_grid(*crowded, grid), without(*crowded, none);
  for (uint64_t i = 0; i < 4; ++i) {
    const SampledScene s = with_grid.Sample(1, i);
    ASSERT_EQ(Fingerprint(s), Fingerprint(without.Sample(1, i))) << i;
    for (size_t a = 0; a < s.scene.objects.size(); ++a) {
      for (size_t b = a + 1; b < s.scene.objects.size(); ++b) {
        if (s.scene.objects[a].cls->name != "Cube" || s.scene.objects[b].cls->name != "Cube")
          continue;
        ASSERT_FALSE(testing_checks::BoxesOverlapByPoints(s.scene.objects[a], s.scene.objects[b]));
      }
    }
  }
}

}  // namespace
}  // namespace prs::sampling
