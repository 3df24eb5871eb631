// Writes what the Table-Cube controller's ceiling camera sees at the start of an episode (the
// simulated world with its arms in their ready pose), for the case-study page's pictures:
//   prs_camera_snapshot SCENARIO SEED INDEX OUT.png
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "render/model_renderer.h"
#include "sampling/sampler.h"
#include "sim/control.h"
#include "sim/world.h"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SCENARIO SEED INDEX OUT.png\n", argv[0]);
    return 2;
  }
  try {
    prs::lang::DiagnosticEngine diagnostics;
    auto program = prs::lang::CompileFile(argv[1], {}, diagnostics);
    if (diagnostics.has_errors()) {
      std::fprintf(stderr, "%s: does not compile (run prs check)\n", argv[1]);
      return 1;
    }
    const auto sampled = prs::sampling::SampleScene(*program, std::strtoull(argv[2], nullptr, 10),
                                                    std::strtoull(argv[3], nullptr, 10));
    prs::sim::World world = prs::sim::BuildWorld(prs::exporting::MakeExportScene(sampled.scene, "snapshot"));
    prs::sim::SimulateFor(*world.model, *world.data, world.arm_indices(), 0.3);  // as the controller
    prs::render::ModelRenderer renderer(*world.model, 640, 480);
    prs::render::WritePng(renderer.Render(*world.data, 0), argv[4]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
