// Persistent --exec workers: line workers (line_worker.h) sent one scene per line, whose answer
// line is an episode's result for that very scene. Anything that is not a proper answer in time
// ends the episode, kills the worker's process group, and the next scene starts a fresh worker.
#include "harness/persistent_controller.h"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <stdexcept>

#include "harness/child_process.h"
#include "harness/line_worker.h"

namespace prs::harness {
namespace {

using namespace internal;

const char* const kProtocolHint =
    "A persistent worker writes the line {\"ready\": true} on stdout once it has started, then "
    "reads one scene per line on stdin and answers each with one JSON line naming its \"seed\" "
    "and \"index\" (docs/harness.md); probrobscene.serve(controller) does this for a Python "
    "function";

// The answer in `line` to `scene`; anything but a proper answer kills the worker, which may
// be out of step.
EpisodeResult ReadAnswer(LineWorker& worker, const std::string& line,
                         const sampling::SampledScene& scene) {
  std::optional<EpisodeResult> result = ParseJsonAnswer(line);
  if (!result) {
    worker.Kill();
    return {"bad-answer",
            worker.Who() + " answered a line that is not JSON, and was killed",
            {{"answer", Shorten(line)}}};
  }
  if (result->outcome == "bad-answer") {
    worker.Kill();
    return *std::move(result);
  }
  if (const std::string wrong = TakeSceneIdentity(*result, scene.seed, scene.index, true);
      !wrong.empty()) {
    worker.Kill();
    return {"bad-answer",
            fmt::format("{}: {}, and was killed", worker.Who(), wrong),
            {{"answer", Shorten(line)}}};
  }
  return *std::move(result);
}

class PersistentController : public Controller {
 public:
  explicit PersistentController(std::shared_ptr<LineWorkerPool> pool) : worker_(std::move(pool)) {}

  EpisodeResult RunEpisode(const sampling::SampledScene& scene,
                           const std::string& scene_json) override {
    LineReply reply = worker_->Ask(scene_json);
    if (!reply.failure.empty()) return {std::move(reply.failure), std::move(reply.detail)};
    return ReadAnswer(*worker_, reply.line, scene);
  }

 private:
  LeasedLineWorker worker_;
};

}  // namespace

ControllerFactory MakePersistentControllerFactory(const PersistentOptions& options) {
  if (options.command.empty()) throw std::invalid_argument("persistent controller: empty command");
  if (!(options.timeout_s > 0) || !(options.startup_timeout_s > 0)) {
    throw std::invalid_argument(fmt::format(
        "persistent controller: timeouts must be > 0 s, got {:g} s per episode and {:g} s to "
        "start",
        options.timeout_s, options.startup_timeout_s));
  }
  auto pool = std::make_shared<LineWorkerPool>(
      LineWorkerOptions{.command = options.command,
                        .timeout_s = options.timeout_s,
                        .startup_timeout_s = options.startup_timeout_s,
                        .cancel = options.cancel,
                        .protocol_hint = kProtocolHint});
  return [pool]() -> std::unique_ptr<Controller> {
    return std::make_unique<PersistentController>(pool);
  };
}

}  // namespace prs::harness
