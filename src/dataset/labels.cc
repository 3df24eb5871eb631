// One picture's labels: the pinhole model of the view, each labelled object's pose in the
// camera frame, its full and visible masks from the renderer's segmentation passes, and the
// counts and boxes BOP's scene_gt_info.json holds; COCO's RLE of a mask.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dataset/dataset.h"
#include "lang/program.h"
#include "render/scene_input.h"

namespace prs::dataset {
namespace {

constexpr int kDefaultWidth = 640;

// Millimetres per unit of the depth PNG: the finest of 0.1, 1 and 10 that holds the picture's
// farthest depth in 16 bits.
double ChooseDepthScale(const render::DepthImage& depth) {
  double farthest_mm = 0;
  for (const float d : depth.depth_m) {
    if (std::isfinite(d)) farthest_mm = std::max(farthest_mm, 1000.0 * d);
  }
  for (const double scale : {0.1, 1.0}) {
    if (farthest_mm / scale <= 65535) return scale;
  }
  return 10.0;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    text += i == 0 ? "" : i + 1 == names.size() ? " and " : ", ";
    text += names[i];
  }
  return text;
}

}  // namespace

std::vector<std::string> ListClassIds(const lang::CompiledProgram& program) {
  std::vector<std::string> names;
  for (const auto& info : program.classes) {
    if (info->name != "Point3D" && info->name != "OrientedPoint3D") names.push_back(info->name);
  }
  return names;
}

std::vector<std::string> ListCameraObjects(const render::RenderScene& scene) {
  std::vector<std::string> names;
  for (const render::RenderObject& o : scene.objects) {
    if (o.shape == render::ObjectShape::kCamera) names.push_back(o.name);
  }
  return names;
}

std::vector<std::string> ListDefaultCameras(const lang::CompiledProgram& program,
                                            const sampling::SampleOptions& sample, uint64_t seed) {
  sampling::SceneSampler sampler(program, sample);
  return ListCameraObjects(render::MakeRenderScene(sampler.Sample(seed, 0).scene));
}

PinholeCamera CalcPinholeCamera(const render::CameraPose& pose, double fovy_deg, int width,
                                int height) {
  const Eigen::Vector3d forward_W = pose.forward_W.normalized();
  const Eigen::Vector3d up_W = (pose.up_W - pose.up_W.dot(forward_W) * forward_W).normalized();
  const Eigen::Vector3d right_W = forward_W.cross(up_W);
  PinholeCamera camera;
  camera.width = width;
  camera.height = height;
  camera.R_CW.row(0) = right_W.transpose();
  camera.R_CW.row(1) = -up_W.transpose();  // image rows run down
  camera.R_CW.row(2) = forward_W.transpose();
  camera.p_CW = -camera.R_CW * pose.p_WC;
  // OpenGL's frustum spans the picture's edges; OpenCV's pixel centres are whole numbers.
  camera.fy = (height / 2.0) / std::tan(fovy_deg * M_PI / 360.0);
  camera.fx = camera.fy;
  camera.cx = width / 2.0 - 0.5;
  camera.cy = height / 2.0 - 0.5;
  return camera;
}

PixelBox CalcMaskBox(const std::vector<uint8_t>& mask, int width, int height) {
  int x0 = width, y0 = height, x1 = -1, y1 = -1;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!mask[size_t(y) * width + x]) continue;
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return {-1, -1, -1, -1};
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

std::string EncodeCocoRle(const std::vector<uint8_t>& mask, int width, int height) {
  // Run lengths down the columns, the first run of 0s (possibly empty).
  std::vector<int64_t> runs;
  uint8_t current = 0;
  int64_t length = 0;
  for (int x = 0; x < width; ++x) {
    for (int y = 0; y < height; ++y) {
      const uint8_t in = mask[size_t(y) * width + x] ? 1 : 0;
      if (in != current) {
        runs.push_back(length);
        length = 0;
        current = in;
      }
      ++length;
    }
  }
  runs.push_back(length);
  // pycocotools' rleToString: each count after the second as the difference to the one two
  // before, in 5-bit groups, least significant first, with 0x20 marking "more follows", each
  // group offset by 48 into printable ASCII.
  std::string counts;
  for (size_t i = 0; i < runs.size(); ++i) {
    int64_t x = runs[i];
    if (i > 2) x -= runs[i - 2];
    bool more = true;
    while (more) {
      int64_t c = x & 0x1f;
      x >>= 5;  // arithmetic: a negative difference keeps its sign
      more = (c & 0x10) ? x != -1 : x != 0;
      if (more) c |= 0x20;
      counts.push_back(char(c + 48));
    }
  }
  return counts;
}

