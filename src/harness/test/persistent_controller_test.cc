// Persistent --exec workers: the handshake, one process for many scenes, chatter ignored, the
// answer rules (the scene's seed and index required), and every way a worker can misbehave —
// exit at once, never start, crash, hang, write garbage, half a line or a flood, answer another
// scene — with the episode recorded, the worker killed and a fresh one for the next scene.
// RunEpisodes with workers gives the records of one process per episode, for any thread count.
#include "harness/persistent_controller.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "harness/exec_controller.h"
#include "harness/test/process_checks.h"
#include "sampling/test/scene_checks.h"

namespace prs::harness {
namespace {

namespace fs = std::filesystem;
using testing_checks::IsGone;

// The protocol in POSIX sh. Before the handshake: `on_start`; per scene, with $seed and $index
// read from the line: `on_scene`, which may answer itself, else the answer is success.
constexpr char kWorkerTemplate[] = R"(#!/bin/sh
echo "start $$" >> "$LOG"
echo "parent $PPID" >> "$LOG"
ON_START
while IFS= read -r line; do
  rest=${line#*\"seed\":}; seed=${rest%%[!0-9]*}
  rest=${line#*\"index\":}; index=${rest%%[!0-9]*}
  echo "scene $index $$" >> "$LOG"
  ON_SCENE
  echo "{\"outcome\":\"success\",\"seed\":$seed,\"index\":$index}"
done
echo "stop $$" >> "$LOG"
)";

class PersistentControllerTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("prs_persistent_test_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A worker script with `on_start` before its handshake and `on_scene` for each scene; returns
  // the command that runs it.
  std::string Worker(const std::string& on_start, const std::string& on_scene,
                     bool handshake = true) {
    std::string text = kWorkerTemplate;
    text.replace(text.find("ON_START"), 8,
                 on_start + (handshake ? "\necho '{\"ready\": true}'" : ""));
    text.replace(text.find("ON_SCENE"), 8, on_scene.empty() ? ":" : on_scene);
    std::ofstream(dir_ / "worker.sh") << text;
    return "LOG='" + (dir_ / "log.txt").string() + "' exec sh '" + (dir_ / "worker.sh").string() +
           "'";
  }

  ControllerFactory Factory(const std::string& command, double timeout_s = 10,
                            double startup_timeout_s = 10) {
    return MakePersistentControllerFactory({command, timeout_s, startup_timeout_s, &cancel_});
  }

  static sampling::SampledScene Scene(uint64_t index, uint64_t seed = 42) {
    sampling::SampledScene scene;
    scene.seed = seed;
    scene.index = index;
    return scene;
  }
  static std::string SceneJson(uint64_t index, uint64_t seed = 42) {
    return R"({"format":"prs-scene/1","seed":)" + std::to_string(seed) + R"(,"index":)" +
           std::to_string(index) + "}";
  }
  static EpisodeResult Run(Controller& controller, uint64_t index) {
    return controller.RunEpisode(Scene(index), SceneJson(index));
  }

  // The log's lines that start with `word` ("start", "scene", "stop").
  std::vector<std::string> Log(const std::string& word) const {
    std::ifstream in(dir_ / "log.txt");
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with(word + " ")) lines.push_back(line.substr(word.size() + 1));
    }
    return lines;
  }
  static pid_t PidOf(const std::string& log_entry) {
    return pid_t(std::stol(log_entry.substr(log_entry.rfind(' ') + 1)));
  }

