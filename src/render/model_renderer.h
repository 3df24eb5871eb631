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
  /// Makes the OpenGL context for width x height pictures. Throws std::runtime_error when no
  /// context can be made.
  ModelRenderer(int width, int height);
  /// The same, then SetModel(model).
  ModelRenderer(const mjModel& model, int width, int height);
  /// Renders `model` from now on (one renderer serves model after model, keeping its OpenGL
  /// context). The model must outlive its use here, and its offscreen buffer (<visual><global
  /// offwidth offheight>) must fit the picture; std::runtime_error otherwise.
  void SetModel(const mjModel& model);
  ~ModelRenderer();
  ModelRenderer(const ModelRenderer&) = delete;
  ModelRenderer& operator=(const ModelRenderer&) = delete;

  /// What camera `camera_id` of the current model sees in state `data`, rows from the top; `depth` (when not null)
  /// gets the distance along the camera's look axis, +infinity where nothing is seen.
  /// With `only_body` >= 0, the geoms of that body alone are drawn, as if nothing else were
  /// in the world (a simulator's "entity to render" for a vision sensor).
  Image Render(mjData& data, int camera_id, DepthImage* depth = nullptr, int only_body = -1);

  /// The current model's near and far clipping planes in metres (MuJoCo's, which scale with
  /// the model's extent): the depth range the camera sees. SetModel first.
  struct ClippingPlanes {
    double near_m = 0, far_m = 0;
  };
  ClippingPlanes GetClippingPlanes() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace prs::render
