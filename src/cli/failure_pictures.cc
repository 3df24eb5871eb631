// Draws failing scenes from their saved JSON lines with src/render, one renderer on the calling
// thread.
#include "cli/failure_pictures.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "cli/common.h"
#include "render/render.h"
#include "render/scene_input.h"

namespace prs::cli {

int64_t DrawFailurePictures(const std::vector<harness::EpisodeRecord>& records) {
  std::unique_ptr<render::Renderer> renderer;  // made only when there is a failure to draw
  int64_t drawn = 0;
  for (const harness::EpisodeRecord& record : records) {
    if (record.saved_scene.empty()) continue;
    std::ifstream file(record.saved_scene);
    std::string line;
    if (!std::getline(file, line)) throw std::runtime_error("cannot read " + record.saved_scene);
    // The JSON, not the sampled scene: the scene's workspace region may be shared with the
    // sampler's threads, and the saved file is what the user will look at anyway.
    render::RenderScene scene = render::ParseRenderSceneJson(line);
    scene.caption =
        fmt::format("seed {}  scene {}  {}", record.seed, record.index, record.result.outcome);
    if (!renderer) renderer = std::make_unique<render::Renderer>();
    const std::filesystem::path png =
        std::filesystem::path(record.saved_scene).replace_extension(".png");
    render::WritePng(renderer->Render(scene, render::RenderOptions{}), png.string());
    ++drawn;
  }
  return drawn;
}

int ReportSavedFailures(const std::vector<harness::EpisodeRecord>& records,
                        const std::string& dir, bool quiet) {
  const int64_t saved = std::count_if(records.begin(), records.end(),
                                      [](const auto& record) { return !record.saved_scene.empty(); });
  int64_t drawn = 0;
  try {
    drawn = DrawFailurePictures(records);
  } catch (const std::exception& error) {
    PrintError(std::string("cannot draw the failing scenes: ") + error.what());
    return kExitScenarioError;
  }
  if (!quiet && saved > 0) {
    PrintNote(fmt::format("{} saved in {} ({})", FormatCount(saved, "failing scene"), dir,
                          drawn == saved ? "JSON and PNG" : "JSON"));
  }
  return kExitSuccess;
}

}  // namespace prs::cli
