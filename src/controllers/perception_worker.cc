// Perception workers (perception_worker.h): each sighting's picture written as rgb.png and
// depth.png in the client's directory, a request line with BOP's camera fields, and an answer
// line checked before the arm is sent anywhere.
#include "controllers/perception_worker.h"

#include <fmt/format.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>

#include "dataset/dataset.h"
#include "render/render.h"

namespace prs::controllers {
namespace {

const char* const kPerceptionHint =
    "A perception worker writes the line {\"ready\": true} on stdout once its model is loaded, "
    "then reads one request per line on stdin and answers each with one JSON line naming the "
    "request's \"seed\", \"index\" and \"sighting\" and the cube's centre \"p_WCube_m\": [x, y, "
    "z] (world frame, metres), or \"found\": false (docs/harness.md, \"Perception workers\"); "
    "probrobscene.serve_perception(perceive) does this for a Python function";

// The camera in OpenCV's convention, as a dataset's scene_camera.json has it.
dataset::PinholeCamera ToOpenCv(const camera::PinholeCamera& camera) {
  render::CameraPose pose;
  pose.p_WC = camera.X_WC.translation();
  pose.forward_W = -camera.X_WC.linear().col(2);  // a MuJoCo camera looks along its −z, +y up
  pose.up_W = camera.X_WC.linear().col(1);
  return dataset::CalcPinholeCamera(pose, camera.fovy_rad * 180 / M_PI, camera.width,
                                    camera.height);
}

sim::CubeSightingAnswer Fail(harness::LineWorker& worker, const std::string& why) {
  worker.Kill();  // it may be out of step: the next sighting starts it afresh
  return {std::nullopt, "controller-error",
          fmt::format("{} {}, and was killed", worker.Who(), why)};
}

std::string Quote(const std::string& line) {
  return line.size() <= 200 ? line : line.substr(0, 197) + "...";
}

}  // namespace

std::shared_ptr<harness::LineWorkerPool> MakePerceptionPool(const PerceptionOptions& options) {
  if (options.command.empty()) throw std::invalid_argument("--perception: empty command");
  if (!(options.timeout_s > 0) || !(options.startup_timeout_s > 0)) {
    throw std::invalid_argument(
        fmt::format("--perception: timeouts must be > 0 s, got {:g} s per sighting and {:g} s to "
                    "start",
                    options.timeout_s, options.startup_timeout_s));
  }
  return std::make_shared<harness::LineWorkerPool>(
      harness::LineWorkerOptions{.command = options.command,
                                 .timeout_s = options.timeout_s,
                                 .startup_timeout_s = options.startup_timeout_s,
                                 .cancel = options.cancel,
                                 .role = "perception worker",
                                 .noun = "perception worker",
                                 .during = "while answering a sighting",
                                 .environment = {{"PRS_PERCEPTION", "1"}},
                                 .protocol_hint = kPerceptionHint});
}

PerceptionClient::PerceptionClient(std::shared_ptr<harness::LineWorkerPool> pool)
    : worker_(std::move(pool)) {
  std::string pattern = (std::filesystem::temp_directory_path() / "prs-perception-XXXXXX").string();
  if (!::mkdtemp(pattern.data())) {
    throw std::runtime_error("cannot make a directory for the perception's pictures in " +
                             std::filesystem::temp_directory_path().string());
  }
  directory_ = pattern;
}

PerceptionClient::~PerceptionClient() {
  std::error_code ignored;
  std::filesystem::remove_all(directory_, ignored);
}

sim::CubeSightingAnswer PerceptionClient::Ask(const sim::CubeSightingRequest& request) {
  const std::string rgb_path = (directory_ / "rgb.png").string();
  const std::string depth_path = (directory_ / "depth.png").string();
  render::WritePng(request.rgb, rgb_path);
  render::WriteDepthPng(request.depth, depth_path, kPerceptionDepthScale_mm);
  nlohmann::ordered_json line = {{"seed", seed_},
                                 {"index", index_},
                                 {"sighting", request.sighting},
                                 {"rgb", rgb_path},
                                 {"depth", depth_path}};
  line.update(dataset::FormatSceneCamera(ToOpenCv(request.camera), kPerceptionDepthScale_mm));
  harness::LineReply reply = worker_->Ask(line.dump());
  if (!reply.failure.empty()) {
    const std::string outcome = reply.failure == "cancelled" ? "cancelled" : "controller-error";
    return {std::nullopt, outcome, reply.failure + ": " + reply.detail};
  }
  const nlohmann::json answer = nlohmann::json::parse(reply.line, nullptr, false);
  if (!answer.is_object())
    return Fail(*worker_, "answered a line that is not JSON: " + Quote(reply.line));
  const auto names = [&](const char* key, uint64_t value) {
    return answer.contains(key) && answer[key].is_number_unsigned() &&
           answer[key].get<uint64_t>() == value;
  };
  if (!names("seed", seed_) || !names("index", index_) ||
      !names("sighting", uint64_t(request.sighting))) {
    return Fail(*worker_,
                fmt::format("answered {} to the request of seed {}, index {}, sighting {} (an "
                            "answer copies the request's \"seed\", \"index\" and \"sighting\")",
                            Quote(reply.line), seed_, index_, request.sighting));
  }
  if (answer.contains("error") && answer["error"].is_string()) {  // it failed, and says why
    return {
        std::nullopt, "controller-error",
        fmt::format("{} failed: {}", worker_->Who(), Quote(answer["error"].get<std::string>()))};
  }
  if (answer.contains("found") && answer["found"] == false) {
    const std::string detail = answer.contains("detail") && answer["detail"].is_string()
                                   ? answer["detail"].get<std::string>()
                                   : "it answered \"found\": false";
    return {std::nullopt, "perception-fault", detail};
  }
  const nlohmann::json* p = answer.contains("p_WCube_m") ? &answer["p_WCube_m"] : nullptr;
  if (!p || !p->is_array() || p->size() != 3 ||
      !std::all_of(p->begin(), p->end(), [](const nlohmann::json& x) {
        return x.is_number() && std::isfinite(x.get<double>());
      })) {
    return Fail(*worker_, "answered " + Quote(reply.line) +
                              ", without \"p_WCube_m\": three finite numbers (metres, world "
                              "frame) or \"found\": false");
  }
  return {Eigen::Vector3d((*p)[0].get<double>(), (*p)[1].get<double>(), (*p)[2].get<double>()), "",
          ""};
}

}  // namespace prs::controllers
