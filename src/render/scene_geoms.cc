// Geoms for each kind of object. Sizes follow MuJoCo's conventions: half-extents for boxes,
// (radius, half-height) for cylinders along the local z axis, thin capsules for lines.
#include "render/scene_geoms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace prs::render {
namespace {

constexpr int kFrustumEdges = 8;
constexpr int kBoxEdges = 12;
constexpr double kFrustumLength_m = 0.15;

mjvGeom& NextGeom(mjvScene& out) {
  if (out.ngeom >= out.maxgeom) throw std::logic_error("render scene has no room for a geom");
  return out.geoms[out.ngeom++];
}

void AddSolid(mjvScene& out, int type, const Eigen::Vector3d& size, const Eigen::Vector3d& p_W,
              const Eigen::Matrix3d& R_W, const Rgba& rgba) {
  mjtNum size_array[3], pos[3], mat[9];
  for (int i = 0; i < 3; ++i) {
    size_array[i] = size[i];
    pos[i] = p_W[i];
    for (int j = 0; j < 3; ++j) mat[3 * i + j] = R_W(i, j);  // row-major
  }
  mjvGeom& geom = NextGeom(out);
  mjv_initGeom(&geom, type, size_array, pos, mat, rgba.data());
  geom.specular = 0.25f;
  geom.shininess = 0.3f;
}

void AddLine(mjvScene& out, const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W, double width_m,
             const Rgba& rgba) {
  const Eigen::Vector3d d_W = b_W - a_W;
  const Eigen::Matrix3d R_W =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d_W).toRotationMatrix();
  AddSolid(out, mjGEOM_BOX, {width_m, width_m, d_W.norm() / 2}, (a_W + b_W) / 2, R_W, rgba);
}

// A camera: its body, and a wire frustum along its look axis (local +y, up +z), opening at the
// camera's own field of view, so that the direction it faces and what it sees show.
void AddCamera(mjvScene& out, const RenderObject& camera, bool frustum_too) {
  const Eigen::Matrix3d R_WO = camera.R_WO.toRotationMatrix();
  Eigen::Vector3d body = camera.dimensions;
  if (body.isZero()) body = Eigen::Vector3d::Constant(0.05);
  AddSolid(out, mjGEOM_BOX, body / 2, camera.p_WO, R_WO, camera.color);
  if (!frustum_too) return;
  const double half_z = kFrustumLength_m * std::tan(camera.fovy_deg * M_PI / 360.0);
  const double half_x = half_z * camera.aspect;
  const Rgba frustum = {0.95f, 0.6f, 0.1f, 1.0f};
  Eigen::Vector3d corners_W[4];
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d p_O((i == 0 || i == 3) ? -half_x : half_x, kFrustumLength_m,
                              i < 2 ? -half_z : half_z);
    corners_W[i] = camera.p_WO + R_WO * p_O;
  }
  for (int i = 0; i < 4; ++i) {
    AddLine(out, camera.p_WO, corners_W[i], 0.003, frustum);
    AddLine(out, corners_W[i], corners_W[(i + 1) % 4], 0.003, frustum);
  }
}

// The 12 edges of a box in a darker shade, so that boxes of one colour that touch (a grey
// tray on a grey table) stay apart in the picture.
void AddBoxEdges(mjvScene& out, const RenderObject& o, const Eigen::Matrix3d& R_WO,
                 double width_m) {
  const Rgba dark = {o.color[0] * 0.45f, o.color[1] * 0.45f, o.color[2] * 0.45f, 1.0f};
  const Eigen::Vector3d half = o.dimensions / 2;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
      Eigen::Vector3d a_O = Eigen::Vector3d::Zero();
      a_O[u] = corner & 1 ? half[u] : -half[u];
      a_O[v] = corner & 2 ? half[v] : -half[v];
      Eigen::Vector3d b_O = a_O;
      a_O[axis] = -half[axis];
      b_O[axis] = half[axis];
      AddLine(out, o.p_WO + R_WO * a_O, o.p_WO + R_WO * b_O, width_m, dark);
    }
  }
}

