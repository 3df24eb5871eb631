// What both kinds of --exec controller need to run a user's program: pipes, posix_spawn of
// `/bin/sh -c CMD` in a process group of its own, the end of a process seen through a pidfd,
// and the rules that read a JSON answer line (docs/harness.md). Internal to src/harness.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "harness/harness.h"

namespace prs::harness::internal {

/// strerror's text for `error`.
std::string DescribeErrno(int error);

/// A pipe whose ends are closed on exec (so that concurrent children do not inherit each
/// other's pipes and miss the end of file) and on destruction.
struct Pipe {
  int read_fd = -1;
  int write_fd = -1;
  Pipe();  // throws std::runtime_error when no pipe can be made
  ~Pipe();
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  void CloseRead();
  void CloseWrite();
};

/// A descriptor that becomes readable when the process ends (a pidfd, Linux 5.3+), so that the
/// end is seen at once; fd() is -1 where pidfds are unavailable.
class ProcessFd {
 public:
  explicit ProcessFd(pid_t pid);
  ~ProcessFd();
  ProcessFd(const ProcessFd&) = delete;
  ProcessFd& operator=(const ProcessFd&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

/// The parent's environment with `ours` set, and without any inherited PRS_SCENE_FILE,
/// PRS_SEED, PRS_INDEX, PRS_PERSISTENT or PRS_WORKER (they would describe another scene).
std::vector<std::string> MakeEnvironment(
    const std::vector<std::pair<std::string, std::string>>& ours);

/// Where the child's standard streams come from: stdin from the file `stdin_path` when it is
/// not empty, else from the descriptor `stdin_fd`.
struct ChildStdio {
  std::string stdin_path;
  int stdin_fd = -1;
  int stdout_fd = -1;
  int stderr_fd = -1;
};

/// Starts `/bin/sh -c command` in a new process group with default signal handling and an
/// empty signal mask (whatever the harness blocks or catches). Throws std::runtime_error when
/// /bin/sh cannot be run.
pid_t SpawnShell(const std::string& command, const ChildStdio& stdio,
                 const std::vector<std::string>& env);

/// True once the process has ended. It is left unreaped (WNOWAIT), so its process group id
/// cannot be reused while the group is killed.
bool HasEnded(pid_t pid);

/// Appends what is readable from `fd` to `tail`, keeping at most 2 * `keep` bytes (the end);
/// returns false at end of file or on an error.
bool ReadInto(int fd, std::string& tail, size_t keep);

/// How a reaped process ended.
struct ExitStatus {
  bool signaled = false;
  int code = 0;  // exit code, or the signal number
  /// When `signaled` because /bin/sh reported that the command it ran was killed by signal N:
  /// the shell's exit status, 128 + N. 0 when the process itself was killed, or exited.
  int shell_status = 0;
};

/// How `/bin/sh -c` ended, from its exit code: a shell reports a command killed by signal N as
/// the exit status 128 + N, so a code from 129 to 159 (N a signal from 1 to 31, SIGHUP to
/// SIGSYS) is read as death by signal N (with shell_status set); any other code as itself.
ExitStatus ReadShellExitCode(int code);

/// Waits for the process and returns how it ended: killed by a signal, or its exit code read by
/// ReadShellExitCode (every process the harness reaps is a `/bin/sh -c`).
ExitStatus Reap(pid_t pid);

/// "the controller exited with code 3; its last error line: ..." (or "was killed by signal 9
/// (SIGKILL)", and "signal 11 (SIGSEGV; /bin/sh reported exit status 139)" when the shell
/// reported it), `who` naming the program.
std::string DescribeExit(const ExitStatus& status, std::string_view stderr_tail,
                         std::string_view who = "the controller");

/// The last line of `text` with something on it, without its line ending.
std::string LastLine(std::string_view text);

/// `text` cut to 200 characters (with "...") for quoting in a message.
std::string Shorten(std::string text);

/// {"outcome": "...", "detail": "...", "score": ..., ...} as a result (a malformed object gives
/// "bad-answer"); nullopt when `line` is not a JSON object.
std::optional<EpisodeResult> ParseJsonAnswer(const std::string& line);

/// Checks the "seed" and "index" an answer may carry (EpisodeResult::extra) against the scene
/// and removes them: "" when they match (or, unless `required`, are absent), else why not.
std::string TakeSceneIdentity(EpisodeResult& result, uint64_t seed, uint64_t index, bool required);

}  // namespace prs::harness::internal
