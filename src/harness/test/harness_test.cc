// RunEpisodes over table_cube.prs with scripted controllers: records in index order and the
// same for any thread count, one controller per thread, exceptions recorded, failing scenes
// saved with the hook called; the outcome table, record JSON, names and the registry.
#include "harness/harness.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <chrono>
#include <mutex>
#include <thread>
#include <set>

#include "harness/registry.h"
#include "sampling/test/scene_checks.h"

namespace prs::harness {
namespace {

namespace fs = std::filesystem;
using sampling::testing_checks::CompileOrDie;
using sampling::testing_checks::RepoPath;

// The paper's Figure 1, compiled from its file (its import resolves beside it).
std::unique_ptr<lang::CompiledProgram> CompileTableCube() {
  std::ifstream file(RepoPath("examples/table_cube.prs"));
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return CompileOrDie(text, "examples/table_cube.prs");
}

// Decides from the scene: the Cube's x position, so the outcome is a pure function of it.
class CubeSideController : public Controller {
 public:
  EpisodeResult RunEpisode(const sampling::SampledScene& scene, const std::string& json) override {
    if (json.find("\"index\":" + std::to_string(scene.index)) == std::string::npos) {
      return {"wrong-json", "the JSON is not this scene's"};
    }
    if (scene.index == 5) throw std::runtime_error("camera unplugged");
    for (const lang::SceneObject& object : scene.scene.objects) {
      if (object.cls->name != "Cube") continue;
      if (object.p_WO.y() > 0) return {"success", "cube at the back"};
      return {object.p_WO.x() < -0.6 ? "far-left" : "no-path", "cube at the front"};
    }
    return {"missing-object", "no cube"};
  }
};

RunOptions MakeOptions(int64_t count, int threads) {
  RunOptions options;
  options.seed = 3;
  options.start = 10;
  options.count = count;
  options.threads = threads;
  options.scenario_args = {"examples/table_cube.prs", "-p", "x=my value"};
  return options;
}

std::vector<std::string> Outcomes(const RunSummary& summary) {
  std::vector<std::string> outcomes;
  for (const EpisodeRecord& record : summary.records) {
    outcomes.push_back(std::to_string(record.index) + " " + record.result.outcome + " " +
                       record.result.detail + " " + record.regenerate);
  }
  return outcomes;
}

TEST(RunEpisodesTest, RecordsComeInIndexOrderAndMatchForAnyThreadCount) {
  auto program = CompileTableCube();
  std::atomic<int> made{0};
  const ControllerFactory factory = [&] {
    ++made;
    return std::make_unique<CubeSideController>();
  };
  std::vector<uint64_t> delivered;
  RunOptions options = MakeOptions(24, 1);
  options.on_record = [&](const EpisodeRecord& record) { delivered.push_back(record.index); };
  const RunSummary one = RunEpisodes(*program, factory, options);
  EXPECT_EQ(made.load(), 1);
  made = 0;
  options.threads = 3;
  const RunSummary three = RunEpisodes(*program, factory, options);
  EXPECT_LE(made.load(), 3) << "more controllers than threads";
  EXPECT_EQ(three.threads, 3);
  ASSERT_EQ(one.records.size(), 24u);
  EXPECT_EQ(Outcomes(one), Outcomes(three));
  for (size_t i = 0; i < one.records.size(); ++i) EXPECT_EQ(one.records[i].index, 10 + i);
  EXPECT_EQ(delivered.size(), 48u);
  std::set<std::string> kinds;
  for (const EpisodeRecord& record : one.records) kinds.insert(record.result.outcome);
  EXPECT_GE(kinds.size(), 3u) << "the scripted controller should give several outcomes";
}

// Counts how many episodes run at the same time (each sleeps 2 ms, so two threads that share
// the work overlap).
class ConcurrencyController : public Controller {
 public:
  ConcurrencyController(std::atomic<int>* running, std::atomic<int>* most)
      : running_(running), most_(most) {}
  EpisodeResult RunEpisode(const sampling::SampledScene&, const std::string&) override {
    const int now = ++*running_;
    for (int seen = most_->load(); now > seen && !most_->compare_exchange_weak(seen, now);) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    --*running_;
    return {"success", ""};
  }

