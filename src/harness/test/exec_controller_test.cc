// The --exec protocol: the scene on stdin and in PRS_SCENE_FILE (removed afterwards), PRS_SEED
// and PRS_INDEX, a JSON answer or the exit status as the outcome, timeouts and signals, and
// no process left behind.
#include "harness/exec_controller.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/child_process.h"
#include "harness/test/process_checks.h"

namespace prs::harness {
namespace {

namespace fs = std::filesystem;
using testing_checks::IsGone;

class ExecControllerTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("prs_exec_test_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    scene_.seed = 42;
    scene_.index = 7;
  }
  void TearDown() override { fs::remove_all(dir_); }

  EpisodeResult Run(const std::string& command, double timeout_s = 10) {
    ExecController controller({command, timeout_s, nullptr});
    return controller.RunEpisode(scene_, kSceneJson);
  }

  std::string Read(const std::string& name) const {
    std::ifstream in(dir_ / name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  // The command's `$D`: this test's directory, quoted for the shell.
  std::string D() const { return "'" + dir_.string() + "'"; }

  static constexpr char kSceneJson[] = R"({"format":"prs-scene/1","seed":42,"index":7})";
  fs::path dir_;
  sampling::SampledScene scene_;
};

TEST_F(ExecControllerTest, SceneArrivesOnStdinAndInTheNamedFileWithSeedAndIndex) {
  const EpisodeResult result = Run("cat > " + D() + "/stdin.txt; cat \"$PRS_SCENE_FILE\" > " + D() +
                                   "/file.txt; echo " + "\"$PRS_SEED $PRS_INDEX\" > " + D() +
                                   "/ids.txt; echo \"$PRS_SCENE_FILE\" > " + D() + "/path.txt");
  EXPECT_EQ(result.outcome, "success") << result.detail;
  EXPECT_EQ(Read("stdin.txt"), std::string(kSceneJson) + "\n");
  EXPECT_EQ(Read("file.txt"), std::string(kSceneJson) + "\n");
  EXPECT_EQ(Read("ids.txt"), "42 7\n");
  std::string path = Read("path.txt");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  EXPECT_FALSE(fs::exists(path)) << "the scene file was not removed: " << path;
}

TEST_F(ExecControllerTest, ExitCodesBecomeOutcomes) {
  EXPECT_EQ(Run("exit 0").outcome, "success");
  const EpisodeResult failed = Run("echo 'gripper jammed' >&2; exit 3");
  EXPECT_EQ(failed.outcome, "exit-3");
  EXPECT_NE(failed.detail.find("code 3"), std::string::npos) << failed.detail;
  EXPECT_NE(failed.detail.find("gripper jammed"), std::string::npos) << failed.detail;
  EXPECT_EQ(Run("no-such-command-prs-test").outcome, "exit-127");
}

TEST_F(ExecControllerTest, JsonAnswerOnTheLastLineWinsAndKeepsTheOtherKeys) {
  const EpisodeResult result =
      Run("echo 'log line'; echo '{\"outcome\": \"poor-grip\", \"detail\": \"slipped\", "
          "\"force_N\": 2.5}'; echo; exit 4");
  EXPECT_EQ(result.outcome, "poor-grip");
  EXPECT_EQ(result.detail, "slipped");
  EXPECT_EQ(result.extra, nlohmann::json({{"force_N", 2.5}}));
}

TEST_F(ExecControllerTest, JsonWithoutAValidOutcomeIsABadAnswer) {
  EXPECT_EQ(Run("echo '{\"outcome\": \"No Path!\"}'").outcome, "bad-answer");
  EXPECT_EQ(Run("echo '{\"result\": \"success\"}'").outcome, "bad-answer");
  // Not a JSON object at all: the exit status decides.
  EXPECT_EQ(Run("echo '[1, 2]'; exit 5").outcome, "exit-5");
  EXPECT_EQ(Run("echo '{not json'").outcome, "success");
}

TEST_F(ExecControllerTest, KilledBySignalIsNamed) {
  const EpisodeResult result = Run("kill -KILL $$");
  EXPECT_EQ(result.outcome, "signal-9");
  EXPECT_NE(result.detail.find("SIGKILL"), std::string::npos) << result.detail;
  EXPECT_EQ(Run("kill -TERM $$").outcome, "signal-15");
}

TEST_F(ExecControllerTest, ACommandKilledUnderTheShellIsASignalNotAnExitCode) {
  // /bin/sh runs the command as its child and exits with 128 + N when the child dies by signal
  // N: a segfaulting controller is signal-11, as docs/harness.md says, not exit-139.
  const EpisodeResult segfault = Run("sh -c 'ulimit -c 0; kill -SEGV $$'; exit $?");
  EXPECT_EQ(segfault.outcome, "signal-11");
  EXPECT_NE(segfault.detail.find("signal 11 (SIGSEGV; /bin/sh reported exit status 139)"),
            std::string::npos)
      << segfault.detail;
  EXPECT_EQ(Run("cd " + D() + " && sh -c 'kill -USR1 $$'").outcome, "signal-10");
  // The shell's report cannot be told from an exit code of 129 to 159: read the same way.
  EXPECT_EQ(Run("exit 130").outcome, "signal-2");
  // Outside 128 + (1 to 31) an exit code is itself.
  EXPECT_EQ(Run("exit 128").outcome, "exit-128");
  EXPECT_EQ(Run("exit 160").outcome, "exit-160");
  EXPECT_EQ(Run("exit 255").outcome, "exit-255");
}

TEST(ShellExitCodeTest, OnlyTheShellsSignalReportsBecomeSignals) {
  using internal::ReadShellExitCode;
  for (int code : {0, 1, 3, 127, 128, 160, 200, 255}) {
    const internal::ExitStatus status = ReadShellExitCode(code);
    EXPECT_FALSE(status.signaled) << code;
    EXPECT_EQ(status.code, code);
  }
  for (int signal_number = 1; signal_number <= 31; ++signal_number) {
    const internal::ExitStatus status = ReadShellExitCode(128 + signal_number);
    EXPECT_TRUE(status.signaled) << signal_number;
    EXPECT_EQ(status.code, signal_number);
    EXPECT_EQ(status.shell_status, 128 + signal_number);
  }
  EXPECT_EQ(internal::DescribeExit({true, 9}, ""),
            "the controller was killed by signal 9 (SIGKILL)");
  EXPECT_EQ(internal::DescribeExit(ReadShellExitCode(139), "Segmentation fault\n"),
            "the controller was killed by signal 11 (SIGSEGV; /bin/sh reported exit status 139); "
            "its last error line: Segmentation fault");
}

TEST_F(ExecControllerTest, HangingControllerTimesOutAndItsChildrenDie) {
  const auto begin = std::chrono::steady_clock::now();
  const EpisodeResult result =
      Run("sleep 30 & echo $! > " + D() + "/child.txt; sleep 30", /*timeout_s=*/0.3);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  EXPECT_EQ(result.outcome, "timeout");
  EXPECT_NE(result.detail.find("0.3 s"), std::string::npos) << result.detail;
  EXPECT_LT(seconds, 3.0);
  const pid_t child = std::stoi(Read("child.txt"));
  EXPECT_TRUE(IsGone(child)) << "the background child " << child << " survived";
}

TEST_F(ExecControllerTest, BackgroundChildrenDoNotHoldTheEpisodeOpen) {
  // The stray `sleep` keeps stdout open; the episode must still end with its parent.
  const auto begin = std::chrono::steady_clock::now();
  const EpisodeResult result = Run("sleep 30 & echo $! > " + D() + "/child.txt; exit 0");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  EXPECT_EQ(result.outcome, "success");
  EXPECT_LT(seconds, 3.0);
  EXPECT_TRUE(IsGone(std::stoi(Read("child.txt"))));
}

TEST_F(ExecControllerTest, CancellationKillsTheRunningEpisode) {
  std::atomic<bool> cancel{true};
  ExecController controller({"sleep 30", 60, &cancel});
  EXPECT_EQ(controller.RunEpisode(scene_, kSceneJson).outcome, "cancelled");
}

TEST(InterpretAnswerTest, LastNonEmptyLineIsTheAnswer) {
  ExecAnswer answer;
  answer.code = 1;
  answer.stdout_tail = "{\"outcome\": \"no-path\"}\r\n\n  \n";
  const EpisodeResult result = InterpretAnswer(answer, 60);
  EXPECT_EQ(result.outcome, "no-path");
  EXPECT_EQ(result.detail, "the controller reported no-path");
  answer.end = ExecAnswer::End::kTimedOut;
  EXPECT_EQ(InterpretAnswer(answer, 60).outcome, "timeout");
}

TEST(InterpretAnswerTest, ScoreMustBeAFiniteNumber) {
  ExecAnswer answer;
  answer.stdout_tail = "{\"outcome\": \"no-path\", \"score\": -0.25, \"gap\": 1}\n";
  EpisodeResult result = InterpretAnswer(answer, 60);
  EXPECT_EQ(result.outcome, "no-path");
  ASSERT_TRUE(result.score.has_value());
  EXPECT_EQ(*result.score, -0.25);
  EXPECT_FALSE(result.extra.contains("score"));
  EXPECT_EQ(result.extra["gap"], 1);
  for (const char* bad : {"{\"outcome\": \"success\", \"score\": \"0.5\"}",
                          "{\"outcome\": \"success\", \"score\": NaN}",
                          "{\"outcome\": \"success\", \"score\": -Infinity}",
                          "{\"outcome\": \"success\", \"score\": null}"}) {
    answer.stdout_tail = bad;
    result = InterpretAnswer(answer, 60);
    EXPECT_EQ(result.outcome, "bad-answer") << bad;
    EXPECT_NE(result.detail.find("finite number"), std::string::npos) << result.detail;
  }
  answer.stdout_tail = "{\"outcome\": \"success\"}";
  EXPECT_FALSE(InterpretAnswer(answer, 60).score.has_value());
}

TEST(ExecControllerOptionsTest, RejectsEmptyCommandAndNonPositiveTimeout) {
  EXPECT_THROW(ExecController({"", 1, nullptr}), std::invalid_argument);
  EXPECT_THROW(ExecController({"true", 0, nullptr}), std::invalid_argument);
}

}  // namespace
}  // namespace prs::harness
