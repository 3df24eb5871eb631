// End-to-end scenario tests: programs compile, sample, and every relation they state holds on
// the sampled values, checked here with plain arithmetic independent of the sampler's regions.
#include <gtest/gtest.h>

#include <set>

#include "sampling/test/scene_checks.h"

namespace prs::sampling {
namespace {

using Eigen::Vector3d;
using lang::Scene;
using lang::SceneObject;
using namespace testing_checks;

TEST(ScenarioTest, RotatedTrayCompletelyOnTableNeverOverhangs) {
  auto program = CompileOrDie(R"(from model import *
table = Table on floor
tray = Tray completely on table, facing V3D(1, 1, 0)
)");
  ASSERT_NE(program, nullptr);
  for (uint64_t i = 0; i < 1000; ++i) {
    const Scene scene = SampleScene(*program, 7, i).scene;
    const SceneObject& tray = Find(scene, "tray");
    const SceneObject& table = Find(scene, "table");
    EXPECT_TRUE((tray.R_WO * Vector3d::UnitY()).isApprox(Vector3d(1, 1, 0).normalized(), 1e-9));
    ExpectCompletelyOn(tray, table);
  }
}

// A scene test handed down from above (as --stable's physics check is) rejects attempts like
// any other reason: the accepted scenes are the program's conditioned on passing it, each
// rejection counted under its kind and culprit, and the same scene for the same (seed, index).
TEST(ScenarioTest, ASceneTestConditionsTheScenesAndCountsItsRejections) {
  auto program =
      CompileOrDie("from model import *\nt = Table on floor\nc = Cube completely on t\n");
  ASSERT_NE(program, nullptr);
  SampleOptions options;
  options.accept = [](const Scene& scene) -> std::optional<lang::Rejection> {
    if (Find(scene, "c").p_WO.x() >= 0) return std::nullopt;
    return lang::Rejection{lang::RejectionKind::kUnstable, "c", {}, "c is left of 0", false};
  };
  int64_t rejected = 0, attempts = 0;
  for (uint64_t i = 0; i < 400; ++i) {
    const SampledScene s = SampleScene(*program, 3, i, options);
    EXPECT_GE(Find(s.scene, "c").p_WO.x(), 0);
    rejected += s.rejections.by_kind.count(lang::RejectionKind::kUnstable)
                    ? s.rejections.by_kind.at(lang::RejectionKind::kUnstable)
                    : 0;
    attempts += s.attempts;
    EXPECT_EQ(s.rejections.total, s.attempts - 1);
    if (s.rejections.total > 0) {
      EXPECT_EQ(s.rejections.by_culprit.begin()->first.second, "c");
    }
    if (i == 17) {  // the same scene again
      const Scene again = SampleScene(*program, 3, i, options).scene;
      EXPECT_EQ(Find(again, "c").p_WO, Find(s.scene, "c").p_WO);
    }
  }
  // Half the table is left of 0: about one rejection per accepted scene.
  EXPECT_NEAR(double(rejected) / 400, 1.0, 0.25);
  EXPECT_EQ(rejected, attempts - 400);
}

// A test that fails a program which draws nothing fails every attempt the same way: said at
// once, not after --max-attempts attempts.
TEST(ScenarioTest, ASceneTestFailingAFixedProgramFailsAtOnce) {
  auto program = CompileOrDie("from model import *\nc = Cube at V3D(0, 0, 1)\n");
  ASSERT_NE(program, nullptr);
  SampleOptions options;
  int calls = 0;
  options.accept = [&calls](const Scene&) -> std::optional<lang::Rejection> {
    ++calls;
    return lang::Rejection{lang::RejectionKind::kUnstable, "c", {}, "c fell 0.97 m", false};
  };
  try {
    SampleScene(*program, 1, 0, options);
    FAIL() << "no error";
  } catch (const lang::ScenarioError& error) {
    const std::string& message = error.diagnostic().message;
    EXPECT_NE(message.find("every attempt fails the same way"), std::string::npos) << message;
    EXPECT_NE(error.diagnostic().message.find("unstable: c"), std::string::npos);
  }
  EXPECT_EQ(calls, 1);
}

// When every scene the program makes fails the test, the failure says so and points at the
// test's culprit, not at the program's own most frequent rejection.
TEST(ScenarioTest, ASceneTestRejectingEverySceneIsWhatTheFailureNames) {
  auto program = CompileOrDie("from model import *\nt = Table on floor\nc = Cube completely on t\n"
                              "require c.position.x > 0\n");
  ASSERT_NE(program, nullptr);
  SampleOptions options;
  options.max_attempts = 200;
  options.accept = [](const Scene&) -> std::optional<lang::Rejection> {
    return lang::Rejection{lang::RejectionKind::kUnstable, "c", {}, "c fell", false};
  };
  try {
    SampleScene(*program, 1, 0, options);
    FAIL() << "no error";
  } catch (const lang::ScenarioError& error) {
    const std::string& message = error.diagnostic().message;
    EXPECT_NE(message.find("met the program's constraints all failed the scene test, most often "
                           "unstable: c ("),
              std::string::npos)
        << message;
  }
}

TEST(ScenarioTest, SameSeedAndIndexGiveTheSameScene) {
  auto program = CompileOrDie("from model import *\n"
                              "t = Table on floor\nc = Cube completely on t\n"
                              "x = Normal(0, 1)\nparam p = x\n");
  ASSERT_NE(program, nullptr);
  const Scene a = SampleScene(*program, 5, 17).scene;
  const Scene b = SampleScene(*program, 5, 17).scene;
  const Scene c = SampleScene(*program, 5, 18).scene;
  EXPECT_EQ(Find(a, "c").p_WO, Find(b, "c").p_WO);
  EXPECT_NE(Find(a, "c").p_WO, Find(c, "c").p_WO);
  EXPECT_EQ(a.params[0].second.As<double>(), b.params[0].second.As<double>());
}

TEST(ScenarioTest, ParamOverrideForAnUndeclaredNameIsAnError) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.param_overrides = {{"clutter", "3"}, {"lable", "x"}};
  lang::CompileText(RepoPath("examples/test.prs"), "param clutter = 2, label = \"a\"\n", options,
                    diagnostics);
  ASSERT_EQ(diagnostics.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].id, "unknown-param");
  EXPECT_EQ(diagnostics.diagnostics()[0].message,
            "-p lable=x: the program declares no param 'lable'; did you mean 'label'?");
}


