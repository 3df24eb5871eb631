// `prs view`: a local web viewer of a scenario's scenes (or of a scenes .jsonl file), served on
// 127.0.0.1 until Ctrl-C (the URL on stdout), or with --html one self-contained page.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <iostream>
#include <limits>
#include <optional>
#include <thread>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/interrupt.h"
#include "export/export.h"
#include "output/line_writer.h"
#include "viewer/viewer.h"

namespace prs::cli {
namespace {

struct ViewArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  uint64_t start = 0;
  int port = 0;          // 0: a free port chosen by the system
  std::string html;      // with --html: the page to write instead of serving
  int64_t count = 1;     // scenes in the --html page
};

viewer::PageInfo MakePageInfo(const ViewArgs& args) {
  return {args.scenario.file, args.sampling.seed, args.start};
}

// Samples the page's scenes in parallel, in index order, then writes it via OUT.partial.
int WriteStandalonePage(const lang::CompiledProgram& program, const ViewArgs& args) {
  InterruptWatch interrupt;
  sampling::BatchOptions options = MakeBatchOptions(args.sampling, args.count, interrupt.flag());
  options.start = args.start;
  std::vector<std::string> records;
  sampling::BatchCallbacks callbacks;
  callbacks.prepare = [](sampling::BatchScene& scene) {
    scene.rendered = viewer::FormatViewRecord(scene.sampled);
  };
  callbacks.consume = [&records](sampling::BatchScene&& scene) {
    records.push_back(std::move(scene.rendered));
  };
  try {
    sampling::SampleBatch(program, options, callbacks);
    output::LineWriter writer(args.html);
    writer.AddLine(viewer::MakeStandalonePage(MakePageInfo(args), records));
    writer.Commit();
  } catch (const lang::ScenarioError& error) {
    return ReportScenarioError(error, program.sources);
  } catch (const sampling::BatchCancelled&) {
    return kExitInterruptedBase + interrupt.signal_number();
  } catch (const std::exception& error) {  // cannot write the page
    PrintError(error.what());
    return kExitScenarioError;
  }
  PrintNote(fmt::format("wrote {} with {}", args.html, FormatCount(args.count, "scene")));
  return kExitSuccess;
}

// Serves until SIGINT or SIGTERM, then stops the server cleanly and exits 0: stopping is how
// a viewer ends, not a failure.
int Serve(viewer::ViewerServer& server, const ViewArgs& args) {
  InterruptWatch interrupt;  // before the URL is printed, so a prompt SIGTERM is handled
  int port = 0;
  try {
    port = server.Bind(args.port);
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
  std::atomic<bool> listening_ended{false};
  std::thread listener([&] {
    server.Listen();
    listening_ended = true;
  });
  std::cout << "http://127.0.0.1:" << port << "/" << std::endl;
  PrintNote(fmt::format("viewing {}; press Ctrl-C to stop", args.scenario.file));
  while (!interrupt.flag() && !listening_ended)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  // Stop() is a no-op until Listen() is running, so repeat it until the listener returns.
  while (!listening_ended) {
    server.Stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  listener.join();
  PrintNote("viewer stopped");
  return kExitSuccess;
}

// The page of a scenes file's scenes (each line checked as scene JSON), or nullopt after
// printing why there is none.
std::optional<std::string> MakeScenesFilePage(const ViewArgs& args) {
  const auto lines = ReadLines(args.scenario.file);
  if (!lines) return std::nullopt;
  std::vector<std::string> records;
  for (size_t i = 0; i < lines->size(); ++i) {
    const std::string& line = (*lines)[i];
    if (IsBlankLine(line)) continue;
    try {
      exporting::ReadSceneJson(line);
    } catch (const std::invalid_argument& error) {
      PrintError(fmt::format("{}:{}: {}", args.scenario.file, i + 1, error.what()));
      return std::nullopt;
    }
    records.push_back(viewer::FormatViewRecordOfLine(line));
  }
  if (records.empty()) {
    PrintNoScenes(args.scenario.file);
    return std::nullopt;
  }
  return viewer::MakeStandalonePage({args.scenario.file, 0, 0}, records);
}

// A scenes file: its scenes as they are, in one page written with --html or served.
int ViewScenesFile(const ViewArgs& args) {
  const std::optional<std::string> page = MakeScenesFilePage(args);
  if (!page) return kExitScenarioError;
  if (!args.html.empty()) {
    try {
      output::LineWriter writer(args.html);
      writer.AddLine(*page);
      writer.Commit();
    } catch (const std::exception& error) {
      PrintError(error.what());
      return kExitScenarioError;
    }
    PrintNote(fmt::format("wrote {} with the scenes of {}", args.html, args.scenario.file));
    return kExitSuccess;
  }
  viewer::ViewerServer server(*page);
  return Serve(server, args);
}

int RunView(const ViewArgs& args) {
  if (IsScenesFile(args.scenario.file)) return ViewScenesFile(args);
  if (!args.html.empty() && args.start > std::numeric_limits<uint64_t>::max() -
                                             uint64_t(args.count - 1)) {
    PrintError(fmt::format("--start {} with -n {} runs past the last scene index, 2^64 - 1",
                           args.start, args.count));
    return kExitUsage;
  }
  auto program = CompileScenario(args.scenario);
  if (!program) return kExitScenarioError;
  if (!args.html.empty()) return WriteStandalonePage(*program, args);
  viewer::ViewerServer server(*program, MakeSampleOptions(args.sampling), MakePageInfo(args));
  return Serve(server, args);
}

}  // namespace

CommandRunner ConfigureViewCommand(CLI::App& command) {
  auto args = std::make_shared<ViewArgs>();
  AddScenarioOptions(command, args->scenario);
  command.add_option("--start", args->start, "index of the first scene shown")
      ->type_name("I")
      ->check(UnsignedIntegerText())
      ->capture_default_str();
  auto* html = command.add_option("--html", args->html,
                                  "write one self-contained page with the scenes embedded to "
                                  "OUT instead of serving");
  html->type_name("OUT")->check(NonEmptyPath());
  command.add_option("-n,--count", args->count, "scenes in the --html page")
      ->type_name("N")
      ->check(IntegerInRange(1, 10'000))
      ->needs(html)
      ->capture_default_str();
  command.add_option("--port", args->port, "port on 127.0.0.1 (default: a free one)")
      ->type_name("PORT")
      ->check(IntegerInRange(0, 65535))
      ->excludes(html);
  AddSamplingOptions(command, args->sampling);
  return [args] { return RunView(*args); };
}

}  // namespace prs::cli
