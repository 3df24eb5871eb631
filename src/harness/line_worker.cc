// Long-lived JSON-line workers (line_worker.h): each process is started once, sent request
// lines on a socket that is its stdin, and read one answer line per request from its stdout
// (poll(2) over stdout, stderr, the socket and a pidfd). Anything that is not an answer line in
// time kills the worker's process group, and the next request starts a fresh worker.
#include "harness/line_worker.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <optional>
#include <stdexcept>

#include "harness/child_process.h"
#include "harness/harness.h"

namespace prs::harness {
namespace {

using namespace internal;
using Clock = std::chrono::steady_clock;

constexpr size_t kStderrKeepBytes = 64 * 1024;
constexpr size_t kMaxLineBytes = 16 * 1024 * 1024;  // one answer line (or handshake) at most
constexpr int kPollIntervalMs = 50;
// Once the worker has ended, how long what it wrote before may take to arrive.
constexpr auto kDrainLimit = std::chrono::seconds(1);
// After its stdin closes, how long a worker may take to exit before its group is killed.
constexpr auto kStopGrace = std::chrono::seconds(2);

// What waiting for a line from the worker ended in.
enum class Wait { kLine, kEnded, kTimedOut, kCancelled, kTooLong };

Clock::time_point After(double seconds) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

bool IsHandshake(const std::string& line) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  return j.is_object() && j.contains("ready") && j["ready"] == true;
}

}  // namespace