  fs::path dir_;
  std::atomic<bool> cancel_{false};
};

TEST_F(PersistentControllerTest, OneProcessAnswersEverySceneAndStopsWhenItsInputEnds) {
  {
    const ControllerFactory factory = Factory(Worker("", ""));
    std::unique_ptr<Controller> controller = factory();
    for (uint64_t i = 0; i < 5; ++i) {
      const EpisodeResult result = Run(*controller, i);
      EXPECT_EQ(result.outcome, "success") << result.detail;
      EXPECT_TRUE(result.extra.empty())
          << "seed and index are the scene's, not extra: " << result.extra.dump();
    }
  }
  ASSERT_EQ(Log("start").size(), 1u) << "started once for five scenes";
  EXPECT_EQ(Log("scene").size(), 5u);
  EXPECT_EQ(Log("stop").size(), 1u) << "the worker sees the end of its input and exits";
  EXPECT_TRUE(IsGone(PidOf(Log("start")[0])));
}

TEST_F(PersistentControllerTest, WorkersAreNamedAndKeptAcrossControllersOfOneFactory) {
  const ControllerFactory factory = Factory(
      Worker("echo \"env $PRS_PERSISTENT $PRS_WORKER ${PRS_SCENE_FILE:-none}\" >> \"$LOG\"", ""));
  {
    std::unique_ptr<Controller> a = factory();
    std::unique_ptr<Controller> b = factory();
    EXPECT_EQ(Run(*a, 0).outcome, "success");
    EXPECT_EQ(Run(*b, 1).outcome, "success");
  }
  {  // a search's next generation: the same two processes
    std::unique_ptr<Controller> a = factory();
    std::unique_ptr<Controller> b = factory();
    EXPECT_EQ(Run(*a, 2).outcome, "success");
    EXPECT_EQ(Run(*b, 3).outcome, "success");
  }
  EXPECT_EQ(Log("start").size(), 2u);
  std::vector<std::string> env = Log("env");
  std::sort(env.begin(), env.end());
  EXPECT_EQ(env, (std::vector<std::string>{"1 0 none", "1 1 none"}));
}

TEST_F(PersistentControllerTest, ChatterIsIgnoredAndTheAnswerKeepsDetailScoreAndExtra) {
  const ControllerFactory factory = Factory(Worker(
      "echo 'Loading the simulator...'; echo 'warning: no GPU' >&2",
      "echo \"step 1\"; echo \"{\\\"outcome\\\":\\\"no-path\\\",\\\"detail\\\":\\\"blocked\\\","
      "\\\"score\\\":-0.5,\\\"grip_n\\\":3,\\\"seed\\\":$seed,\\\"index\\\":$index}\"; continue"));
  std::unique_ptr<Controller> controller = factory();
  const EpisodeResult result = Run(*controller, 3);
  EXPECT_EQ(result.outcome, "no-path");
  EXPECT_EQ(result.detail, "blocked");
  ASSERT_TRUE(result.score.has_value());
  EXPECT_EQ(*result.score, -0.5);
  EXPECT_EQ(result.extra, nlohmann::json({{"grip_n", 3}}));
}

TEST_F(PersistentControllerTest, AWorkerWhoseShellReportsASignalGivesThatSignal) {
  // The worker's shell exits with 128 + 11 after its child segfaults: signal-11, not exit-139.
  const ControllerFactory factory =
      Factory(Worker("", "[ \"$index\" = 1 ] && { sh -c 'ulimit -c 0; kill -SEGV $$'; exit $?; }"));
  std::unique_ptr<Controller> controller = factory();
  EXPECT_EQ(Run(*controller, 0).outcome, "success");
  const EpisodeResult crashed = Run(*controller, 1);
  EXPECT_EQ(crashed.outcome, "signal-11");
  EXPECT_NE(crashed.detail.find("SIGSEGV; /bin/sh reported exit status 139"), std::string::npos)
      << crashed.detail;
  EXPECT_EQ(Run(*controller, 2).outcome, "success");
}

TEST_F(PersistentControllerTest, AWorkerKilledMidEpisodeFailsThatEpisodeAndTheNextGetsAFreshOne) {
  const ControllerFactory factory = Factory(Worker("", "[ \"$index\" = 1 ] && kill -9 $$"));
  std::unique_ptr<Controller> controller = factory();
  EXPECT_EQ(Run(*controller, 0).outcome, "success");
  const EpisodeResult killed = Run(*controller, 1);
  EXPECT_EQ(killed.outcome, "signal-9");
  EXPECT_NE(killed.detail.find("SIGKILL"), std::string::npos) << killed.detail;
  EXPECT_EQ(Run(*controller, 2).outcome, "success");
  const std::vector<std::string> starts = Log("start");
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_NE(PidOf(starts[0]), PidOf(starts[1]));
  const std::vector<std::string> scenes = Log("scene");
  ASSERT_EQ(scenes.size(), 3u) << "no episode is run twice";
  EXPECT_TRUE(scenes[0].starts_with("0 ") && scenes[1].starts_with("1 ") &&
              scenes[2].starts_with("2 "));
}

TEST_F(PersistentControllerTest, AHangingWorkerTimesOutAndIsKilledWithItsChildren) {
  const ControllerFactory factory = Factory(
      Worker("", "[ \"$index\" = 1 ] && { sleep 30 & echo \"child $!\" >> \"$LOG\"; sleep 30; }"),
      /*timeout_s=*/0.3);
  std::unique_ptr<Controller> controller = factory();
  EXPECT_EQ(Run(*controller, 0).outcome, "success");
  const EpisodeResult hung = Run(*controller, 1);
  EXPECT_EQ(hung.outcome, "timeout");
  EXPECT_NE(hung.detail.find("0.3 s"), std::string::npos) << hung.detail;
  ASSERT_EQ(Log("child").size(), 1u);
  EXPECT_TRUE(IsGone(PidOf(Log("start")[0])));
  EXPECT_TRUE(IsGone(PidOf(Log("child")[0]))) << "its background child was killed too";
  EXPECT_EQ(Run(*controller, 2).outcome, "success");
}

TEST_F(PersistentControllerTest, GarbageOtherScenesAndNamelessAnswersAreBadAnswersAndRestart) {
  const ControllerFactory factory = Factory(
      Worker("",
             "case $index in 1) echo '{not json'; continue;; "
             "2) echo '{\"outcome\":\"success\"}'; continue;; "
             "3) echo \"{\\\"outcome\\\":\\\"success\\\",\\\"seed\\\":$seed,\\\"index\\\":9}\"; "
             "continue;; "
             "4) echo '{\"outcome\":\"Not A Name\"}'; continue;; esac"));
  std::unique_ptr<Controller> controller = factory();
  EXPECT_EQ(Run(*controller, 0).outcome, "success");
  const EpisodeResult garbage = Run(*controller, 1);
  EXPECT_EQ(garbage.outcome, "bad-answer");
  EXPECT_NE(garbage.detail.find("not JSON"), std::string::npos) << garbage.detail;
  const EpisodeResult nameless = Run(*controller, 2);
  EXPECT_EQ(nameless.outcome, "bad-answer");
  EXPECT_NE(nameless.detail.find("\"seed\" and \"index\""), std::string::npos) << nameless.detail;
  const EpisodeResult other = Run(*controller, 3);
  EXPECT_EQ(other.outcome, "bad-answer");
  EXPECT_NE(other.detail.find("another scene (seed 42, index 9)"), std::string::npos)
      << other.detail;
  EXPECT_EQ(Run(*controller, 4).outcome, "bad-answer");
  EXPECT_EQ(Run(*controller, 5).outcome, "success");
  EXPECT_EQ(Log("start").size(), 5u) << "each bad answer restarts the worker";
}

TEST_F(PersistentControllerTest, HalfALineThenAnExitAndAFloodAreRecorded) {
  const ControllerFactory factory =
      Factory(Worker("",
                     "case $index in 1) printf '{\"outcome\":\"succ'; exit 4;; "
                     "2) head -c 20000000 /dev/zero | tr '\\0' '{'; sleep 30;; esac"));
  std::unique_ptr<Controller> controller = factory();
  const EpisodeResult half = Run(*controller, 1);
  EXPECT_EQ(half.outcome, "exit-4");
  EXPECT_NE(half.detail.find("part of a line: {\"outcome\":\"succ"), std::string::npos)
      << half.detail;
  const EpisodeResult flood = Run(*controller, 2);
  EXPECT_EQ(flood.outcome, "bad-answer");
  EXPECT_NE(flood.detail.find("16 MiB"), std::string::npos) << flood.detail;
  EXPECT_EQ(Run(*controller, 3).outcome, "success");
}

TEST_F(PersistentControllerTest, AWorkerThatCannotStartStopsTheRunWithItsReason) {
  {
    std::unique_ptr<Controller> controller =
        Factory(Worker("echo 'no licence for the simulator' >&2; exit 3", "", false))();
    try {
      Run(*controller, 0);
      ADD_FAILURE() << "a worker that exits at once must not give an episode";
    } catch (const ControllerStartError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find("exited with code 3"), std::string::npos) << what;
      EXPECT_NE(what.find("no licence for the simulator"), std::string::npos) << what;
      EXPECT_NE(what.find("{\"ready\": true}"), std::string::npos) << what;
    }
  }
  {
    std::unique_ptr<Controller> controller =
        Factory(Worker("echo 'still loading' >&2; sleep 30", "", false), 10, 0.3)();
    try {
      Run(*controller, 0);
      ADD_FAILURE() << "no handshake must stop the run";
    } catch (const ControllerStartError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find("no handshake within 0.3 s"), std::string::npos) << what;
      EXPECT_NE(what.find("still loading"), std::string::npos) << what;
      EXPECT_NE(what.find("--startup-timeout"), std::string::npos) << what;
    }
    EXPECT_TRUE(IsGone(PidOf(Log("start")[0])));
  }
  std::unique_ptr<Controller> controller =
      Factory(Worker("echo '{\"outcome\":\"success\"}'", "", false))();
  EXPECT_THROW(Run(*controller, 0), ControllerStartError);
}

