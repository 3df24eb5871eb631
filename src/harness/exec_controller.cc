// One process per episode with posix_spawn: stdin from a temporary scene file, stdout and
// stderr through pipes read with poll(2) until the process ends or its time is up, then its
// process group is killed and the process reaped (no zombies, no strays).
#include "harness/exec_controller.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

extern char** environ;

namespace prs::harness {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kTailBytes = 64 * 1024;
constexpr int kPollIntervalMs = 50;
// Once the process has ended, how long its pipes may stay open (held by a process that left
// the group) before they are abandoned.
constexpr auto kDrainLimit = std::chrono::seconds(1);
constexpr size_t kMaxQuotedChars = 200;

std::string DescribeErrno(int error) { return std::generic_category().message(error); }

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

// A pipe whose ends are closed on exec (so that concurrent episodes do not inherit each
// other's pipes and miss the end of file) and on destruction.
struct Pipe {
  int read_fd = -1;
  int write_fd = -1;
  Pipe() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      throw std::runtime_error("cannot create a pipe: " + DescribeErrno(errno));
    }
    read_fd = fds[0];
    write_fd = fds[1];
  }
  ~Pipe() {
    CloseRead();
    CloseWrite();
  }
  void CloseRead() { CloseFd(read_fd); }
  void CloseWrite() { CloseFd(write_fd); }

 private:
  static void CloseFd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

// The parent's environment with PRS_SCENE_FILE, PRS_SEED and PRS_INDEX set for this scene.
std::vector<std::string> MakeEnvironment(const std::string& scene_path,
                                         const sampling::SampledScene& scene) {
  const std::array<std::string, 3> ours = {"PRS_SCENE_FILE=" + scene_path,
                                           "PRS_SEED=" + std::to_string(scene.seed),
                                           "PRS_INDEX=" + std::to_string(scene.index)};
  std::vector<std::string> env;
  for (char** entry = environ; *entry; ++entry) {
    const std::string_view text(*entry);
    const bool replaced = text.starts_with("PRS_SCENE_FILE=") || text.starts_with("PRS_SEED=") ||
                          text.starts_with("PRS_INDEX=");
    if (!replaced) env.emplace_back(text);
  }
  env.insert(env.end(), ours.begin(), ours.end());
  return env;
}

// posix_spawn's C structures, destroyed on every path out.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
};

// Starts `/bin/sh -c command` in a new process group with default signal handling and an
// empty signal mask (whatever the harness blocks or catches), stdin from `stdin_path`.
pid_t SpawnShell(const std::string& command, const std::string& stdin_path, const Pipe& out,
                 const Pipe& err, const std::vector<std::string>& env) {
  SpawnSetup setup;
  posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, stdin_path.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&setup.actions, out.write_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&setup.actions, err.write_fd, STDERR_FILENO);
  sigset_t empty, defaults;
  sigemptyset(&empty);
  sigemptyset(&defaults);
  for (const int signal_number : {SIGPIPE, SIGINT, SIGTERM, SIGQUIT, SIGHUP}) {
    sigaddset(&defaults, signal_number);
  }
  posix_spawnattr_setflags(&setup.attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  posix_spawnattr_setpgroup(&setup.attributes, 0);
  posix_spawnattr_setsigmask(&setup.attributes, &empty);
  posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  std::vector<char*> envp;
  for (const std::string& entry : env) envp.push_back(const_cast<char*>(entry.c_str()));
  envp.push_back(nullptr);
  const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
  pid_t pid = -1;
  const int error = posix_spawn(&pid, "/bin/sh", &setup.actions, &setup.attributes,
                                const_cast<char* const*>(argv), envp.data());
  if (error != 0) throw std::runtime_error("cannot run /bin/sh: " + DescribeErrno(error));
  return pid;
}

// True once the process has ended. It is left unreaped (WNOWAIT), so its process group id
// cannot be reused while the group is killed.
bool HasEnded(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid != 0;
}

// Appends what is readable; returns false at end of file or on an error.
bool ReadInto(int fd, std::string& tail) {
  char buffer[16384];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) return false;
  tail.append(buffer, size_t(n));
  if (tail.size() > 2 * kTailBytes) tail.erase(0, tail.size() - kTailBytes);
  return true;
}

// A descriptor that becomes readable when the process ends (a pidfd, Linux 5.3+), so that the
// end is seen at once; -1 where pidfds are unavailable, and then the poll interval bounds the
// delay.
class ProcessFd {
 public:
  // The raw system call: Debian 12's <sys/pidfd.h> declares pidfd_open without C linkage.
  explicit ProcessFd(pid_t pid) : fd_(int(::syscall(SYS_pidfd_open, pid, 0))) {}
  ~ProcessFd() {
    if (fd_ >= 0) ::close(fd_);
  }
  ProcessFd(const ProcessFd&) = delete;
  ProcessFd& operator=(const ProcessFd&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
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
          !ReadInto(fds[i].fd, *tails[i])) {
        fds[i].fd = -1;  // end of file: poll ignores negative descriptors
      }
    }
    if (fds[2].revents != 0) fds[2].fd = -1;  // ended: HasEnded says so from now on
  }
  return answer;
}