// A copy of the mesh's drawing, moved from the identity pose to the object's.
void AddMesh(mjvScene& out, const RenderObject& o, const Eigen::Matrix3d& R_WO,
             const mjvGeom& drawing) {
  using RowMajor3 = Eigen::Matrix<float, 3, 3, Eigen::RowMajor>;
  mjvGeom& geom = NextGeom(out);
  geom = drawing;
  const Eigen::Map<const Eigen::Vector3f> p_OG(drawing.pos);
  const Eigen::Map<const RowMajor3> R_OG(drawing.mat);
  Eigen::Map<Eigen::Vector3f>(geom.pos) = (o.p_WO + R_WO * p_OG.cast<double>()).cast<float>();
  Eigen::Map<RowMajor3>(geom.mat) = (R_WO * R_OG.cast<double>()).cast<float>();
  for (int i = 0; i < 4; ++i) geom.rgba[i] = o.color[i];
  geom.objtype = mjOBJ_UNKNOWN;
  geom.objid = -1;
  geom.category = mjCAT_DECOR;
  geom.specular = 0.25f;
  geom.shininess = 0.3f;
}

// `edge_width_m` 0: no box edges, and a camera without its frustum (a dataset's pictures).
void AddObject(mjvScene& out, const RenderObject& o, double edge_width_m,
               const std::vector<MeshDrawing>& meshes) {
  const Eigen::Matrix3d R_WO = o.R_WO.toRotationMatrix();
  const bool decorations = edge_width_m > 0;
  switch (o.shape) {
    case ObjectShape::kMesh:
      for (const MeshDrawing& drawing : meshes) {
        if (drawing.key == internal::MeshKey(o.mesh.get(), o.mesh_scale))
          return AddMesh(out, o, R_WO, drawing.geom);
      }
      [[fallthrough]];  // not in the model: its box
    case ObjectShape::kBox:
      AddSolid(out, mjGEOM_BOX, o.dimensions / 2, o.p_WO, R_WO, o.color);
      if (!decorations) return;
      return AddBoxEdges(out, o, R_WO, std::min(edge_width_m, 0.05 * o.dimensions.minCoeff()));
    case ObjectShape::kCylinder: {
      // MuJoCo has no elliptic cylinder: the radius is the mean of the half width and length.
      const double radius = (o.dimensions.x() + o.dimensions.y()) / 4;
      return AddSolid(out, mjGEOM_CYLINDER, {radius, o.dimensions.z() / 2, 0}, o.p_WO, R_WO,
                      o.color);
    }
    case ObjectShape::kSphere:
      return AddSolid(out, mjGEOM_ELLIPSOID, o.dimensions / 2, o.p_WO, R_WO, o.color);
    case ObjectShape::kCapsule: {
      // No taller than wide, a capsule is all caps: the ellipsoid (MuJoCo draws nothing for a
      // capsule without a straight part).
      const double radius = (o.dimensions.x() + o.dimensions.y()) / 4;
      if (o.dimensions.z() / 2 <= radius)
        return AddSolid(out, mjGEOM_ELLIPSOID, o.dimensions / 2, o.p_WO, R_WO, o.color);
      return AddSolid(out, mjGEOM_CAPSULE, {radius, o.dimensions.z() / 2 - radius, 0}, o.p_WO,
                      R_WO, o.color);
    }
    case ObjectShape::kPoint:
      if (!decorations) return;  // a marker, not a solid
      return AddSolid(out, mjGEOM_SPHERE, Eigen::Vector3d::Constant(0.02), o.p_WO, R_WO, o.color);
    case ObjectShape::kCamera:
      // A dataset's picture: cameras are viewpoints, as in BlenderProc, not things in the
      // scene (a pile's other views would float in it; docs/dataset.md).
      if (!decorations) return;
      return AddCamera(out, o, decorations);
    case ObjectShape::kLight:
      return;  // it lights the scene (renderer.cc), it is not seen
  }
}

