// A RenderScene as MuJoCo decoration geoms: boxes, cylinders, meshes, point markers, camera bodies
// with their view frustum, the workspace outline and the floor. Internal to src/render.
#pragma once

#include <mujoco/mujoco.h>

#include <vector>

#include "render/mujoco_model.h"
#include "render/render.h"

namespace prs::render {

/// How MuJoCo draws one mesh of the render model: its static geom as mjv_updateScene made it,
/// at the identity pose. A mesh object's geom is a copy moved to the object's pose.
struct MeshDrawing {
  internal::MeshKey key;
  mjvGeom geom;
};

/// The sphere around the objects, and the floor height (z = 0, or lower under objects below).
struct SceneExtent {
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
  double radius_m = 1.0;
  double floor_z_m = 0.0;
};

SceneExtent CalcSceneExtent(const RenderScene& scene);

/// How many geoms AddSceneGeoms adds for `scene`.
int CountSceneGeoms(const RenderScene& scene);

/// Appends the scene's geoms to `out` (which must have room: CountSceneGeoms), except those of
/// `viewpoint` (the camera looked through; may be null). The floor uses texture
/// `floor_texture` of `model`; camera frusta open at each camera's own field of view; mesh
/// objects are drawn from `meshes` (an object whose mesh is not among them as its box). Each
/// geom of object i has segid i (MuJoCo's segmentation rendering); the floor and the outlines
/// -1. Without `decorations` (a dataset's pictures): the solids alone, with no box edges, no
/// camera frusta, no point markers and no outlines.
void AddSceneGeoms(const RenderScene& scene, const RenderObject* viewpoint,
                   const SceneExtent& extent, int floor_texture, const mjModel* model,
                   const std::vector<MeshDrawing>& meshes, bool decorations, mjvScene& out);

}  // namespace prs::render