 private:
  std::atomic<int>* running_;
  std::atomic<int>* most_;
};

// Regression: with many episodes a worker used to claim the whole reordering window (a chunk
// of up to 16 against a window of 4 per thread) and run it alone while the others waited, so
// `prs test --threads 2` of 2,000 Table-Cube episodes took as long as one thread.
TEST(RunEpisodesTest, ManyEpisodesRunOnEveryThreadAtOnce) {
  auto program = CompileTableCube();
  std::atomic<int> running{0}, most{0};
  const ControllerFactory factory = [&] {
    return std::make_unique<ConcurrencyController>(&running, &most);
  };
  RunOptions options = MakeOptions(400, 2);
  RunEpisodes(*program, factory, options);
  EXPECT_EQ(most.load(), 2) << "the two threads never ran episodes at the same time";
}

TEST(RunEpisodesTest, FailuresCarryTheRegenerateCommand) {
  auto program = CompileTableCube();
  const RunSummary summary = RunEpisodes(
      *program, [] { return std::make_unique<CubeSideController>(); }, MakeOptions(8, 2));
  ASSERT_EQ(summary.records.size(), 8u);
  for (const EpisodeRecord& record : summary.records) {
    if (record.result.outcome == "success") {
      EXPECT_TRUE(record.regenerate.empty());
    } else {
      EXPECT_EQ(record.regenerate,
                "prs sample examples/table_cube.prs -p 'x=my value' -s 3 "
                "--start " +
                    std::to_string(record.index) + " -n 1");
    }
  }
}

TEST(RunEpisodesTest, ThrowingControllerBecomesControllerError) {
  auto program = CompileTableCube();
  RunOptions options = MakeOptions(1, 1);
  options.start = 5;
  const RunSummary summary = RunEpisodes(
      *program, [] { return std::make_unique<CubeSideController>(); }, options);
  ASSERT_EQ(summary.records.size(), 1u);
  EXPECT_EQ(summary.records[0].result.outcome, "controller-error");
  EXPECT_EQ(summary.records[0].result.detail, "camera unplugged");
}

TEST(RunEpisodesTest, FailingScenesAreSavedAndTheHookGetsTheirStems) {
  auto program = CompileTableCube();
  const fs::path dir = fs::temp_directory_path() / ("prs_harness_save_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  RunOptions options = MakeOptions(16, 2);
  options.save_failures_dir = dir.string();
  std::mutex mutex;
  std::set<std::string> hooked;
  options.on_failure = [&](const sampling::SampledScene& scene, const std::string& stem) {
    EXPECT_FALSE(scene.scene.objects.empty()) << "the hook needs the scene's objects";
    std::lock_guard lock(mutex);
    hooked.insert(stem);
  };
  const RunSummary summary = RunEpisodes(
      *program, [] { return std::make_unique<CubeSideController>(); }, options);
  std::set<std::string> expected;
  for (const EpisodeRecord& record : summary.records) {
    const std::string stem = (dir / ("seed-3-index-" + std::to_string(record.index))).string();
    if (record.result.outcome == "success") {
      EXPECT_FALSE(fs::exists(stem + ".json"));
      continue;
    }
    expected.insert(stem);
    EXPECT_EQ(record.saved_scene, stem + ".json");
    std::ifstream file(stem + ".json");
    std::string line;
    ASSERT_TRUE(std::getline(file, line)) << stem;
    const nlohmann::json scene = nlohmann::json::parse(line);
    EXPECT_EQ(scene["index"], record.index);
    EXPECT_EQ(scene["seed"], 3);
  }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(hooked, expected);
  fs::remove_all(dir);
}

// Warns about its scene: every odd index "odd scene", index 12 also "twelve"; each distinct
// sentence reaches on_warning once, at its first record in index order, before that record.
class WarningController : public Controller {
 public:
  EpisodeResult RunEpisode(const sampling::SampledScene& scene, const std::string&) override {
    EpisodeResult result{"success", ""};
    if (scene.index % 2 == 1) result.warnings.push_back("odd scene");
    if (scene.index == 12) result.warnings = {"twelve", "odd scene"};
    return result;
  }
};

TEST(RunEpisodesTest, EachDistinctWarningIsReportedOnceInIndexOrder) {
  const auto program = CompileTableCube();
  for (const int threads : {1, 2}) {
    RunOptions options = MakeOptions(8, threads);  // scenes 10..17
    std::vector<std::string> events;
    options.on_warning = [&](const std::string& w) { events.push_back("warning " + w); };
    options.on_record = [&](const EpisodeRecord& r) {
      events.push_back("record " + std::to_string(r.index));
    };
    RunEpisodes(*program, [] { return std::make_unique<WarningController>(); }, options);
    const std::vector<std::string> expected = {
        "record 10", "warning odd scene", "record 11", "warning twelve", "record 12",
        "record 13", "record 14", "record 15", "record 16", "record 17"};
    EXPECT_EQ(events, expected) << threads << " threads";
  }
}

TEST(TabulateOutcomesTest, SuccessFirstThenByCountAndSharesAddUp) {
  std::vector<EpisodeRecord> records;
  for (const char* outcome :
       {"no-path", "poor-grip", "success", "no-path", "abc", "poor-grip", "no-path", "success"}) {
    records.push_back({.seed = 0,
                       .index = 0,
                       .result = {outcome, ""},
                       .wall_s = 0,
                       .saved_scene = {},
                       .regenerate = {},
                       .coordinates = {},
                       .spec = {},
                       .search = {},
                       .features = {}});
  }
  const std::vector<OutcomeRow> rows = TabulateOutcomes(records);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].outcome, "success");
  EXPECT_EQ(rows[0].count, 2);
  EXPECT_EQ(rows[1].outcome, "no-path");
  EXPECT_EQ(rows[2].outcome, "poor-grip");
  EXPECT_EQ(rows[3].outcome, "abc");
  int64_t total = 0;
  double share = 0;
  for (const OutcomeRow& row : rows) {
    total += row.count;
    share += row.share;
  }
  EXPECT_EQ(total, 8);
  EXPECT_DOUBLE_EQ(share, 1.0);
}

TEST(FormatRecordJsonTest, KeysInOrderWithExtraAndRegenerate) {
  EpisodeRecord record{.seed = 1,
                       .index = 2,
                       .result = {"no-path", "far", {{"d_m", 0.9}}},
                       .wall_s = 0.5,
                       .saved_scene = {},
                       .regenerate = "prs sample f -s 1",
                       .coordinates = {},
                       .spec = {},
                       .search = {},
                       .features = {}};
  EXPECT_EQ(FormatRecordJson(record),
            R"({"seed":1,"index":2,"outcome":"no-path","detail":"far","wall_s":0.5,)"
            R"("extra":{"d_m":0.9},"regenerate":"prs sample f -s 1"})");
}

TEST(OutcomeNameTest, LowercaseHyphenatedOnly) {
  for (const char* good : {"success", "no-path", "exit-3", "signal-9", "a"}) {
    EXPECT_TRUE(IsOutcomeName(good)) << good;
  }
  for (const char* bad : {"", "No-path", "no path", "-a", "a-", "a--b", "ok!", "é"}) {
    EXPECT_FALSE(IsOutcomeName(bad)) << bad;
  }
  EXPECT_EQ(QuoteForShell("a b'c"), "'a b'\\''c'");
  EXPECT_EQ(QuoteForShell("dir/x.prs"), "dir/x.prs");
}

TEST(RegistryTest, DemoReachIsBuiltInAndNamesAreUnique) {
  const ControllerInfo* demo = FindController("demo-reach");
  ASSERT_NE(demo, nullptr);
  EXPECT_EQ(FindController("demo-rech"), nullptr);
  EXPECT_THROW(RegisterController("demo-reach", "again", MakeDemoReachController),
               std::invalid_argument);
  EXPECT_THROW(RegisterController("Bad Name", "x", MakeDemoReachController), std::invalid_argument);
  RegisterController("test-only", "for this test", MakeDemoReachController);
  std::vector<std::string> names;
  for (const ControllerInfo& info : ListControllers()) names.push_back(info.name);
  EXPECT_EQ(names, (std::vector<std::string>{"demo-reach", "planted-1-percent",
                                              "planted-1-permille", "test-only"}));
}

TEST(PlantedTest, FailuresHoldThePlannedShareOfTableCube) {
  // 50,000 scenes: about 525 (1.05 %) and 56 (0.11 %) failures, measured with 200,000 scenes
  // (docs/search.md); the bounds are more than 4 standard deviations wide.
  auto program = CompileTableCube();
  for (const auto& [failure, lo, hi] :
       {std::tuple{PlantedOnePercent(), 430, 620}, std::tuple{PlantedOnePermille(), 27, 90}}) {
    const RunSummary summary = RunEpisodes(
        *program, [f = failure] { return MakePlantedController(f); }, MakeOptions(50000, 2));
    int64_t failures = 0;
    for (const EpisodeRecord& record : summary.records) {
      ASSERT_TRUE(record.result.score.has_value());
      const bool failed = record.result.outcome == "planted-failure";
      failures += failed;
      EXPECT_EQ(failed, *record.result.score <= 0);
    }
    EXPECT_GE(failures, lo);
    EXPECT_LE(failures, hi);
  }
}

TEST(DemoReachTest, ClassifiesByTheDistanceFromCubeToNearestRobot) {
  auto program = CompileTableCube();
  const RunSummary summary = RunEpisodes(*program, MakeDemoReachController, MakeOptions(40, 2));
  int64_t successes = 0;
  for (const EpisodeRecord& record : summary.records) {
    const double distance_m = record.result.extra.at("distance_m").get<double>();
    const bool in_reach = distance_m >= 0.25 && distance_m <= 0.855;
    EXPECT_EQ(record.result.outcome, in_reach ? "success" : "no-path") << record.result.detail;
    successes += in_reach;
  }
  EXPECT_GT(successes, 0);
}

}  // namespace
}  // namespace prs::harness