LabelledView RenderLabelledView(render::Renderer& renderer, const render::RenderScene& scene,
                                const std::string& camera, const DatasetOptions& options,
                                const std::vector<std::string>& class_ids) {
  const render::RenderObject& viewpoint = render::FindViewpointObject(scene, camera);
  if (!viewpoint.missing_view_properties.empty()) {
    throw std::invalid_argument(fmt::format(
        "camera '{}' has no {}: a dataset needs each camera's fovy_deg (degrees), aspect "
        "(width / height), near and far (metres); give them in its class, as examples/model.prs "
        "does for Camera",
        camera, JoinNames(viewpoint.missing_view_properties)));
  }
  render::RenderOptions view;
  view.width = options.width > 0 ? options.width : kDefaultWidth;
  view.height =
      options.height > 0 ? options.height : int(std::lround(kDefaultWidth / viewpoint.aspect));
  view.view = {render::ViewKind::kCamera, camera};
  view.decorations = false;
  // The objects labelled: of a class asked for, with a solid; not cameras (viewpoints, not
  // drawn without decorations: a scene's several views), lights or points.
  std::vector<int> labelled;
  std::vector<int> obj_ids;
  bool asked_for_a_camera = false;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const render::RenderObject& o = scene.objects[i];
    if (!options.labels.empty() && std::find(options.labels.begin(), options.labels.end(),
                                             o.class_name) == options.labels.end())
      continue;
    asked_for_a_camera |= o.shape == render::ObjectShape::kCamera && !options.labels.empty();
    if (o.shape == render::ObjectShape::kCamera || o.shape == render::ObjectShape::kPoint ||
        o.shape == render::ObjectShape::kLight)
      continue;
    const auto id = std::find(class_ids.begin(), class_ids.end(), o.class_name);
    if (id == class_ids.end())
      throw std::invalid_argument(
          fmt::format("object {} has class {}, which has no id", o.name, o.class_name));
    labelled.push_back(int(i));
    obj_ids.push_back(int(id - class_ids.begin()) + 1);
  }
  if (labelled.empty()) {
    throw std::invalid_argument(
        options.labels.empty()
            ? fmt::format("camera '{}' has nothing to label: the scene has no other object", camera)
        : asked_for_a_camera
            ? fmt::format("--label {}: cameras are not labelled (they are the viewpoints, not "
                          "drawn in a dataset's pictures); label the objects they see",
                          JoinNames(options.labels))
            : fmt::format("the scene has no object of class {} to label (--label)",
                          JoinNames(options.labels)));
  }
  LabelledView out;
  out.camera = viewpoint.name;
  const auto begin = std::chrono::steady_clock::now();
  out.picture = renderer.RenderLabelled(scene, view, labelled);
  const auto drawn = std::chrono::steady_clock::now();
  out.render_s = std::chrono::duration<double>(drawn - begin).count();
  out.pinhole = CalcPinholeCamera(out.picture.pose, viewpoint.fovy_deg, view.width, view.height);
  out.depth_scale = ChooseDepthScale(out.picture.depth);
  const size_t pixels = size_t(view.width) * size_t(view.height);
  for (size_t k = 0; k < labelled.size(); ++k) {
    const render::RenderObject& o = scene.objects[size_t(labelled[k])];
    ObjectLabel label;
    label.object = labelled[k];
    label.obj_id = obj_ids[k];
    label.R_CO = out.pinhole.R_CW * o.R_WO.normalized().toRotationMatrix();
    label.p_CO_mm = 1000.0 * (out.pinhole.R_CW * o.p_WO + out.pinhole.p_CW);
    label.mask = std::move(out.picture.silhouettes[k]);
    label.mask_visib.assign(pixels, 0);
    for (size_t p = 0; p < pixels; ++p) {
      label.mask_visib[p] = out.picture.visible.object[p] == labelled[k];
      label.px_count_visib += label.mask_visib[p];
      if (!label.mask[p]) continue;
      ++label.px_count_all;
      // Valid: the depth PNG holds a measurement there (BOP's px_count_valid).
      const double units = std::round(1000.0 * out.picture.depth.depth_m[p] / out.depth_scale);
      label.px_count_valid += std::isfinite(units) && units > 0 && units <= 65535;
    }
    label.visib_fract =
        label.px_count_all > 0 ? double(label.px_count_visib) / double(label.px_count_all) : 0.0;
    label.bbox_obj = CalcMaskBox(label.mask, view.width, view.height);
    label.bbox_visib = CalcMaskBox(label.mask_visib, view.width, view.height);
    out.objects.push_back(std::move(label));
  }
  out.picture.silhouettes.clear();
  out.label_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - drawn).count();
  return out;
}

}  // namespace prs::dataset
