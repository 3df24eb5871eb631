// Renderer: the scene's objects as MuJoCo decoration geoms over a checker floor, drawn by
// mjr_render into MuJoCo's offscreen framebuffer and read back as RGB and metric depth.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "render/context_key.h"
#include "render/egl_context.h"
#include "render/model_renderer.h"
#include "render/mujoco_model.h"
#include "render/render.h"
#include "render/scene_geoms.h"

namespace prs::render {

struct Renderer::State {
  internal::EglContext egl;  // first: MuJoCo's context needs a current OpenGL context
  ModelPtr model_owner;
  DataPtr data_owner;
  mjModel* model = nullptr;
  mjData* data = nullptr;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjrContext context;
  int buffer_width = 0, buffer_height = 0;
  int floor_texture = -1;
  std::vector<internal::MeshKey> meshes;  // the render model's, in asset order
  std::vector<std::shared_ptr<const shapes::MeshShape>> mesh_owners;  // keep `meshes` alive

  // The context is current only inside each call (internal::EglContext::Scope), so that a
  // renderer may move between threads (a dataset's pool).
  State() {
    mjv_defaultScene(&scene);
    mjr_defaultContext(&context);
    LoadModel();
    egl.Release();
  }
  ~State() {
    internal::EglContext::Scope current(egl);
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
  }

  // (Re)loads the render model with `meshes` as assets; the scene and the render context
  // (which holds the model's meshes) are made again on their next use.
  void LoadModel() {
    model_owner = internal::LoadRenderModel(meshes);
    data_owner = MakeData(*model_owner);
    model = model_owner.get();
    data = data_owner.get();
    mj_forward(model, data);  // the lights' world positions and directions
    mjv_freeScene(&scene);
    mjv_defaultScene(&scene);
    mjv_defaultOption(&option);
    mjv_defaultFreeCamera(model, &camera);
    floor_texture = model->mat_texid[mj_name2id(model, mjOBJ_MATERIAL, "floor")];
    buffer_width = buffer_height = 0;  // EnsureBuffer makes the context again
  }

  // Makes the model hold the meshes of `scene` (reloading it only when they change).
  void UseMeshesOf(const RenderScene& scene) {
    std::vector<internal::MeshKey> wanted;
    for (const RenderObject& o : scene.objects) {
      const internal::MeshKey key(o.mesh.get(), o.mesh_scale);
      if (o.shape == ObjectShape::kMesh && o.mesh &&
          std::find(wanted.begin(), wanted.end(), key) == wanted.end())
        wanted.push_back(key);
    }
    // Keep meshes already loaded when the new scene's are among them (a grid of scenes).
    if (std::all_of(wanted.begin(), wanted.end(), [&](const internal::MeshKey& key) {
          return std::find(meshes.begin(), meshes.end(), key) != meshes.end();
        }))
      return;
    meshes = std::move(wanted);
    mesh_owners.clear();
    for (const RenderObject& o : scene.objects)
      if (o.mesh) mesh_owners.push_back(o.mesh);
    LoadModel();
  }

  // The model's mesh geoms as mjv_updateScene drew them (geom i draws mesh i).
  std::vector<MeshDrawing> ReadMeshDrawings() const {
    std::vector<MeshDrawing> drawings;
    for (int i = 0; i < scene.ngeom; ++i) {
      const mjvGeom& geom = scene.geoms[i];
      if (geom.objtype == mjOBJ_GEOM && geom.objid >= 0 && geom.objid < int(meshes.size()))
        drawings.push_back({meshes[geom.objid], geom});
    }
    return drawings;
  }

  // MuJoCo 2.2 sizes its offscreen buffer once, from the model, when the context is made.
  void EnsureBuffer(int width, int height) {
    if (width == buffer_width && height == buffer_height) return;
    mjr_freeContext(&context);
    mjr_defaultContext(&context);
    model->vis.global.offwidth = width;
    model->vis.global.offheight = height;
    mjr_makeContext(model, &context, height >= 600 ? mjFONTSCALE_150 : mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &context);
    if (context.currentBuffer != mjFB_OFFSCREEN)
      throw std::runtime_error("MuJoCo could not make its offscreen framebuffer");
    buffer_width = width;
    buffer_height = height;
  }