// Everything public: only LineWorker, which forwards to it, sees this class.
class LineWorker::Process {
 public:
  Process(LineWorkerOptions options, int slot) : options_(std::move(options)), slot_(slot) {}
  ~Process() {
    RequestStop();
    AwaitStop(Clock::now() + kStopGrace);
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  LineReply Ask(const std::string& request) {
    if (running() && HasEnded(pid_)) Finish();  // it ended after its last answer: start afresh
    if (!running() && !Start()) return Cancelled();
    std::string line;
    switch (AwaitLine(After(options_.timeout_s), request + "\n", line)) {
      case Wait::kLine:
        return {std::move(line), "", ""};
      case Wait::kTimedOut:
        Kill();
        return {"", "timeout",
                fmt::format("{} did not answer within {:g} s and was killed", Who(),
                            options_.timeout_s)};
      case Wait::kCancelled:
        Kill();
        return Cancelled();
      case Wait::kTooLong:
        Kill();
        return {"", "bad-answer",
                fmt::format("{} wrote more than {} MiB on stdout without ending the line, and was "
                            "killed",
                            Who(), kMaxLineBytes >> 20)};
      case Wait::kEnded:
        break;
    }
    const std::string partial = out_buffer_;
    const ExitStatus status = Finish();
    LineReply reply{"",
                    status.signaled ? "signal-" + std::to_string(status.code)
                                    : "exit-" + std::to_string(status.code),
                    DescribeExit(status, "", Who()) + " " + options_.during + LastErrorLine()};
    if (!partial.empty()) reply.detail += "; it had written part of a line: " + Shorten(partial);
    return reply;
  }

  // Closes the worker's stdin: a worker exits when its input ends.
  void RequestStop() {
    if (stdin_fd_ >= 0) ::close(stdin_fd_);
    stdin_fd_ = -1;
  }

  // Waits until the worker has exited or `deadline`, then kills its group and reaps it.
  void AwaitStop(Clock::time_point deadline) {
    if (!running()) return;
    while (!HasEnded(pid_) && Clock::now() < deadline) {
      if (!Drain(std::min(deadline, Clock::now() + std::chrono::milliseconds(kPollIntervalMs)))) {
        break;
      }
    }
    Finish();
  }

  bool running() const { return pid_ > 0; }

  std::vector<std::pair<std::string, std::string>> Environment() const {
    auto environment = options_.environment;
    environment.emplace_back("PRS_WORKER", std::to_string(slot_));
    return environment;
  }

  std::string Who() const {
    return fmt::format("the {} '{}' (worker {})", options_.role, Shorten(options_.command), slot_);
  }

  LineReply Cancelled() const {
    return {"", "cancelled", "the run was interrupted and the " + options_.noun + " was killed"};
  }

  // Starts the process and waits for its handshake; false when cancelled meanwhile. Throws
  // ControllerStartError when it cannot start.
  bool Start() {
    if (options_.cancel && options_.cancel->load(std::memory_order_relaxed)) return false;
    Launch();
    std::string line;
    switch (AwaitLine(After(options_.startup_timeout_s), {}, line)) {
      case Wait::kLine:
        if (IsHandshake(line)) return true;
        Kill();
        throw ControllerStartError(
            fmt::format("{} began with the line {} instead of its "
                        "handshake. {}",
                        Who(), Shorten(line), options_.protocol_hint));
      case Wait::kTimedOut:
        Kill();
        throw ControllerStartError(fmt::format(
            "{} sent no handshake within {:g} s{}. {}, or give it longer with --startup-timeout",
            Who(), options_.startup_timeout_s, LastErrorLine(), options_.protocol_hint));
      case Wait::kCancelled:
        Kill();
        return false;
      case Wait::kTooLong:
        Kill();
        throw ControllerStartError(fmt::format(
            "{} wrote more than {} MiB on stdout without ending the line before its handshake. {}",
            Who(), kMaxLineBytes >> 20, options_.protocol_hint));
      case Wait::kEnded:
        break;
    }
    const ExitStatus status = Finish();
    throw ControllerStartError(fmt::format("{} before its handshake{}. {}",
                                           DescribeExit(status, "", Who()), LastErrorLine(),
                                           options_.protocol_hint));
  }

  std::string LastErrorLine() const {
    const std::string said = LastLine(err_tail_);
    return said.empty() ? "" : "; its last error line: " + Shorten(said);
  }

  // Spawns `/bin/sh -c COMMAND` with a socket as stdin (written with MSG_NOSIGNAL, so a worker
  // that is gone cannot kill the harness with SIGPIPE) and pipes as stdout and stderr.
  void Launch() {
    int sockets[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
      throw ControllerStartError("cannot create a socket for the " + options_.role + ": " +
                                 DescribeErrno(errno));
    }
    out_ = std::make_unique<Pipe>();
    err_ = std::make_unique<Pipe>();
    try {
      pid_ = SpawnShell(options_.command,
                        {.stdin_path = {},
                         .stdin_fd = sockets[1],
                         .stdout_fd = out_->write_fd,
                         .stderr_fd = err_->write_fd},
                        MakeEnvironment(Environment()));
    } catch (const std::exception& error) {
      ::close(sockets[0]);
      ::close(sockets[1]);
      throw ControllerStartError(error.what());
    }
    ::close(sockets[1]);
    out_->CloseWrite();  // only the worker writes now: end of file when its group ends
    err_->CloseWrite();
    stdin_fd_ = sockets[0];
    ::fcntl(stdin_fd_, F_SETFL, ::fcntl(stdin_fd_, F_GETFL) | O_NONBLOCK);
    process_ = std::make_unique<ProcessFd>(pid_);
    process_ended_ = false;
    out_buffer_.clear();
    err_tail_.clear();
  }

  // Takes the next complete stdout line that starts with '{' into `line`; lines that do not
  // (a library's chatter) are dropped. False when no such line is complete yet.
  bool TakeLine(std::string& line) {
    for (size_t end; (end = out_buffer_.find('\n')) != std::string::npos;) {
      std::string text = out_buffer_.substr(0, end);
      out_buffer_.erase(0, end + 1);
      const size_t first = text.find_first_not_of(" \t\r");
      if (first == std::string::npos || text[first] != '{') continue;
      while (!text.empty() && (text.back() == '\r' || text.back() == ' ')) text.pop_back();
      line = text.substr(first);
      return true;
    }
    return false;
  }

  // Sends `request` (when not empty) and reads until a line, the worker's end, `deadline` or
  // cancellation.
  Wait AwaitLine(Clock::time_point deadline, std::string request, std::string& line) {
    std::string_view unsent = request;
    std::optional<Clock::time_point> ended_at;
    while (true) {
      if (TakeLine(line)) return Wait::kLine;
      if (out_buffer_.size() > kMaxLineBytes) return Wait::kTooLong;
      if (ended_at) {
        if (out_->read_fd < 0 || Clock::now() - *ended_at > kDrainLimit) return Wait::kEnded;
      } else if (HasEnded(pid_) || out_->read_fd < 0) {
        ended_at = Clock::now();  // read on: what it wrote before it ended may still be in the pipe
      } else if (options_.cancel && options_.cancel->load(std::memory_order_relaxed)) {
        return Wait::kCancelled;
      } else if (Clock::now() >= deadline) {
        return Wait::kTimedOut;
      }
      if (!unsent.empty() && !Send(unsent)) unsent = {};  // it closed its stdin: wait for its end
      const auto next =
          std::min(deadline, Clock::now() + std::chrono::milliseconds(kPollIntervalMs));
      if (!Drain(next, !unsent.empty())) return Wait::kEnded;
    }
  }

  // Writes what the socket takes now; false when the worker no longer reads.
  bool Send(std::string_view& unsent) {
    while (!unsent.empty()) {
      const ssize_t n =
          ::send(stdin_fd_, unsent.data(), unsent.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
      if (n <= 0) return false;
      unsent.remove_prefix(size_t(n));
    }
    return true;
  }

  // One poll until `until` over stdout, stderr, the process (and stdin when `writing`), reading
  // what has arrived. False when poll itself fails.
  bool Drain(Clock::time_point until, bool writing = false) {
    std::array<pollfd, 4> fds = {pollfd{out_->read_fd, POLLIN, 0}, pollfd{err_->read_fd, POLLIN, 0},
                                 pollfd{process_ended_ ? -1 : process_->fd(), POLLIN, 0},
                                 pollfd{writing ? stdin_fd_ : -1, POLLOUT, 0}};
    const auto wait_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    const int timeout_ms = int(std::clamp<int64_t>(wait_ms.count(), 0, kPollIntervalMs));
    if (::poll(fds.data(), fds.size(), timeout_ms) < 0 && errno != EINTR) return false;
    if (fds[0].revents != 0 && !ReadInto(out_->read_fd, out_buffer_, kMaxLineBytes)) {
      out_->CloseRead();  // end of file: the worker (and its group) closed its stdout
    }
    if (fds[1].revents != 0 && !ReadInto(err_->read_fd, err_tail_, kStderrKeepBytes)) {
      err_->CloseRead();
    }
    process_ended_ = process_ended_ || fds[2].revents != 0;  // stays readable: poll it no more
    return true;
  }

  // Kills the worker's process group and reaps it.
  void Kill() {
    if (running()) Finish();
  }

  // Kills what is left of the worker's group (it may have left children), reaps the worker
  // (unreaped until now, so its group id cannot have been reused), and closes its descriptors.
  ExitStatus Finish() {
    ::kill(-pid_, SIGKILL);
    const ExitStatus status = Reap(pid_);
    pid_ = -1;
    RequestStop();
    out_.reset();
    err_.reset();
    process_.reset();
    return status;
  }

  const LineWorkerOptions options_;
  const int slot_;
  pid_t pid_ = -1;
  int stdin_fd_ = -1;  // our end of the socket that is the worker's stdin
  std::unique_ptr<Pipe> out_, err_;
  std::unique_ptr<ProcessFd> process_;
  bool process_ended_ = false;  // its pidfd has fired
  std::string out_buffer_;      // stdout not yet taken as lines
  std::string err_tail_;        // the end of stderr, for messages
};

LineWorker::LineWorker(LineWorkerOptions options, int slot)
    : process_(std::make_unique<Process>(std::move(options), slot)) {}
LineWorker::~LineWorker() = default;
LineReply LineWorker::Ask(const std::string& request) { return process_->Ask(request); }
void LineWorker::Kill() { process_->Kill(); }
std::string LineWorker::Who() const { return process_->Who(); }
std::string LineWorker::LastErrorLine() const { return process_->LastErrorLine(); }
void LineWorker::RequestStop() { process_->RequestStop(); }
void LineWorker::AwaitStop(Clock::time_point deadline) { process_->AwaitStop(deadline); }

LineWorkerPool::~LineWorkerPool() {
  // Every worker is asked to stop first, so that they exit side by side.
  for (auto& worker : idle_) worker->RequestStop();
  const auto deadline = Clock::now() + kStopGrace;
  for (auto& worker : idle_) worker->AwaitStop(deadline);
}

std::unique_ptr<LineWorker> LineWorkerPool::Take() {
  std::lock_guard lock(mutex_);
  if (idle_.empty()) return std::make_unique<LineWorker>(options_, next_slot_++);
  std::unique_ptr<LineWorker> worker = std::move(idle_.back());
  idle_.pop_back();
  return worker;
}

void LineWorkerPool::Give(std::unique_ptr<LineWorker> worker) {
  std::lock_guard lock(mutex_);
  idle_.push_back(std::move(worker));
}

}  // namespace prs::harness
