// The fixed MuJoCo model every picture shares (sky, checker floor texture, sun light), loaded
// from text through MuJoCo's virtual file system. Internal to src/render.
#pragma once

#include <mujoco/mujoco.h>

namespace prs::render::internal {

/// Compiles the fixed model. Throws std::runtime_error with MuJoCo's message on failure.
mjModel* LoadRenderModel();

/// Routes MuJoCo's warnings and errors to stderr instead of its defaults, which write
/// MUJOCO_LOG.TXT into the working directory (and exit, for errors).
void InstallMujocoMessageHandlers();

}  // namespace prs::render::internal
