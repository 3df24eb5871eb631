// libFuzzer entry point for the readers of text that other programs write: one line of a
// scenes file (spec §8) as `prs export` and `prs render` read it (and every export format
// written from what was read), and a controller's standard output as `prs test --exec` reads
// it. A reader may refuse its input only as it documents: ReadSceneJson and
// ParseRenderSceneJson with std::invalid_argument (a message naming the field), and
// InterpretAnswer never (a malformed answer is the outcome "bad-answer"). Any other exception,
// crash, hang, leak or sanitizer report is a bug (spec §9).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "export/export.h"
#include "harness/exec_controller.h"
#include "render/scene_input.h"

namespace {

constexpr size_t kMaxInputBytes = 64 * 1024;  // the stdout a controller keeps is 64 KiB

void ReadAndExport(std::string_view line) {
  prs::exporting::ExportScene scene;
  try {
    scene = prs::exporting::ReadSceneJson(line);
  } catch (const std::invalid_argument&) {
    return;  // refused with a message: what a user sees as FILE:LINE: message
  }
  for (const prs::exporting::Format format :
       {prs::exporting::Format::kMjcf, prs::exporting::Format::kUrdf,
        prs::exporting::Format::kSdf, prs::exporting::Format::kUsda,
        prs::exporting::Format::kGltf, prs::exporting::Format::kGlb}) {
    volatile size_t sink = prs::exporting::WriteScene(scene, format).size();
    (void)sink;
  }
}

void ReadForRendering(std::string_view line) {
  std::vector<std::string> unknown_colors;
  try {
    volatile size_t sink = prs::render::ParseRenderSceneJson(line, &unknown_colors).objects.size();
    (void)sink;
  } catch (const std::invalid_argument&) {
  }
}

void ReadControllerAnswer(std::string_view text) {
  prs::harness::ExecAnswer answer;
  answer.stdout_tail = std::string(text);
  volatile size_t sink = prs::harness::InterpretAnswer(answer, 1.0).outcome.size();
  (void)sink;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > kMaxInputBytes) return -1;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ReadAndExport(text);
  ReadForRendering(text);
  ReadControllerAnswer(text);
  return 0;
}
