// One process per episode with posix_spawn: stdin from a temporary scene file, stdout and
// stderr through pipes read with poll(2) until the process ends or its time is up, then its
// process group is killed and the process reaped (no zombies, no strays).
#include "harness/exec_controller.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "harness/child_process.h"

namespace prs::harness {
namespace {

using namespace internal;
using Clock = std::chrono::steady_clock;
constexpr size_t kTailBytes = 64 * 1024;
constexpr int kPollIntervalMs = 50;
// Once the process has ended, how long its pipes may stay open (held by a process that left
// the group) before they are abandoned.
constexpr auto kDrainLimit = std::chrono::seconds(1);

// The scene written to a fresh temporary file, removed when this goes out of scope.
class SceneFile {
 public:
  explicit SceneFile(const std::string& scene_json) {
    const char* tmpdir = std::getenv("TMPDIR");
    const std::string dir = tmpdir && *tmpdir ? tmpdir : "/tmp";
    std::string path = dir + "/prs-scene-XXXXXX.json";
    const int fd = ::mkostemps(path.data(), 5, O_CLOEXEC);
    if (fd < 0) {
      throw std::runtime_error("cannot create a scene file in " + dir + ": " +
                               DescribeErrno(errno));
    }
    path_ = path;
    const std::string line = scene_json + "\n";
    const bool written = WriteAll(fd, line);
    const int error = errno;
    ::close(fd);
    if (!written) throw std::runtime_error("cannot write " + path_ + ": " + DescribeErrno(error));
  }
  ~SceneFile() { ::unlink(path_.c_str()); }
  SceneFile(const SceneFile&) = delete;
  SceneFile& operator=(const SceneFile&) = delete;

  const std::string& path() const { return path_; }

 private:
  static bool WriteAll(int fd, std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::write(fd, bytes.data(), bytes.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      bytes.remove_prefix(size_t(n));
    }
    return true;
  }

  std::string path_;
};

// Reads the pipes until the process has ended and they are closed, killing the process
// group when it ends, at the deadline, or on cancellation. Leaves the process unreaped.
ExecAnswer Supervise(pid_t pid, Pipe& out, Pipe& err, double timeout_s,
                     const std::atomic<bool>* cancel) {
  ExecAnswer answer;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
  std::optional<Clock::time_point> ended_at;
  const ProcessFd process(pid);
  std::array<pollfd, 3> fds = {pollfd{out.read_fd, POLLIN, 0}, pollfd{err.read_fd, POLLIN, 0},
                               pollfd{process.fd(), POLLIN, 0}};
  std::array<std::string*, 2> tails = {&answer.stdout_tail, &answer.stderr_tail};
  while (true) {
    const bool cancelled = cancel && cancel->load(std::memory_order_relaxed);
    if (!ended_at && (cancelled || Clock::now() >= deadline || HasEnded(pid))) {
      if (!HasEnded(pid))
        answer.end = cancelled ? ExecAnswer::End::kCancelled : ExecAnswer::End::kTimedOut;
      ::kill(-pid, SIGKILL);  // the whole group: the shell, the controller, their children
      ended_at = Clock::now();
    }
    const bool pipes_open = fds[0].fd >= 0 || fds[1].fd >= 0;
    if (ended_at && (!pipes_open || Clock::now() - *ended_at > kDrainLimit)) break;
    if (::poll(fds.data(), fds.size(), kPollIntervalMs) < 0 && errno != EINTR) break;
    for (size_t i = 0; i < tails.size(); ++i) {
      if (fds[i].fd >= 0 && (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) &&
          !ReadInto(fds[i].fd, *tails[i], kTailBytes)) {
        fds[i].fd = -1;  // end of file: poll ignores negative descriptors
      }
    }
    if (fds[2].revents != 0) fds[2].fd = -1;  // ended: HasEnded says so from now on
  }
  return answer;
}

// Reaps the process and records how it ended (unless it was killed for time or cancelling).
void ReapInto(pid_t pid, ExecAnswer& answer) {
  const ExitStatus status = Reap(pid);
  if (answer.end != ExecAnswer::End::kExited) return;
  if (status.signaled) answer.end = ExecAnswer::End::kSignaled;
  answer.code = status.code;
  answer.shell_status = status.shell_status;
}

std::string DescribeStatus(const ExecAnswer& answer) {
  return DescribeExit(
      {answer.end == ExecAnswer::End::kSignaled, answer.code, answer.shell_status},
      answer.stderr_tail);
}

}  // namespace

EpisodeResult InterpretAnswer(const ExecAnswer& answer, double timeout_s) {
  switch (answer.end) {
    case ExecAnswer::End::kTimedOut:
      return {"timeout",
              fmt::format("the controller did not finish within {:g} s and was killed", timeout_s)};
    case ExecAnswer::End::kCancelled:
      return {"cancelled", "the run was interrupted and the controller was killed"};
    case ExecAnswer::End::kExited:
    case ExecAnswer::End::kSignaled:
      break;
  }
  if (auto result = ParseJsonAnswer(LastLine(answer.stdout_tail))) return *std::move(result);
  if (answer.end == ExecAnswer::End::kSignaled) {
    return {"signal-" + std::to_string(answer.code), DescribeStatus(answer)};
  }
  if (answer.code == 0) return {"success", DescribeStatus(answer)};
  return {"exit-" + std::to_string(answer.code), DescribeStatus(answer)};
}

ExecController::ExecController(ExecOptions options) : options_(std::move(options)) {
  if (options_.command.empty()) throw std::invalid_argument("ExecController: empty command");
  if (!(options_.timeout_s > 0)) {
    throw std::invalid_argument("ExecController: timeout must be > 0 s, got " +
                                std::to_string(options_.timeout_s));
  }
}

EpisodeResult ExecController::RunEpisode(const sampling::SampledScene& scene,
                                         const std::string& scene_json) {
  const SceneFile file(scene_json);
  Pipe out, err;
  const pid_t pid = SpawnShell(options_.command,
                               {.stdin_path = file.path(), .stdout_fd = out.write_fd,
                                .stderr_fd = err.write_fd},
                               MakeEnvironment({{"PRS_SCENE_FILE", file.path()},
                                                {"PRS_SEED", std::to_string(scene.seed)},
                                                {"PRS_INDEX", std::to_string(scene.index)}}));
  // Only the child writes now, so the pipes reach end of file when it (and its group) end.
  out.CloseWrite();
  err.CloseWrite();
  ExecAnswer answer = Supervise(pid, out, err, options_.timeout_s, options_.cancel);
  ReapInto(pid, answer);
  EpisodeResult result = InterpretAnswer(answer, options_.timeout_s);
  // An answer may name its scene, as persistent workers must (docs/harness.md).
  if (const std::string wrong = TakeSceneIdentity(result, scene.seed, scene.index, false);
      !wrong.empty()) {
    return {"bad-answer", wrong, {{"answer", Shorten(LastLine(answer.stdout_tail))}}};
  }
  return result;
}

}  // namespace prs::harness