  void EnsureGeomCapacity(int count) {
    if (scene.maxgeom >= count) return;
    mjv_freeScene(&scene);
    mjv_makeScene(model, &scene, std::max(count, 2 * scene.maxgeom));
  }
};

namespace {

void SetGlCamera(mjvGLCamera& gl, const CameraPose& pose, double fovy_deg) {
  for (int i = 0; i < 3; ++i) {
    gl.pos[i] = static_cast<float>(pose.p_WC[i]);
    gl.forward[i] = static_cast<float>(pose.forward_W[i]);
    gl.up[i] = static_cast<float>(pose.up_W[i]);
  }
  const double half_height = pose.near_m * std::tan(fovy_deg * M_PI / 360.0);
  gl.frustum_center = 0;
  gl.frustum_top = static_cast<float>(half_height);
  gl.frustum_bottom = static_cast<float>(-half_height);
  gl.frustum_near = static_cast<float>(pose.near_m);
  gl.frustum_far = static_cast<float>(pose.far_m);
}

// mjv_updateScene placed the camera and lights for MuJoCo's own free camera: put the camera
// (both stereo eyes) at our pose, the headlight with it, and the sun's shadow over the scene.
void PlaceCameraAndLights(mjvScene& scene, mjrContext& context, const CameraPose& pose,
                          const SceneExtent& extent, double fovy_deg) {
  for (mjvGLCamera& gl : scene.camera) SetGlCamera(gl, pose, fovy_deg);
  for (int i = 0; i < scene.nlight; ++i) {
    mjvLight& light = scene.lights[i];
    const Eigen::Vector3d dir_W(light.dir[0], light.dir[1], light.dir[2]);
    // MuJoCo clips the sun's shadow map to the camera's [near, far] as seen from the light.
    const double light_distance_m = pose.near_m + 1.5 * extent.radius_m;
    const Eigen::Vector3d p_W =
        light.headlight ? pose.p_WC : extent.centre_W - light_distance_m * dir_W.normalized();
    for (int k = 0; k < 3; ++k) light.pos[k] = static_cast<float>(p_W[k]);
    if (light.headlight)
      for (int k = 0; k < 3; ++k) light.dir[k] = static_cast<float>(pose.forward_W[k]);
  }
  context.shadowClip = static_cast<float>(1.5 * extent.radius_m);
}

// The scene's light objects, when it has any, replace the render model's sun; the headlight
// keeps only its ambient fill, so that what the objects receive is the scene's to choose.
void AddSceneLights(const RenderScene& scene, const SceneExtent& extent, mjvScene& out) {
  const auto is_light = [](const RenderObject& o) { return o.shape == ObjectShape::kLight; };
  if (std::none_of(scene.objects.begin(), scene.objects.end(), is_light)) return;
  int kept = 0;
  for (int i = 0; i < out.nlight; ++i) {
    if (!out.lights[i].headlight) continue;
    mjvLight& fill = out.lights[kept++] = out.lights[i];
    for (int k = 0; k < 3; ++k) fill.diffuse[k] = fill.specular[k] = 0;
  }
  out.nlight = kept;
  for (const RenderObject& o : scene.objects) {
    if (!is_light(o) || out.nlight >= mjMAXLIGHT) continue;
    mjvLight& light = out.lights[out.nlight++];
    light = mjvLight{};
    const Eigen::Vector3d dir_W = o.R_WO.normalized().toRotationMatrix().col(1);
    // A sun's shadow is cast from a point back along its direction, as for the model's sun.
    const Eigen::Vector3d p_W =
        o.light.directional ? Eigen::Vector3d(extent.centre_W - 1.5 * extent.radius_m * dir_W) : o.p_WO;
    for (int k = 0; k < 3; ++k) {
      light.pos[k] = float(p_W[k]);
      light.dir[k] = float(dir_W[k]);
      light.diffuse[k] = float(o.light.intensity * o.color[k]);
      light.specular[k] = float(0.3 * o.light.intensity * o.color[k]);
    }
    light.attenuation[0] = 1;
    light.cutoff = float(o.light.cutoff_deg);
    light.exponent = 10;
    light.directional = o.light.directional;
    light.castshadow = o.light.castshadow;
  }
}

// OpenGL rows run bottom-up; pictures run top-down.
template <typename T>
void FlipRows(std::vector<T>& pixels, int width, int height, int channels) {
  const size_t row = static_cast<size_t>(width) * channels;
  for (int y = 0; y < height / 2; ++y) {
    std::swap_ranges(pixels.begin() + y * row, pixels.begin() + (y + 1) * row,
                     pixels.begin() + (height - 1 - y) * row);
  }
}

// Depth-buffer values d in [0, 1] to distance along the view axis, as MuJoCo's docs give it:
// near / (1 - d (1 - near / far)). The far plane itself (the sky) is "nothing seen".
void LinearizeDepth(std::vector<float>& depth, double near, double far) {
  for (float& d : depth) {
    d = d >= 1.0f ? std::numeric_limits<float>::infinity()
                  : static_cast<float>(near / (1.0 - d * (1.0 - near / far)));
  }
}

}  // namespace

Renderer::Renderer() : state_(std::make_unique<State>()) {}
Renderer::~Renderer() = default;

namespace {

// The picture MuJoCo drew, read back top-down: RGB, and metric depth when `depth` is not null.
Image ReadPicture(mjrContext& context, const RenderOptions& options, const CameraPose& pose,
                  DepthImage* depth) {
  const mjrRect viewport = {0, 0, options.width, options.height};
  Image image{options.width, options.height,
              std::vector<uint8_t>(size_t(options.width) * options.height * 3)};
  std::vector<float> raw_depth(depth ? size_t(options.width) * options.height : 0);
  mjr_readPixels(image.rgb.data(), depth ? raw_depth.data() : nullptr, viewport, &context);
  FlipRows(image.rgb, options.width, options.height, 3);
  if (depth) {
    FlipRows(raw_depth, options.width, options.height, 1);
    LinearizeDepth(raw_depth, pose.near_m, pose.far_m);
    *depth = DepthImage{options.width, options.height, std::move(raw_depth)};
  }
  return image;
}

// mjRND_IDCOLOR draws geom g in the colour segid + 1, little-endian in (r, g, b); 0 is
// nothing (the background, and the geoms whose segid is -1).
ObjectIdImage DecodeObjectIds(const Image& picture, int objects) {
  ObjectIdImage ids{picture.width, picture.height,
                    std::vector<int32_t>(size_t(picture.width) * picture.height)};
  for (size_t i = 0; i < ids.object.size(); ++i) {
    const uint8_t* c = &picture.rgb[3 * i];
    const int32_t id = int32_t(c[0] | c[1] << 8 | c[2] << 16) - 1;
    if (id >= objects) throw std::logic_error("segmentation rendering gave an unknown colour");
    ids.object[i] = id;
  }
  return ids;
}

// The rectangle of pixels an object's picture may cover (its bounding box's corners seen from
// `pose`, a cylinder's or capsule's widened to its round radius, two pixels of margin), or the
// whole picture when a corner is not in front of the near plane.
struct PixelRect {
  double x0, y0, x1, y1;
  bool Overlaps(const PixelRect& o) const {
    return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1;
  }
};

PixelRect CalcPixelRect(const RenderObject& o, const CameraPose& pose, double fovy_deg, int width,
                        int height) {
  const PixelRect whole{-HUGE_VAL, -HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Eigen::Vector3d half = o.dimensions / 2;
  if (o.shape == ObjectShape::kCylinder || o.shape == ObjectShape::kCapsule)
    half.x() = half.y() = std::max(half.x(), half.y());
  if (o.shape == ObjectShape::kCamera && half.isZero()) half = Eigen::Vector3d::Constant(0.025);
  const Eigen::Matrix3d R_WO = o.R_WO.normalized().toRotationMatrix();
  const Eigen::Vector3d right_W = pose.forward_W.cross(pose.up_W);
  const double focal = height / 2.0 / std::tan(fovy_deg * M_PI / 360.0);
  PixelRect rect{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d sign(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    const Eigen::Vector3d q = o.p_WO + R_WO * sign.cwiseProduct(half) - pose.p_WC;
    const double depth = q.dot(pose.forward_W);
    if (depth <= pose.near_m) return whole;
    const double u = width / 2.0 + focal * q.dot(right_W) / depth;
    const double v = height / 2.0 - focal * q.dot(pose.up_W) / depth;
    rect = {std::min(rect.x0, u), std::min(rect.y0, v), std::max(rect.x1, u), std::max(rect.y1, v)};
  }
  return {rect.x0 - 2, rect.y0 - 2, rect.x1 + 2, rect.y1 + 2};
}

// The objects (places in `objects`) in groups whose pictures cannot overlap, greedily in order.
std::vector<std::vector<size_t>> GroupApart(const RenderScene& scene,
                                            const std::vector<int>& objects,
                                            const CameraPose& pose, double fovy_deg, int width,
                                            int height) {
  std::vector<std::vector<size_t>> groups;
  std::vector<std::vector<PixelRect>> rects;
  for (size_t k = 0; k < objects.size(); ++k) {
    const PixelRect rect =
        CalcPixelRect(scene.objects[size_t(objects[k])], pose, fovy_deg, width, height);
    size_t g = 0;
    while (g < groups.size() && std::any_of(rects[g].begin(), rects[g].end(),
                                            [&](const PixelRect& r) { return r.Overlaps(rect); }))
      ++g;
    if (g == groups.size()) {
      groups.emplace_back();
      rects.emplace_back();
    }
    groups[g].push_back(k);
    rects[g].push_back(rect);
  }
  return groups;
}

}  // namespace

CameraPose Renderer::Prepare(const RenderScene& scene, const RenderOptions& options,
                             double* fovy_deg_out) {
  const CameraPose pose = CalcViewPose(scene, options);  // may throw: check before drawing
  State& s = *state_;
  s.UseMeshesOf(scene);
  s.EnsureBuffer(options.width, options.height);
  // Remakes the scene: before updating it. The model's own geoms are its meshes.
  s.EnsureGeomCapacity(CountSceneGeoms(scene) + s.model->ngeom);
  mjv_updateScene(s.model, s.data, &s.option, nullptr, &s.camera, mjCAT_ALL, &s.scene);
  const std::vector<MeshDrawing> meshes = s.ReadMeshDrawings();
  const SceneExtent extent = CalcSceneExtent(scene);
  s.scene.ngeom = 0;
  const RenderObject* viewpoint = options.view.kind == ViewKind::kCamera
                                      ? &FindViewpointObject(scene, options.view.camera_name)
                                      : nullptr;  // a camera does not see its own body
  AddSceneGeoms(scene, viewpoint, extent, s.floor_texture, s.model, meshes, options.decorations,
                s.scene);
  // Through a camera, its own field of view (the picture's size sets the aspect).
  const double fovy_deg = viewpoint ? viewpoint->fovy_deg : options.camera_fovy_deg;
  PlaceCameraAndLights(s.scene, s.context, pose, extent, fovy_deg);
  if (fovy_deg_out) *fovy_deg_out = fovy_deg;
  AddSceneLights(scene, extent, s.scene);
  return pose;
}

Image Renderer::Render(const RenderScene& scene, const RenderOptions& options, DepthImage* depth) {
  internal::EglContext::Scope current(state_->egl);
  const CameraPose pose = Prepare(scene, options);
  State& s = *state_;
  const mjrRect viewport = {0, 0, options.width, options.height};
  mjr_render(viewport, &s.scene, &s.context);
  if (!scene.caption.empty() && options.decorations)
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, scene.caption.c_str(), nullptr,
                &s.context);
  return ReadPicture(s.context, options, pose, depth);
}

LabelledPicture Renderer::RenderLabelled(const RenderScene& scene, const RenderOptions& options,
                                         const std::vector<int>& silhouettes_of) {
  for (const int i : silhouettes_of) {
    if (i < 0 || size_t(i) >= scene.objects.size())
      throw std::out_of_range("RenderLabelled: no object " + std::to_string(i));
  }
  internal::EglContext::Scope current(state_->egl);
  double fovy_deg = 0;
  const CameraPose pose = Prepare(scene, options, &fovy_deg);
  State& s = *state_;
  const mjrRect viewport = {0, 0, options.width, options.height};
  LabelledPicture out;
  out.pose = pose;
  mjr_render(viewport, &s.scene, &s.context);
  out.rgb = ReadPicture(s.context, options, pose, &out.depth);
  const int objects = int(scene.objects.size());
  s.scene.flags[mjRND_SEGMENT] = 1;
  s.scene.flags[mjRND_IDCOLOR] = 1;
  mjr_render(viewport, &s.scene, &s.context);
  out.visible = DecodeObjectIds(ReadPicture(s.context, options, pose, nullptr), objects);
  // Each object alone: only its geoms in the scene. Objects whose pictures cannot overlap
  // share a pass (GroupApart): none can hide another.
  const std::vector<mjvGeom> all(s.scene.geoms, s.scene.geoms + s.scene.ngeom);
  out.silhouettes.assign(silhouettes_of.size(),
                         std::vector<uint8_t>(size_t(options.width) * options.height, 0));
  for (const std::vector<size_t>& group :
       GroupApart(scene, silhouettes_of, pose, fovy_deg, options.width, options.height)) {
    s.scene.ngeom = 0;
    for (const mjvGeom& g : all) {
      for (const size_t k : group) {
        if (g.segid == silhouettes_of[k]) s.scene.geoms[s.scene.ngeom++] = g;
      }
    }
    if (s.scene.ngeom == 0) continue;
    mjr_render(viewport, &s.scene, &s.context);
    const ObjectIdImage alone =
        DecodeObjectIds(ReadPicture(s.context, options, pose, nullptr), objects);
    for (const size_t k : group) {
      std::vector<uint8_t>& mask = out.silhouettes[k];
      for (size_t p = 0; p < mask.size(); ++p) mask[p] = alone.object[p] == silhouettes_of[k];
    }
  }
  std::copy(all.begin(), all.end(), s.scene.geoms);
  s.scene.ngeom = int(all.size());
  s.scene.flags[mjRND_SEGMENT] = 0;
  s.scene.flags[mjRND_IDCOLOR] = 0;
  return out;
}

// --- ModelRenderer: a simulation's own model and cameras ---

struct ModelRenderer::State {
  internal::EglContext egl;  // first: MuJoCo's context needs a current OpenGL context
  const mjModel* model = nullptr;
  int width, height;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjrContext context;
  std::string context_key;  // CalcRenderContextKey of the model the context was made for

