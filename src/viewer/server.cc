// The `prs view` HTTP server (cpp-httplib, Debian's libcpp-httplib-dev): the page, the script,
// and scenes sampled on request by one SceneSampler behind a mutex (sampling is fast next to
// a person clicking; the sampler's caches then serve every request).
#include <charconv>
#include <mutex>
#include <optional>

#include "output/scene_json.h"
#include "viewer/assets.h"
#include "viewer/viewer.h"

// After Eigen: included first, a macro from the system headers it pulls in breaks Eigen's.
#include <httplib.h>

namespace prs::viewer {
namespace {

constexpr int kBadRequest = 400;
constexpr int kUnprocessable = 422;  // the request was fine; the scenario cannot give the scene
constexpr const char* kJson = "application/json";

// A query parameter holding a 64-bit unsigned integer, or an error message naming it.
std::optional<uint64_t> ParseIndexParam(const httplib::Request& request, const char* name,
                                        std::string& error) {
  if (!request.has_param(name)) {
    error = std::string("missing query parameter '") + name + "' (e.g. ?seed=0&index=0)";
    return std::nullopt;
  }
  const std::string text = request.get_param_value(name);
  uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, failure] = std::from_chars(text.data(), end, value);
  if (text.empty() || failure != std::errc() || stop != end) {
    error = std::string("query parameter '") + name +
            "' expects an integer from 0 to 2^64 - 1, got '" + text + "'";
    return std::nullopt;
  }
  return value;
}

}  // namespace

struct ViewerServer::Impl {
  Impl(const lang::CompiledProgram& program, const sampling::SampleOptions& options, PageInfo page)
      : program(&program), page(std::move(page)) {
    sampler.emplace(program, options);
  }
  explicit Impl(std::string standalone_page) : fixed_page(std::move(standalone_page)) {}
  void AddRoutes();
  // Samples the scene the request names and answers with `format`'s text, or an error record.
  void AnswerScene(const httplib::Request& request, httplib::Response& response,
                   std::string (*format)(const sampling::SampledScene&));

  const lang::CompiledProgram* program = nullptr;  // null: a fixed page, nothing to sample
  std::mutex sampler_mutex;
  std::optional<sampling::SceneSampler> sampler;
  PageInfo page;
  std::string fixed_page;
  httplib::Server http;
};

void ViewerServer::Impl::AnswerScene(const httplib::Request& request, httplib::Response& response,
                                     std::string (*format)(const sampling::SampledScene&)) {
  if (!sampler) {
    response.status = kBadRequest;
    response.set_content(FormatErrorRecord("not-sampling",
                                           "this viewer shows the scenes of a "
                                           "scenes file and samples nothing"),
                         kJson);
    return;
  }
  std::string error;
  const auto seed = ParseIndexParam(request, "seed", error);
  const auto index = seed ? ParseIndexParam(request, "index", error) : std::nullopt;
  if (!index) {
    response.status = kBadRequest;
    response.set_content(FormatErrorRecord("bad-request", error), kJson);
    return;
  }
  try {
    const std::lock_guard lock(sampler_mutex);
    response.set_content(format(sampler->Sample(*seed, *index)), kJson);
  } catch (const lang::ScenarioError& failure) {
    response.status = kUnprocessable;
    const std::string message =
        lang::RenderDiagnostic(failure.diagnostic(), program->sources, false);
    response.set_content(FormatErrorRecord(failure.diagnostic().id, message), kJson);
  }
}

void ViewerServer::Impl::AddRoutes() {
  http.Get("/", [this](const httplib::Request&, httplib::Response& response) {
    response.set_content(fixed_page.empty() ? MakeServedPage(page) : fixed_page,
                         "text/html; charset=utf-8");
  });
  http.Get("/viewer.js", [](const httplib::Request&, httplib::Response& response) {
    const std::string_view script = ViewerScript();
    response.set_content(script.data(), script.size(), "text/javascript; charset=utf-8");
  });
  http.Get("/view", [this](const httplib::Request& request, httplib::Response& response) {
    AnswerScene(request, response, FormatViewRecord);
  });
  http.Get("/scene", [this](const httplib::Request& request, httplib::Response& response) {
    AnswerScene(request, response, output::FormatSceneJson);
  });
  // Unknown paths: a JSON error rather than an empty 404 body.
  http.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    if (response.status != 404) return;
    response.set_content(FormatErrorRecord("not-found", "no such page: " + request.path), kJson);
  });
}

ViewerServer::ViewerServer(const lang::CompiledProgram& program,
                           const sampling::SampleOptions& options, PageInfo page)
    : impl_(std::make_unique<Impl>(program, options, std::move(page))) {
  Configure();
}

ViewerServer::ViewerServer(std::string standalone_page)
    : impl_(std::make_unique<Impl>(std::move(standalone_page))) {
  Configure();
}

void ViewerServer::Configure() {
  impl_->AddRoutes();
  // httplib's default also sets SO_REUSEPORT, which lets a second server share a port that is
  // in use; SO_REUSEADDR alone still allows a quick restart on the same --port.
  // Stopping waits for connections a browser keeps open; 1 s (not 5) keeps Ctrl-C prompt.
  impl_->http.set_keep_alive_timeout(1);
  impl_->http.set_socket_options([](socket_t socket) {
    const int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
}

ViewerServer::~ViewerServer() = default;

int ViewerServer::Bind(int port) {
  // Loopback only: the viewer is for the person at this machine, not the network.
  const char* host = "127.0.0.1";
  if (port == 0) {
    const int chosen = impl_->http.bind_to_any_port(host);
    if (chosen > 0) return chosen;
  } else if (impl_->http.bind_to_port(host, port)) {
    return port;
  }
  throw std::runtime_error("cannot listen on " + std::string(host) + ":" +
                           (port == 0 ? std::string("(any port)") : std::to_string(port)) +
                           " (is the port in use?)");
}

void ViewerServer::Listen() { impl_->http.listen_after_bind(); }

void ViewerServer::Stop() { impl_->http.stop(); }

}  // namespace prs::viewer
