// `prs render`: pictures of sampled scenes (or of a scenes .jsonl file) as PNG, drawn offscreen
// by src/render; one file per scene, or --grid for all in one image; --depth for camera views.
#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "cli/commands.h"
#include "cli/common.h"
#include "cli/progress.h"
#include "render/render.h"
#include "render/scene_input.h"

namespace prs::cli {
namespace {

struct RenderArgs {
  ScenarioArgs scenario;
  SamplingArgs sampling;
  SceneRangeArgs range;
  std::string output = "scene.png";
  std::string size = "640x480";
  std::string view = "overview";
  std::string depth_output;
  bool grid = false;
  bool show_regions = false;
  bool quiet = false;
};

// Scenes start..start+count-1 of the scenario; throws lang::ScenarioError from sampling.
std::vector<render::RenderScene> SampleScenes(const lang::CompiledProgram& program,
                                              const RenderArgs& args) {
  const std::atomic<bool> never_cancel{false};
  sampling::BatchOptions options = MakeBatchOptions(args.sampling, args.range.count, never_cancel);
  options.start = args.range.start;
  options.sample.run.record_regions = args.show_regions;
  std::vector<sampling::SampledScene> sampled;
  sampling::SampleBatch(program, options, {nullptr, [&](sampling::BatchScene&& s) {
                                             sampled.push_back(std::move(s.sampled));
                                           }});
  // Converted after the workers stopped: the workspace region may be shared with them.
  std::vector<std::string> unknown_colors;
  std::vector<render::RenderScene> scenes;
  for (const sampling::SampledScene& s : sampled) {
    scenes.push_back(render::MakeRenderScene(s.scene, &unknown_colors));
    scenes.back().caption = fmt::format("seed {}  scene {}", s.seed, s.index);
  }
  if (!unknown_colors.empty())
    PrintNote("unknown color " + unknown_colors.front() + " drawn in the default colour");
  return scenes;
}

// Lines start..start+count-1 (blank lines skipped) of a scenes file. Errors: "FILE:LINE: ...".
std::vector<render::RenderScene> ReadScenesFile(const RenderArgs& args) {
  std::ifstream in(args.scenario.file);
  if (!in) throw std::runtime_error("cannot read " + args.scenario.file);
  std::vector<render::RenderScene> scenes;
  std::string line;
  uint64_t scene_index = 0;
  for (int line_number = 1; std::getline(in, line) && int64_t(scenes.size()) < args.range.count;
       ++line_number) {
    if (IsBlankLine(line)) continue;
    if (scene_index++ < args.range.start) continue;
    try {
      scenes.push_back(render::ParseRenderSceneJson(line));
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error(
          fmt::format("{}:{}: {}", args.scenario.file, line_number, error.what()));
    }
    scenes.back().caption = fmt::format("scene {}", scene_index - 1);
  }
  if (scenes.empty())
    throw std::runtime_error(
        fmt::format("{} has no scene at index {}", args.scenario.file, args.range.start));
  return scenes;
}

// OUT for one picture; OUT's stem + "_INDEX" otherwise (scene.png -> scene_3.png).
std::string NumberedPath(const std::string& path, uint64_t index, bool numbered) {
  if (!numbered) return path;
  std::filesystem::path p(path);
  const std::string stem = p.stem().string() + "_" + std::to_string(index);
  return (p.parent_path() / (stem + p.extension().string())).string();
}

constexpr size_t kManyObjects = 1000;

int RenderScenes(const std::vector<render::RenderScene>& scenes, const RenderArgs& args,
                 const render::RenderOptions& options) {
  render::Renderer renderer;
  std::vector<render::Image> tiles;
  const bool numbered = scenes.size() > 1 && !args.grid;
  // A picture is one MuJoCo draw call, so progress is per scene; a large scene is announced
  // before its draw (about 1.5 s per 1,000 boxes on the software rasteriser).
  const bool terminal = !args.quiet && IsStderrTerminal();
  ProgressBar progress(int64_t(scenes.size()), terminal);
  for (size_t i = 0; i < scenes.size(); ++i) {
    progress.Update(int64_t(i));
    if (terminal && scenes[i].objects.size() >= kManyObjects) {
      progress.Erase();
      PrintNote(fmt::format("drawing scene {} of {}: {} objects", i + 1, scenes.size(),
                            scenes[i].objects.size()));
    }
    render::RenderScene scene = scenes[i];
    if (!args.grid) scene.caption.clear();
    render::DepthImage depth;
    render::Image image =
        renderer.Render(scene, options, args.depth_output.empty() ? nullptr : &depth);
    if (!args.depth_output.empty())
      render::WriteDepthPng(depth, NumberedPath(args.depth_output, args.range.start + i, numbered));
    if (args.grid) {
      tiles.push_back(std::move(image));
    } else {
      render::WritePng(image, NumberedPath(args.output, args.range.start + i, numbered));
    }
  }
  if (args.grid) render::WritePng(render::ComposeGrid(tiles), args.output);
  return kExitSuccess;
}

// Checks that need several options together; returns the message, or "" when all is well.
std::string CheckOptionCombinations(const RenderArgs& args, const render::View& view) {
  if (!args.depth_output.empty() && view.kind != render::ViewKind::kCamera)
    return "--depth needs a camera view (--view camera:NAME)";
  if (!args.depth_output.empty() && args.grid)
    return "--depth writes one depth image per scene and cannot be used with --grid";
  if (args.show_regions && IsScenesFile(args.scenario.file))
    return "--show-regions needs the .prs scenario (a scenes file does not keep the regions its "
           "objects were drawn from)";
  return "";
}

std::vector<render::RenderScene> LoadScenes(const RenderArgs& args, int& exit_code) {
  if (IsScenesFile(args.scenario.file)) return ReadScenesFile(args);
  auto program = CompileScenario(args.scenario);
  if (!program) {
    exit_code = kExitScenarioError;
    return {};
  }
  try {
    return SampleScenes(*program, args);
  } catch (const lang::ScenarioError& error) {
    exit_code = ReportScenarioError(error, program->sources);
    return {};
  }
}

int RunRender(const RenderArgs& args) {
  if (!CheckSceneRange(args.range)) return kExitUsage;
  const auto begin = std::chrono::steady_clock::now();
  render::RenderOptions options;
  options.view = render::ParseView(args.view);  // validated by the option's check
  std::tie(options.width, options.height) = render::ParseSize(args.size);
  if (const std::string problem = CheckOptionCombinations(args, options.view); !problem.empty()) {
    PrintError(problem);
    return kExitUsage;
  }
  int exit_code = kExitSuccess;
  std::vector<render::RenderScene> scenes;
  try {
    scenes = LoadScenes(args, exit_code);
    if (exit_code != kExitSuccess) return exit_code;
    exit_code = RenderScenes(scenes, args, options);
  } catch (const std::invalid_argument& error) {  // a camera name no scene has
    PrintError(error.what());
    return kExitUsage;
  } catch (const std::exception& error) {  // unreadable input, no OpenGL, unwritable output
    PrintError(error.what());
    return kExitScenarioError;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  const bool numbered = scenes.size() > 1 && !args.grid;
  const std::string where =
      numbered ? NumberedPath(args.output, args.range.start, true) + " ..." : args.output;
  if (!args.quiet)
    PrintNote(fmt::format("rendered {} ({}x{}, {}) in {:.2f} s to {}",
                          FormatCount(int64_t(scenes.size()), "scene"), options.width,
                          options.height, args.view, seconds, where));
  return exit_code;
}

// CLI11 check from a parser that throws std::invalid_argument with the message to show.
template <typename Parse>
CLI::Validator CheckedBy(Parse parse) {
  return CLI::Validator(
      [parse](std::string& text) -> std::string {
        try {
          parse(text);
          return "";
        } catch (const std::invalid_argument& error) {
          return error.what();
        }
      },
      "");
}

}  // namespace

CommandRunner ConfigureRenderCommand(CLI::App& command) {
  auto args = std::make_shared<RenderArgs>();
  AddScenarioOptions(command, args->scenario);
  command.get_option("FILE")->description("the .prs scenario, or a scenes .jsonl (prs sample)");
  AddSceneRangeOptions(command, args->range, 1);
  command
      .add_option("-o,--output", args->output,
                  "PNG to write (several scenes without --grid: OUT_INDEX.png)")
      ->type_name("OUT")
      ->check(NonEmptyPath())
      ->capture_default_str();
  command.add_option("--size", args->size, "picture size (per scene with --grid)")
      ->type_name("WxH")
      ->check(CheckedBy(render::ParseSize))
      ->capture_default_str();
  command.add_option("--view", args->view, "overview, top, front or camera:NAME")
      ->type_name("VIEW")
      ->check(CheckedBy(render::ParseView))
      ->capture_default_str();
  command.add_flag("--grid", args->grid, "all scenes in one picture, in rows of ceil(sqrt(N))");
  command.add_flag("--show-regions", args->show_regions,
                   "also draw the region each object's position was drawn from (green) and the "
                   "views of cameras that view specifiers name (orange)");
  command
      .add_option("--depth", args->depth_output,
                  "also write the camera's depth as a 16-bit PNG in millimetres")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  AddSamplingOptions(command, args->sampling);
  command.add_flag("-q,--quiet", args->quiet, "no summary on stderr");
  return [args] { return RunRender(*args); };
}

}  // namespace prs::cli