TEST_F(PersistentControllerTest, CancellingKillsTheRunningEpisode) {
  const ControllerFactory factory = Factory(Worker("", "sleep 30"));
  std::unique_ptr<Controller> controller = factory();
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    cancel_ = true;
  });
  const EpisodeResult result = Run(*controller, 0);
  canceller.join();
  EXPECT_EQ(result.outcome, "cancelled");
  EXPECT_TRUE(IsGone(PidOf(Log("start")[0])));
}

TEST_F(PersistentControllerTest, AWorkerThatIgnoresTheEndOfItsInputIsKilled) {
  {
    // The shell around the worker goes on after the worker's input ends.
    std::string command = Worker("", "");
    command.replace(command.find("exec "), 5, "");
    const ControllerFactory factory = Factory(command + "; sleep 30");
    std::unique_ptr<Controller> controller = factory();
    EXPECT_EQ(Run(*controller, 0).outcome, "success");
  }
  EXPECT_EQ(Log("stop").size(), 1u);
  EXPECT_TRUE(IsGone(PidOf(Log("parent")[0])));
}

// Records of RunEpisodes over table_cube.prs: the same script answers in both modes.
std::vector<EpisodeRecord> RunTableCube(const ControllerFactory& factory, int threads) {
  std::ifstream file(sampling::testing_checks::RepoPath("examples/table_cube.prs"));
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto program = sampling::testing_checks::CompileOrDie(text, "examples/table_cube.prs");
  RunOptions options;
  options.seed = 5;
  options.count = 12;
  options.threads = threads;
  return RunEpisodes(*program, factory, options).records;
}

