// Which models can share one MuJoCo render context: the parts of a model that mjr_makeContext
// uploads or copies (textures, materials' texture mapping, plane grids, meshes, height fields,
// the offscreen and shadow buffers' sizes, fog and line settings, and the model's extent, which
// sizes infinite planes, fog and the shadow clip). A simulation that builds a new model per
// scene (sim/world.h) changes only what is drawn per frame, so one context serves all of them;
// remaking it cost about a fifth of a Table-Cube episode in page faults and buffer clears
// (docs/benchmarks.md, "Scaling with threads").
#pragma once

#include <mujoco/mujoco.h>

#include <string>

namespace prs::render {

/// Those parts of `model` as bytes: two models with equal non-empty keys draw the same with one
/// context. Empty for a model whose context is never shared (one with skins).
std::string CalcRenderContextKey(const mjModel& model);

}  // namespace prs::render
