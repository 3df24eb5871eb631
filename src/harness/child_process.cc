// Process plumbing and answer rules shared by ExecController (one process per episode) and the
// persistent workers (one process per worker thread).
#include "harness/child_process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>

extern char** environ;

namespace prs::harness::internal {
namespace {

constexpr size_t kMaxQuotedChars = 200;

void CloseFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
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

std::string_view TrimRight(std::string_view text) {
  while (!text.empty() && std::strchr(" \t\r\n", text.back())) text.remove_suffix(1);
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

}  // namespace

std::string DescribeErrno(int error) { return std::generic_category().message(error); }

Pipe::Pipe() {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    throw std::runtime_error("cannot create a pipe: " + DescribeErrno(errno));
  }
  read_fd = fds[0];
  write_fd = fds[1];
}

Pipe::~Pipe() {
  CloseRead();
  CloseWrite();
}

void Pipe::CloseRead() { CloseFd(read_fd); }
void Pipe::CloseWrite() { CloseFd(write_fd); }

// The raw system call: Debian 12's <sys/pidfd.h> declares pidfd_open without C linkage.
ProcessFd::ProcessFd(pid_t pid) : fd_(int(::syscall(SYS_pidfd_open, pid, 0))) {}

ProcessFd::~ProcessFd() {
  if (fd_ >= 0) ::close(fd_);
}

std::vector<std::string> MakeEnvironment(
    const std::vector<std::pair<std::string, std::string>>& ours) {
  static constexpr std::string_view kScenePrefixes[] = {
      "PRS_SCENE_FILE=", "PRS_SEED=", "PRS_INDEX=", "PRS_PERSISTENT=", "PRS_WORKER="};
  std::vector<std::string> env;
  for (char** entry = environ; *entry; ++entry) {
    const std::string_view text(*entry);
    bool replaced = false;
    for (const std::string_view prefix : kScenePrefixes) replaced |= text.starts_with(prefix);
    if (!replaced) env.emplace_back(text);
  }
  for (const auto& [name, value] : ours) env.push_back(name + "=" + value);
  return env;
}

pid_t SpawnShell(const std::string& command, const ChildStdio& stdio,
                 const std::vector<std::string>& env) {
  SpawnSetup setup;
  if (!stdio.stdin_path.empty()) {
    posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, stdio.stdin_path.c_str(),
                                     O_RDONLY, 0);
  } else {
    posix_spawn_file_actions_adddup2(&setup.actions, stdio.stdin_fd, STDIN_FILENO);
  }
  posix_spawn_file_actions_adddup2(&setup.actions, stdio.stdout_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&setup.actions, stdio.stderr_fd, STDERR_FILENO);
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

bool HasEnded(pid_t pid) {
  siginfo_t info{};
  return ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid != 0;
}

bool ReadInto(int fd, std::string& tail, size_t keep) {
  char buffer[16384];
  const ssize_t n = ::read(fd, buffer, sizeof buffer);
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) return false;
  tail.append(buffer, size_t(n));
  if (tail.size() > 2 * keep) tail.erase(0, tail.size() - keep);
  return true;
}

ExitStatus ReadShellExitCode(int code) {
  // Signals 1 to 31 are the ones with names (sigabbrev_np); the real-time ones above are not
  // sent by crashes, and 160 to 255 stay exit codes.
  constexpr int kLastNamedSignal = 31;
  const int signal_number = code - 128;
  if (signal_number >= 1 && signal_number <= kLastNamedSignal) {
    return {true, signal_number, code};
  }
  return {false, code};
}

ExitStatus Reap(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) return {true, WTERMSIG(status)};
  return ReadShellExitCode(WEXITSTATUS(status));
}

std::string DescribeExit(const ExitStatus& status, std::string_view stderr_tail,
                         std::string_view who) {
  std::string text;
  if (status.signaled) {
    const char* name = ::sigabbrev_np(status.code);
    std::string about;
    if (name) about = std::string("SIG") + name;
    if (status.shell_status != 0) {
      about += fmt::format("{}/bin/sh reported exit status {}", about.empty() ? "" : "; ",
                           status.shell_status);
    }
    text = fmt::format("{} was killed by signal {}{}", who, status.code,
                       about.empty() ? "" : " (" + about + ")");
  } else {
    text = fmt::format("{} exited with code {}", who, status.code);
  }
  const std::string said = LastLine(stderr_tail);
  if (status.code != 0 && !said.empty()) text += "; its last error line: " + Shorten(said);
  return text;
}

std::string LastLine(std::string_view text) {
  text = TrimRight(text);
  const size_t newline = text.rfind('\n');
  return std::string(newline == std::string_view::npos ? text : text.substr(newline + 1));
}

std::string Shorten(std::string text) {
  if (text.size() > kMaxQuotedChars) text = text.substr(0, kMaxQuotedChars) + "...";
  return text;
}

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
                         fmt::format("the controller's answer nests JSON more than {} levels "
                                     "deep",
                                     kMaxAnswerDepth),
                         {{"answer", Shorten(line)}}};
  }
  const auto outcome = answer.find("outcome");
  if (outcome == answer.end() || !outcome->is_string() ||
      !IsOutcomeName(outcome->get<std::string>())) {
    return EpisodeResult{"bad-answer",
                         "the controller's answer is a JSON object without a valid "
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
                           "safer, 0 or less a failure), got " +
                               Shorten(score->dump()),
                           {{"answer", Shorten(line)}}};
    }
    result.score = score->get<double>();
    answer.erase("score");
  }
  result.extra = std::move(answer);
  return result;
}

std::string TakeSceneIdentity(EpisodeResult& result, uint64_t seed, uint64_t index, bool required) {
  nlohmann::json& extra = result.extra;
  const bool has_seed = extra.is_object() && extra.contains("seed");
  const bool has_index = extra.is_object() && extra.contains("index");
  if (!has_seed && !has_index && !required) return "";
  if (!has_seed || !has_index) {
    return "the answer does not name its scene: copy the scene's \"seed\" and \"index\" into it";
  }
  const nlohmann::json& said_seed = extra["seed"];
  const nlohmann::json& said_index = extra["index"];
  if (!said_seed.is_number_unsigned() || !said_index.is_number_unsigned() ||
      said_seed.get<uint64_t>() != seed || said_index.get<uint64_t>() != index) {
    return fmt::format(
        "the answer is for another scene (seed {}, index {}) than the one sent "
        "(seed {}, index {})",
        Shorten(said_seed.dump()), Shorten(said_index.dump()), seed, index);
  }
  extra.erase("seed");
  extra.erase("index");
  return "";
}

}  // namespace prs::harness::internal