TEST_F(PersistentControllerTest, RecordsEqualOneProcessPerEpisodeForAnyThreadCount) {
  // Odd scenes fail with their index as the score; in persistent mode index 5 kills its worker
  // the first time (a flaky simulator), which costs that episode alone.
  const std::string once = (dir_ / "crashed-once").string();
  const std::string command = Worker(
      "", "[ \"$index\" = 5 ] && [ -n \"$PRS_PERSISTENT\" ] && [ ! -e '" + once +
              "' ] && "
              "{ touch '" +
              once +
              "'; kill -9 $$; }\n"
              "  [ $((index % 2)) = 1 ] && echo "
              "\"{\\\"outcome\\\":\\\"no-path\\\",\\\"score\\\":$index,"
              "\\\"seed\\\":$seed,\\\"index\\\":$index}\" && continue\n"
              "  [ -z \"$PRS_PERSISTENT\" ] && { echo '{\"outcome\":\"success\"}'; exit 0; }");
  const std::vector<EpisodeRecord> baseline = RunTableCube(
      [&] {
        return std::make_unique<ExecController>(ExecOptions{command, 10});
      },
      2);
  ASSERT_EQ(baseline.size(), 12u);
  for (const int threads : {1, 2}) {
    fs::remove(once);
    const std::vector<EpisodeRecord> records = RunTableCube(Factory(command), threads);
    ASSERT_EQ(records.size(), baseline.size());
    for (size_t i = 0; i < records.size(); ++i) {
      SCOPED_TRACE("threads " + std::to_string(threads) + ", index " + std::to_string(i));
      EXPECT_EQ(records[i].index, baseline[i].index);
      if (i == 5) {
        EXPECT_EQ(records[i].result.outcome, "signal-9");
        continue;
      }
      EXPECT_EQ(records[i].result.outcome, baseline[i].result.outcome);
      EXPECT_EQ(records[i].result.score, baseline[i].result.score);
      EXPECT_EQ(records[i].result.extra, baseline[i].result.extra);
      EXPECT_EQ(records[i].features, baseline[i].features);
    }
  }
}

}  // namespace
}  // namespace prs::harness