  // The context is current only inside each call (internal::EglContext::Scope): a
  // renderer may be used by one thread after another.
  State(int w, int h) : width(w), height(h) {
    InstallMujocoMessageHandlers();
    egl.Release();
    mjv_defaultScene(&scene);
    mjv_defaultOption(&option);
    mjv_defaultCamera(&camera);
    camera.type = mjCAMERA_FIXED;
    mjr_defaultContext(&context);
  }
  ~State() {
    internal::EglContext::Scope current(egl);
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
  }

  // MuJoCo's scene and render context hold the model's meshes, textures and buffer sizes:
  // they are remade only for a model that differs in those (render/context_key.h).
  void UseModel(const mjModel& m) {
    if (width > m.vis.global.offwidth || height > m.vis.global.offheight)
      throw std::runtime_error("the model's offscreen buffer is smaller than the picture");
    std::string key = CalcRenderContextKey(m);
    if (model && !key.empty() && key == context_key) {
      model = &m;
      return;
    }
    context_key.clear();
    internal::EglContext::Scope current(egl);
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
    mjv_makeScene(&m, &scene, 4000);
    mjr_makeContext(&m, &context, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &context);
    if (context.currentBuffer != mjFB_OFFSCREEN)
      throw std::runtime_error("MuJoCo could not make its offscreen framebuffer");
    model = &m;
    context_key = std::move(key);
  }
};

ModelRenderer::ModelRenderer(int width, int height)
    : state_(std::make_unique<State>(width, height)) {}
ModelRenderer::ModelRenderer(const mjModel& model, int width, int height)
    : ModelRenderer(width, height) {
  SetModel(model);
}
ModelRenderer::~ModelRenderer() = default;

void ModelRenderer::SetModel(const mjModel& model) { state_->UseModel(model); }

ModelRenderer::ClippingPlanes ModelRenderer::GetClippingPlanes() const {
  const mjModel* m = state_->model;
  if (!m) throw std::logic_error("ModelRenderer::GetClippingPlanes before SetModel");
  return {m->vis.map.znear * m->stat.extent, m->vis.map.zfar * m->stat.extent};
}

namespace {

// Drops every drawn geom that is not one of `body`'s own.
void KeepOnlyBody(const mjModel& model, int body, mjvScene& scene) {
  int kept = 0;
  for (int i = 0; i < scene.ngeom; ++i) {
    const mjvGeom& g = scene.geoms[i];
    if (g.objtype == mjOBJ_GEOM && model.geom_bodyid[g.objid] == body) scene.geoms[kept++] = g;
  }
  scene.ngeom = kept;
}

}  // namespace

Image ModelRenderer::Render(mjData& data, int camera_id, DepthImage* depth, int only_body) {
  State& s = *state_;
  if (!s.model) throw std::logic_error("ModelRenderer::Render before SetModel");
  internal::EglContext::Scope current(s.egl);
  s.camera.fixedcamid = camera_id;
  mjv_updateScene(s.model, &data, &s.option, nullptr, &s.camera, mjCAT_ALL, &s.scene);
  if (only_body >= 0) KeepOnlyBody(*s.model, only_body, s.scene);
  const mjrRect viewport = {0, 0, s.width, s.height};
  mjr_render(viewport, &s.scene, &s.context);
  Image image{s.width, s.height, std::vector<uint8_t>(size_t(s.width) * s.height * 3)};
  std::vector<float> raw_depth(depth ? size_t(s.width) * s.height : 0);
  mjr_readPixels(image.rgb.data(), depth ? raw_depth.data() : nullptr, viewport, &s.context);
  FlipRows(image.rgb, s.width, s.height, 3);
  if (depth) {
    const ClippingPlanes planes = GetClippingPlanes();
    FlipRows(raw_depth, s.width, s.height, 1);
    LinearizeDepth(raw_depth, planes.near_m, planes.far_m);
    *depth = DepthImage{s.width, s.height, std::move(raw_depth)};
  }
  return image;
}

}  // namespace prs::render