// Reaps the process and records how it ended (unless it was killed for time or cancelling).
void Reap(pid_t pid, ExecAnswer& answer) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (answer.end != ExecAnswer::End::kExited) return;
  if (WIFSIGNALED(status)) {
    answer.end = ExecAnswer::End::kSignaled;
    answer.code = WTERMSIG(status);
  } else {
    answer.code = WEXITSTATUS(status);
  }
}

std::string_view TrimRight(std::string_view text) {
  while (!text.empty() && std::strchr(" \t\r\n", text.back())) text.remove_suffix(1);
  return text;
}

// The last line with something on it, without its line ending.
std::string LastLine(std::string_view text) {
  text = TrimRight(text);
  const size_t newline = text.rfind('\n');
  return std::string(newline == std::string_view::npos ? text : text.substr(newline + 1));
}

std::string Shorten(std::string text) {
  if (text.size() > kMaxQuotedChars) text = text.substr(0, kMaxQuotedChars) + "...";
  return text;
}

// JSON has no NaN or infinity, but Python's json.dumps prints them: `"score": NaN` (or
// Infinity, -Infinity, nan, inf), which makes the line unparsable.
bool HasNonFiniteScore(std::string_view line) {
  for (size_t at = line.find("\"score\""); at != std::string_view::npos;
       at = line.find("\"score\"", at + 1)) {
    size_t i = at + 7;
    auto skip_spaces = [&] {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    };
    skip_spaces();
    if (i >= line.size() || line[i] != ':') continue;
    ++i;
    skip_spaces();
    if (i < line.size() && (line[i] == '-' || line[i] == '+')) ++i;
    const std::string_view rest = line.substr(i);
    for (std::string_view word : {"NaN", "nan", "Infinity", "inf"}) {
      if (rest.starts_with(word)) return true;
    }
  }
  return false;
}

// {"outcome": "...", "detail": "...", ...} as a result; nullopt when `line` is not a JSON
// object (then the exit status decides).
std::optional<EpisodeResult> ParseJsonAnswer(const std::string& line) {
  if (!line.starts_with('{')) return std::nullopt;
  // Records carry the answer's other fields; writing them recurses, so bound their depth.
  constexpr int kMaxAnswerDepth = 64;
  bool too_deep = false;
  nlohmann::json answer = nlohmann::json::parse(
      line,
      [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
        too_deep = too_deep || depth > kMaxAnswerDepth;
        return true;
      },
      /*allow_exceptions=*/false);
  if (!answer.is_object()) {
    if (HasNonFiniteScore(line)) {
      return EpisodeResult{"bad-answer",
                           "the controller's \"score\" must be a finite number (larger is "
                           "safer, 0 or less a failure), not NaN or infinity",
                           {{"answer", Shorten(line)}}};
    }
    return std::nullopt;
  }
  if (too_deep) {
    return EpisodeResult{"bad-answer",
                         fmt::format("the controller's last line nests JSON more than {} levels "
                                     "deep",
                                     kMaxAnswerDepth),
                         {{"answer", Shorten(line)}}};
  }
  const auto outcome = answer.find("outcome");
  if (outcome == answer.end() || !outcome->is_string() ||
      !IsOutcomeName(outcome->get<std::string>())) {
    return EpisodeResult{"bad-answer",
                         "the controller's last line is a JSON object without a valid "
                         "\"outcome\" (a lowercase-hyphenated string such as \"no-path\")",
                         {{"answer", Shorten(line)}}};
  }
  EpisodeResult result;
  result.outcome = outcome->get<std::string>();
  answer.erase("outcome");
  const auto detail = answer.find("detail");
  if (detail != answer.end() && detail->is_string()) {
    result.detail = detail->get<std::string>();
    answer.erase("detail");
  } else {
    result.detail = "the controller reported " + result.outcome;
  }
  const auto score = answer.find("score");
  if (score != answer.end()) {
    if (!score->is_number() || !std::isfinite(score->get<double>())) {
      return EpisodeResult{"bad-answer",
                           "the controller's \"score\" must be a finite number (larger is "
                           "safer, 0 or less a failure), got " + Shorten(score->dump()),
                           {{"answer", Shorten(line)}}};
    }
    result.score = score->get<double>();
    answer.erase("score");
  }
  result.extra = std::move(answer);
  return result;
}

std::string DescribeStatus(const ExecAnswer& answer) {
  std::string text;
  if (answer.end == ExecAnswer::End::kSignaled) {
    const char* name = ::sigabbrev_np(answer.code);
    text = "the controller was killed by signal " + std::to_string(answer.code) +
           (name ? std::string(" (SIG") + name + ")" : "");
  } else {
    text = "the controller exited with code " + std::to_string(answer.code);
  }
  const std::string said = LastLine(answer.stderr_tail);
  if (answer.code != 0 && !said.empty()) text += "; its last error line: " + Shorten(said);
  return text;
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
  const pid_t pid =
      SpawnShell(options_.command, file.path(), out, err, MakeEnvironment(file.path(), scene));
  // Only the child writes now, so the pipes reach end of file when it (and its group) end.
  out.CloseWrite();
  err.CloseWrite();
  ExecAnswer answer = Supervise(pid, out, err, options_.timeout_s, options_.cancel);
  Reap(pid, answer);
  return InterpretAnswer(answer, options_.timeout_s);
}

}  // namespace prs::harness