void AddFloor(mjvScene& out, const SceneExtent& extent, int floor_texture, const mjModel* model) {
  const double half_size = std::max(20.0, 40 * extent.radius_m);
  const Eigen::Vector3d p_W(extent.centre_W.x(), extent.centre_W.y(), extent.floor_z_m);
  AddSolid(out, mjGEOM_PLANE, {half_size, half_size, 1.0}, p_W, Eigen::Matrix3d::Identity(),
           {1, 1, 1, 1});
  mjvGeom& floor = out.geoms[out.ngeom - 1];
  floor.texid = floor_texture;
  const int material = mj_name2id(model, mjOBJ_MATERIAL, "floor");
  floor.texuniform = model->mat_texuniform[material];
  floor.texrepeat[0] = model->mat_texrepeat[2 * material];
  floor.texrepeat[1] = model->mat_texrepeat[2 * material + 1];
  floor.specular = 0.1f;
}

}  // namespace

SceneExtent CalcSceneExtent(const RenderScene& scene) {
  if (scene.objects.empty()) return {};
  Eigen::Vector3d min_W = Eigen::Vector3d::Constant(1e300), max_W = -min_W;
  for (const RenderObject& o : scene.objects) {
    if (o.shape == ObjectShape::kLight) continue;  // far above, it would shrink the picture
    const Eigen::Vector3d half = o.R_WO.toRotationMatrix().cwiseAbs() * o.dimensions / 2;
    min_W = min_W.cwiseMin(o.p_WO - half);
    max_W = max_W.cwiseMax(o.p_WO + half);
  }
  SceneExtent extent;
  extent.centre_W = (min_W + max_W) / 2;
  extent.radius_m = std::max(0.25, (max_W - min_W).norm() / 2);
  extent.floor_z_m = std::min(0.0, min_W.z());
  return extent;
}

int CountSceneGeoms(const RenderScene& scene) {
  int count = 1 + static_cast<int>(scene.workspace_edges.size());  // floor, outline
  for (const RegionOutline& region : scene.regions) count += static_cast<int>(region.edges.size());
  for (const RenderObject& o : scene.objects)
    count += o.shape == ObjectShape::kCamera                              ? 1 + kFrustumEdges
             : o.shape == ObjectShape::kBox || o.shape == ObjectShape::kMesh ? 1 + kBoxEdges
                                                                             : 1;
  return count;
}

void AddSceneGeoms(const RenderScene& scene, const RenderObject* viewpoint,
                   const SceneExtent& extent, int floor_texture, const mjModel* model,
                   const std::vector<MeshDrawing>& meshes, bool decorations, mjvScene& out) {
  AddFloor(out, extent, floor_texture, model);
  out.geoms[out.ngeom - 1].segid = -1;
  const double line_width = std::clamp(0.003 * extent.radius_m, 0.0015, 0.015);
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    if (&scene.objects[i] == viewpoint) continue;
    const int first = out.ngeom;
    AddObject(out, scene.objects[i], decorations ? line_width / 2 : 0, meshes);
    for (int g = first; g < out.ngeom; ++g) out.geoms[g].segid = int(i);
  }
  if (!decorations) return;
  const int first_decoration = out.ngeom;
  for (const auto& [a_W, b_W] : scene.workspace_edges)
    AddLine(out, a_W, b_W, line_width, {0.3f, 0.38f, 0.55f, 1.0f});
  // Regions in bright colours, thinner than the workspace: positions green, views orange.
  for (const RegionOutline& region : scene.regions) {
    const Rgba color = region.is_view ? Rgba{0.95f, 0.6f, 0.1f, 1.0f} : Rgba{0.1f, 0.75f, 0.3f, 1.0f};
    for (const auto& [a_W, b_W] : region.edges) {
      if ((b_W - a_W).norm() > 1e-9) AddLine(out, a_W, b_W, line_width * 0.6, color);
    }
  }
  for (int g = first_decoration; g < out.ngeom; ++g) out.geoms[g].segid = -1;
}

}  // namespace prs::render
