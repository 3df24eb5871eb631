// A long-lived helper program that answers one JSON line per request line: a persistent
// --exec controller (persistent_controller.h) or a perception worker (`prs test --perception`,
// bound in src/controllers). Started on first use, it sends the handshake {"ready": true}; each
// request gets one answer line within a timeout, and a worker that ends, hangs, floods its
// stdout or is cancelled is killed with its process group and started afresh on the next
// request (protocol in docs/harness.md).
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace prs::harness {

struct LineWorkerOptions {
  std::string command;             // run as `/bin/sh -c COMMAND`
  double timeout_s = 60;           // per request, from the line sent to the answer read
  double startup_timeout_s = 120;  // from the start to the handshake line
  /// Polled between reads; once true the worker is killed and the request is "cancelled".
  const std::atomic<bool>* cancel = nullptr;
  /// What the worker is, for messages: "the {role} 'COMMAND' (worker K)", "the {noun} was
  /// killed", and "... exited with code 3 {during}".
  std::string role = "persistent controller";
  std::string noun = "controller";
  std::string during = "during the episode";
  /// Set in the worker's environment, with PRS_WORKER=K.
  std::vector<std::pair<std::string, std::string>> environment = {{"PRS_PERSISTENT", "1"}};
  /// The end of every start error: what a worker must do.
  std::string protocol_hint;
};

/// What one request came to. `failure` is empty when `line` is the answer; otherwise the
/// worker has been killed (it starts afresh on the next request) and `failure` is "timeout",
/// "exit-N", "signal-N", "bad-answer" (a line of more than 16 MiB) or "cancelled", with a
/// sentence in `detail` naming the worker, what happened and its last error line.
struct LineReply {
  std::string line;
  std::string failure;
  std::string detail;
};

/// One worker process, used by one thread at a time. Not running until the first Ask.
class LineWorker {
 public:
  LineWorker(LineWorkerOptions options, int slot);
  ~LineWorker();  // RequestStop, then AwaitStop for 2 s
  LineWorker(const LineWorker&) = delete;
  LineWorker& operator=(const LineWorker&) = delete;

  /// Starts the worker when it is not running (throws ControllerStartError when it cannot
  /// start: it exits, or sends no handshake in time), writes `request` and a line end, and
  /// reads the first answer line (a stdout line that starts with '{'; others are ignored).
  LineReply Ask(const std::string& request);
  /// Kills the worker's process group (after an answer that is not one), so that the next
  /// request starts it afresh.
  void Kill();
  /// "the perception worker 'python3 perceive.py' (worker 0)".
  std::string Who() const;
  /// "; its last error line: ..." or "".
  std::string LastErrorLine() const;

  /// Closes the worker's stdin: a worker exits when its input ends.
  void RequestStop();
  /// Waits until the worker has exited or `deadline`, then kills its group and reaps it.
  void AwaitStop(std::chrono::steady_clock::time_point deadline);

 private:
  class Process;
  std::unique_ptr<Process> process_;
};

/// The workers of one factory (each thread's controller takes one and gives it back), so that
/// a search's generations reuse them; at most as many run as are taken at once.
class LineWorkerPool {
 public:
  explicit LineWorkerPool(LineWorkerOptions options) : options_(std::move(options)) {}
  ~LineWorkerPool();  // asks every idle worker to stop, side by side
  LineWorkerPool(const LineWorkerPool&) = delete;
  LineWorkerPool& operator=(const LineWorkerPool&) = delete;

  std::unique_ptr<LineWorker> Take();
  void Give(std::unique_ptr<LineWorker> worker);

 private:
  const LineWorkerOptions options_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<LineWorker>> idle_;
  int next_slot_ = 0;
};

/// A worker taken from a pool for the lifetime of this lease (one controller's).
class LeasedLineWorker {
 public:
  explicit LeasedLineWorker(std::shared_ptr<LineWorkerPool> pool)
      : pool_(std::move(pool)), worker_(pool_->Take()) {}
  ~LeasedLineWorker() { pool_->Give(std::move(worker_)); }
  LeasedLineWorker(const LeasedLineWorker&) = delete;
  LeasedLineWorker& operator=(const LeasedLineWorker&) = delete;
  LineWorker& operator*() { return *worker_; }
  LineWorker* operator->() { return worker_.get(); }

 private:
  std::shared_ptr<LineWorkerPool> pool_;
  std::unique_ptr<LineWorker> worker_;
};

}  // namespace prs::harness
