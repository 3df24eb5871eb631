// Pictures of a simulated MuJoCo world from one of its own cameras, RGB and metric depth, on
// the same software EGL context as the scene renderer: what a robot's RGB-D camera would see
// (src/sim's controller looks through it).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>

#include "render/render.h"

namespace prs::render {

class ModelRenderer {
 public:
  /// Prepares rendering of `model`, which must outlive this object. width x height must fit
  /// the model's offscreen buffer (<visual><global offwidth offheight>). Throws
  /// std::runtime_error when no OpenGL context or framebuffer can be made.
  ModelRenderer(const mjModel& model, int width, int height);
  ~ModelRenderer();
  ModelRenderer(const ModelRenderer&) = delete;
  ModelRenderer& operator=(const ModelRenderer&) = delete;

  /// What camera `camera_id` sees in state `data`, rows from the top; `depth` (when not null)
  /// gets the distance along the camera's look axis, +infinity where nothing is seen.
  Image Render(mjData& data, int camera_id, DepthImage* depth = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace prs::render