// Imported modules that draw nothing are run once per sampler and their globals shared
// (RunCache::module_globals); what a scene can change or draw must still differ per scene.
TEST(ScenarioTest, SharedModuleGlobalsStillVaryPerScene) {
  auto program = CompileOrDie("from shared_values import *\n"
                              "from random_module import *\n"
                              "from reexport import *\n"
                              "param drawn = size + 0\n"
                              "param moved = offset\n"
                              "b = Box at Vector3D(offset, 0, 0.5)\n",
                              "tests/lang/modules/main.prs");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  std::set<double> sizes, offsets;
  for (uint64_t i = 0; i < 20; ++i) {
    const SampledScene s = sampler.Sample(4, i);
    ASSERT_EQ(s.scene.params.size(), 2u);
    sizes.insert(s.scene.params[0].second.As<double>());    // a tuple from the module
    offsets.insert(s.scene.params[1].second.As<double>());  // a draw in the module
    EXPECT_EQ(Find(s.scene, "b").dimensions.x(), 0.1);
    // Cached or not, the scene is the same as a fresh sampler's.
    EXPECT_EQ(Find(s.scene, "b").p_WO, Find(SampleScene(*program, 4, i).scene, "b").p_WO);
  }
  EXPECT_EQ(sizes.size(), 20u);
  EXPECT_EQ(offsets.size(), 20u);
}


// Fixed objects are built once per sampler and copied (RunCache::fixed_objects): the scenes
// and their rejections must be those of fresh samplers, also when a random object placed
// before a fixed one collides with it, and when a fixed object's specifier creates another.
TEST(ScenarioTest, CachedFixedObjectsGiveTheScenesOfAFreshSampler) {
  auto program = CompileOrDie("from model import *\n"
                              "c = Cube at Vector3D(Range(-1.4, 1.4), 0, 0.5)\n"
                              "t = Table on Vector3D(0, 0, 0)\n"
                              "g = Gear on (Plate on Vector3D(1, 1, 0))\n");
  ASSERT_NE(program, nullptr);
  SceneSampler sampler(*program);
  int64_t rejections = 0;
  for (uint64_t i = 0; i < 30; ++i) {
    const SampledScene cached = sampler.Sample(6, i);
    const SampledScene fresh = SampleScene(*program, 6, i);
    ASSERT_EQ(cached.scene.objects.size(), 4u);
    EXPECT_EQ(cached.attempts, fresh.attempts);
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(cached.scene.objects[k].p_WO, fresh.scene.objects[k].p_WO);
    }
    EXPECT_FALSE(BoxesOverlapByPoints(Find(cached.scene, "c"), Find(cached.scene, "t")));
    rejections += cached.rejections.total;
  }
  EXPECT_GT(rejections, 0);  // the cube does land in the table, and is rejected
}

// `for x in range(...)` runs over the numbers without making the list: the same numbers in the
// same order, break and continue, an empty range, a user's own `range`, and the located errors
// of an unpacking target and of a range past the loop limit.
TEST(ScenarioTest, ForOverRangeGivesItsNumbersInOrder) {
  auto numbers = [](const std::string& text) {
    auto program = CompileOrDie("from model import *\nxs = []\n" + text + "param got = xs\n");
    EXPECT_NE(program, nullptr);
    std::vector<double> got;
    if (!program) return got;
    const Scene scene = SampleScene(*program, 1, 0).scene;
    for (const lang::Value& x :
         scene.params.at(0).second.As<std::shared_ptr<lang::ListData>>()->elements) {
      got.push_back(x.As<double>());
    }
    return got;
  };
  EXPECT_EQ(numbers("for i in range(2, 11, 3):\n    xs = xs + [i]\n"),
            (std::vector<double>{2, 5, 8}));
  EXPECT_EQ(numbers("for j in range(5, 0, -2):\n    if j == 3:\n        continue\n"
                    "    xs = xs + [j]\n"),
            (std::vector<double>{5, 1}));
  EXPECT_EQ(numbers("for k in range(100):\n    if k == 2:\n        break\n    xs = xs + [k]\n"),
            (std::vector<double>{0, 1}));
  EXPECT_EQ(numbers("for n in range(0):\n    xs = xs + [n]\n"), std::vector<double>{});
  EXPECT_EQ(numbers("def range(n):\n    return [7]\nfor m in range(3):\n    xs = xs + [m]\n"),
            (std::vector<double>{7}));

  for (const auto& [text, message] :
       {std::pair{"for a, b in range(2):\n    pass\n", "cannot iterate over a number"},
        {"for a in range(10000000):\n    pass\n",
         "range of 10000000 numbers is longer than the loop limit of one scene"}}) {
    auto program = CompileOrDie(std::string("from model import *\n") + text);
    ASSERT_NE(program, nullptr);
    try {
      SampleScene(*program, 1, 0);
      ADD_FAILURE() << text << " sampled";
    } catch (const lang::ScenarioError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_EQ(e.diagnostic().span.begin, std::string_view(text).find("range") + 20) << text;
    }
  }
}

}  // namespace
}  // namespace prs::sampling
