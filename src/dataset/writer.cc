// DatasetWriter: the files of a dataset. Workers render scenes and write each picture's PNGs
// (rgb/, depth/, mask/, mask_visib/); the calling thread adds the labels in index order and
// writes each chunk's JSON (BOP's scene_camera, scene_gt, scene_gt_info; COCO's
// annotations.json; the scenes' lines) when its last image is in, then camera.json and the
// models. Everything goes to DIR.partial, renamed to DIR when complete.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "dataset/dataset.h"
#include "dataset/files.h"
#include "dataset/models.h"
#include "export/export.h"
#include "output/scene_json.h"
#include "render/scene_input.h"

namespace prs::dataset {

namespace fs = std::filesystem;

// COCO annotation ids: image g's k-th labelled object is g * kMaxLabelsPerImage + k + 1, unique
// across chunks, shards and runs of the same dataset.
constexpr int64_t kMaxLabelsPerImage = 10000;

struct ImageRecord {
  uint64_t image = 0;  // g
  std::string camera;
  PinholeCamera pinhole;
  double depth_scale = 1;
  struct Object {
    int obj_id = 0;
    Eigen::Matrix3d R_CO;
    Eigen::Vector3d p_CO_mm;
    PixelBox bbox_obj, bbox_visib;
    int64_t px_count_all = 0, px_count_valid = 0, px_count_visib = 0;
    double visib_fract = 0;
    std::string rle;  // COCO, of the visible mask
  };
  std::vector<Object> objects;
};

struct SceneLabels {
  uint64_t index = 0;  // the scene's position
  std::string line;    // the scene's line with its images and features
  std::vector<ImageRecord> images;
  // Per class labelled in the scene, its obj_id and its first labelled object's body.
  std::vector<std::pair<int, exporting::Body>> bodies;
};

namespace {

Json FormatMatrix(const Eigen::Matrix3d& R) {
  Json m = Json::array();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.push_back(R(i, j));
  return m;
}

Json FormatVector(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace

Json FormatSceneCamera(const PinholeCamera& c, double depth_scale) {
  return {{"cam_K", {c.fx, 0.0, c.cx, 0.0, c.fy, c.cy, 0.0, 0.0, 1.0}},
          {"cam_R_w2c", FormatMatrix(c.R_CW)},
          {"cam_t_w2c", FormatVector(1000.0 * c.p_CW)},
          {"depth_scale", depth_scale},
          {"width", c.width},
          {"height", c.height}};
}

namespace {

Json FormatBox(const PixelBox& b) { return Json::array({b[0], b[1], b[2], b[3]}); }

std::string ImageName(uint64_t im_id) { return fmt::format("{:06d}", im_id); }

}  // namespace

std::string ReadFileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct DatasetWriter::State {
  DatasetOptions options;
  std::vector<std::string> class_ids;
  fs::path dir, partial;
  // The chunks whose last image is not in yet.
  struct Chunk {
    Json scene_camera = Json::object(), scene_gt = Json::object(), scene_gt_info = Json::object();
    Json images = Json::array(), annotations = Json::array();
    std::string scenes;  // lines
    int64_t images_in = 0;
  };
  std::map<uint64_t, Chunk> chunks;
  std::map<int, exporting::Body> models;   // obj_id -> its class's first labelled object
  std::optional<ImageRecord> first_image;  // for camera.json
  int64_t images = 0, scenes = 0;
  bool finished = false;
  // StageSeconds in nanoseconds, added to by every thread.
  std::atomic<int64_t> render_ns{0}, labels_ns{0}, pictures_ns{0}, json_ns{0};
  // Renderers (OpenGL contexts) free for the next scene: one per thread drawing at once.
  std::mutex pool_mutex;
  std::vector<std::unique_ptr<render::Renderer>> pool;

  std::unique_ptr<render::Renderer> TakeRenderer() {
    {
      std::lock_guard<std::mutex> lock(pool_mutex);
      if (!pool.empty()) {
        std::unique_ptr<render::Renderer> renderer = std::move(pool.back());
        pool.pop_back();
        return renderer;
      }
    }
    return std::make_unique<render::Renderer>();
  }
  void ReturnRenderer(std::unique_ptr<render::Renderer> renderer) {
    std::lock_guard<std::mutex> lock(pool_mutex);
    pool.push_back(std::move(renderer));
  }

  const char* PictureExtension() const { return options.jpeg ? ".jpg" : ".png"; }
  uint64_t chunk_of(uint64_t g) const { return g / uint64_t(options.images_per_chunk); }
  uint64_t im_id_of(uint64_t g) const { return g % uint64_t(options.images_per_chunk); }
  fs::path chunk_dir(uint64_t chunk) const {
    return partial / "train_pbr" / fmt::format("{:06d}", chunk);
  }

  Json Categories() const {
    Json categories = Json::array();
    for (size_t i = 0; i < class_ids.size(); ++i) {
      const std::string& name = class_ids[i];
      if (!options.labels.empty() &&
          std::find(options.labels.begin(), options.labels.end(), name) == options.labels.end())
        continue;
      categories.push_back({{"id", int(i) + 1}, {"name", name}, {"supercategory", "object"}});
    }
    return categories;
  }

  void WriteChunk(uint64_t number, const Chunk& chunk) {
    const auto begin = std::chrono::steady_clock::now();
    WriteChunkFiles(number, chunk);
    json_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::steady_clock::now() - begin)
                   .count();
  }

  void WriteChunkFiles(uint64_t number, const Chunk& chunk) const {
    const fs::path folder = chunk_dir(number);
    fs::create_directories(folder);
    if (options.bop) {
      WriteFileAtomically(folder / "scene_camera.json", FormatBopJson(chunk.scene_camera));
      WriteFileAtomically(folder / "scene_gt.json", FormatBopJson(chunk.scene_gt));
      WriteFileAtomically(folder / "scene_gt_info.json", FormatBopJson(chunk.scene_gt_info));
    }
    if (options.coco) {
      Json coco;
      coco["info"] = {{"description", "prs dataset (docs/dataset.md)"}, {"version", "1.0"}};
      coco["licenses"] = Json::array();
      coco["categories"] = Categories();
      coco["images"] = chunk.images;
      coco["annotations"] = chunk.annotations;
      WriteFileAtomically(folder / "annotations.json", FormatCocoJson(coco));
    }
    WriteFileAtomically(folder / "scenes.jsonl", chunk.scenes);
  }

  void AddImage(const ImageRecord& image) {
    const uint64_t number = chunk_of(image.image), im_id = im_id_of(image.image);
    Chunk& chunk = chunks[number];
    const std::string key = std::to_string(im_id);
    const PinholeCamera& c = image.pinhole;
    chunk.scene_camera[key] = FormatSceneCamera(c, image.depth_scale);
    chunk.scene_camera[key]["camera"] = image.camera;
    Json gt = Json::array(), info = Json::array();
    for (size_t k = 0; k < image.objects.size(); ++k) {
      const ImageRecord::Object& o = image.objects[k];
      gt.push_back({{"obj_id", o.obj_id},
                    {"cam_R_m2c", FormatMatrix(o.R_CO)},
                    {"cam_t_m2c", FormatVector(o.p_CO_mm)}});
      info.push_back({{"bbox_obj", FormatBox(o.bbox_obj)},
                      {"bbox_visib", FormatBox(o.bbox_visib)},
                      {"px_count_all", o.px_count_all},
                      {"px_count_valid", o.px_count_valid},
                      {"px_count_visib", o.px_count_visib},
                      {"visib_fract", o.visib_fract}});
      if (o.px_count_visib == 0) continue;  // COCO keeps only what shows
      chunk.annotations.push_back(
          {{"id", int64_t(image.image) * kMaxLabelsPerImage + int64_t(k) + 1},
           {"image_id", image.image},
           {"category_id", o.obj_id},
           {"bbox", FormatBox(o.bbox_visib)},
           {"area", o.px_count_visib},
           {"segmentation", {{"size", {c.height, c.width}}, {"counts", o.rle}}},
           {"iscrowd", 0}});
    }
    chunk.scene_gt[key] = std::move(gt);
    chunk.scene_gt_info[key] = std::move(info);
    chunk.images.push_back({{"id", image.image},
                            {"file_name", "rgb/" + ImageName(im_id) + PictureExtension()},
                            {"width", c.width},
                            {"height", c.height}});
    if (!first_image) first_image = image;
    ++images;
    if (++chunk.images_in == options.images_per_chunk) {
      WriteChunk(number, chunk);
      chunks.erase(number);
    }
  }
};

DatasetWriter::DatasetWriter(DatasetOptions options, std::vector<std::string> class_ids)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  if (options.cameras.empty()) throw std::invalid_argument("a dataset needs a camera");
  if ((options.width != 0 || options.height != 0) && (options.width < 16 || options.height < 16))
    throw std::invalid_argument("a dataset's pictures are at least 16 x 16 pixels");
  if (options.images_per_chunk < 1) throw std::invalid_argument("a chunk holds an image or more");
  s.dir = options.dir;
  s.partial = options.dir + ".partial";
  s.options = std::move(options);
  s.class_ids = std::move(class_ids);
  std::error_code error;
  if (fs::exists(s.dir, error) && !(fs::is_directory(s.dir) && fs::is_empty(s.dir))) {
    throw std::runtime_error(fmt::format(
        "{} exists and is not an empty directory: give a new one (a dataset is never written "
        "over another)",
        s.dir.string()));
  }
  if (fs::exists(s.partial, error)) {
    throw std::runtime_error(fmt::format(
        "{} holds an earlier run's unfinished dataset: remove it, or move it aside to keep it",
        s.partial.string()));
  }
  fs::create_directories(s.partial / "train_pbr", error);
  if (error) {
    throw std::runtime_error(
        fmt::format("cannot make {}: {}", s.partial.string(), error.message()));
  }
}

DatasetWriter::~DatasetWriter() = default;

std::string DatasetWriter::partial_dir() const { return state_->partial.string(); }

StageSeconds DatasetWriter::stage_seconds() const {
  const State& s = *state_;
  return {1e-9 * double(s.render_ns), 1e-9 * double(s.labels_ns), 1e-9 * double(s.pictures_ns),
          1e-9 * double(s.json_ns)};
}

std::shared_ptr<SceneLabels> DatasetWriter::RenderScene(const sampling::SampledScene& sampled,
                                                        uint64_t position) const {
  State& s = *state_;
  // A renderer of the pool for this scene, returned to it however the scene ends.
  struct Lease {
    State& s;
    std::unique_ptr<render::Renderer> renderer;
    ~Lease() { s.ReturnRenderer(std::move(renderer)); }
  } lease{s, s.TakeRenderer()};
  render::Renderer* renderer = lease.renderer.get();
  const render::RenderScene scene = render::MakeRenderScene(sampled.scene);
  const exporting::ExportScene bodies = exporting::MakeExportScene(sampled.scene, "");
  auto labels = std::make_shared<SceneLabels>();
  labels->index = position;
  Json images = Json::array();
  const uint64_t cameras = s.options.cameras.size();
  for (size_t c = 0; c < cameras; ++c) {
    LabelledView view;
    try {
      view = RenderLabelledView(*renderer, scene, s.options.cameras[c], s.options, s.class_ids);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(
          fmt::format("scene {} of seed {}: {}", sampled.index, sampled.seed, error.what()));
    }
    ImageRecord image;
    image.image = position * cameras + c;
    image.camera = view.camera;
    image.pinhole = view.pinhole;
    image.depth_scale = view.depth_scale;
    const int w = view.pinhole.width, h = view.pinhole.height;
    const auto encoding = std::chrono::steady_clock::now();
    for (const ObjectLabel& o : view.objects) {
      image.objects.push_back({o.obj_id, o.R_CO, o.p_CO_mm, o.bbox_obj, o.bbox_visib,
                               o.px_count_all, o.px_count_valid, o.px_count_visib, o.visib_fract,
                               s.options.coco ? EncodeCocoRle(o.mask_visib, w, h) : ""});
      // A model is its class's first labelled object: one body per class and scene suffices.
      const auto& kept = labels->bodies;
      if (std::none_of(kept.begin(), kept.end(),
                       [&](const auto& b) { return b.first == o.obj_id; }))
        labels->bodies.emplace_back(o.obj_id, bodies.bodies[size_t(o.object)]);
    }
    const auto writing = std::chrono::steady_clock::now();
    const uint64_t im_id = s.im_id_of(image.image);
    const fs::path folder = s.chunk_dir(s.chunk_of(image.image));
    const std::string name = ImageName(im_id);
    fs::create_directories(folder / "rgb");
    const std::string picture = (folder / "rgb" / (name + s.PictureExtension())).string();
    if (s.options.jpeg) {
      render::WriteJpeg(view.picture.rgb, picture);
    } else {
      render::WritePng(view.picture.rgb, picture);
    }
    if (s.options.bop) {
      fs::create_directories(folder / "depth");
      fs::create_directories(folder / "mask");
      fs::create_directories(folder / "mask_visib");
      render::WriteDepthPng(view.picture.depth, (folder / "depth" / (name + ".png")).string(),
                            view.depth_scale);
      for (size_t k = 0; k < view.objects.size(); ++k) {
        const std::string mask_name = fmt::format("{}_{:06d}.png", name, k);
        render::WriteMaskPng(view.objects[k].mask, w, h, (folder / "mask" / mask_name).string());
        render::WriteMaskPng(view.objects[k].mask_visib, w, h,
                             (folder / "mask_visib" / mask_name).string());
      }
    }
    const auto written = std::chrono::steady_clock::now();
    const auto ns = [](auto duration) {
      return int64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(duration).count());
    };
    s.render_ns += int64_t(view.render_s * 1e9);
    s.labels_ns += int64_t(view.label_s * 1e9) + ns(writing - encoding);
    s.pictures_ns += ns(written - writing);
    images.push_back(
        {{"chunk", s.chunk_of(image.image)}, {"im_id", im_id}, {"camera", view.camera}});
    labels->images.push_back(std::move(image));
  }
  // The scene's line as `prs sample` writes it, with the images it made and its features (the
  // inputs of `prs report` and `--like`) after its own fields.
  std::string line = output::FormatSceneJson(sampled);
  line.pop_back();  // its closing brace
  Json extra;
  extra["images"] = std::move(images);
  Json features = Json::object();
  for (const auto& [name, value] : output::CalcSceneFeatures(sampled.scene)) features[name] = value;
  extra["features"] = std::move(features);
  if (!sampled.coordinates.empty()) extra["coordinates"] = sampled.coordinates;
  const std::string fields = extra.dump();
  labels->line = line + "," + fields.substr(1) + "\n";
  return labels;
}

void AddSampledScenes(DatasetWriter& writer, const lang::CompiledProgram& program,
                      const sampling::BatchOptions& batch, sampling::BatchCallbacks callbacks) {
  if (callbacks.prepare || callbacks.format)
    throw std::invalid_argument("AddSampledScenes: prepare and format are its own");
  // Each scene is rendered by the worker that sampled it; the labels wait here for their turn.
  std::mutex mutex;
  std::map<uint64_t, std::shared_ptr<SceneLabels>> rendered;
  callbacks.prepare = [&](sampling::BatchScene& scene) {
    auto labels = writer.RenderScene(scene.sampled, scene.sampled.index);
    std::lock_guard<std::mutex> lock(mutex);
    rendered[scene.sampled.index] = std::move(labels);
  };
  callbacks.consume = [&, after = std::move(callbacks.consume)](sampling::BatchScene&& scene) {
    std::shared_ptr<SceneLabels> labels;
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = rendered.find(scene.sampled.index);
      labels = std::move(it->second);
      rendered.erase(it);
    }
    writer.Add(*labels);
    if (after) after(std::move(scene));
  };
  sampling::SampleBatch(program, batch, callbacks);
}

void DatasetWriter::Add(const SceneLabels& labels) {
  State& s = *state_;
  if (s.finished) throw std::logic_error("DatasetWriter::Add after Finish");
  if (!labels.images.empty()) {
    s.chunks[s.chunk_of(labels.images.front().image)].scenes += labels.line;
  }
  for (const auto& [obj_id, body] : labels.bodies) s.models.emplace(obj_id, body);
  for (const ImageRecord& image : labels.images) s.AddImage(image);
  ++s.scenes;
}

int64_t DatasetWriter::scenes_added() const { return state_->scenes; }

int64_t DatasetWriter::Finish() {
  State& s = *state_;
  if (s.finished) throw std::logic_error("DatasetWriter::Finish twice");
  for (const auto& [number, chunk] : s.chunks) s.WriteChunk(number, chunk);
  s.chunks.clear();
  const auto begin = std::chrono::steady_clock::now();
  if (s.first_image && s.options.bop) {
    const PinholeCamera& c = s.first_image->pinhole;
    const Json camera = {
        {"cx", c.cx},      {"cy", c.cy}, {"depth_scale", s.first_image->depth_scale},
        {"fx", c.fx},      {"fy", c.fy}, {"height", c.height},
        {"width", c.width}};
    WriteFileAtomically(s.partial / "camera.json", FormatBopJson(camera));
    fs::create_directories(s.partial / "models");
    Json info = Json::object();
    for (const auto& [obj_id, body] : s.models) {
      const ModelFile model = MakeModelFile(body);
      WriteFileAtomically(s.partial / "models" / fmt::format("obj_{:06d}.ply", obj_id), model.ply);
      info[std::to_string(obj_id)] = model.info;
    }
    WriteFileAtomically(s.partial / "models" / "models_info.json", FormatBopJson(info));
  }
  s.json_ns +=
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - begin)
          .count();
  std::error_code error;
  if (fs::exists(s.dir, error)) fs::remove(s.dir);  // empty, as the constructor checked
  fs::rename(s.partial, s.dir);
  s.finished = true;
  return s.images;
}

int64_t AddScenes(DatasetWriter& writer, const std::vector<const sampling::SampledScene*>& scenes,
                  const std::vector<uint64_t>& positions, int threads) {
  if (positions.size() != scenes.size())
    throw std::invalid_argument("AddScenes: a position per scene");
  std::vector<std::shared_ptr<SceneLabels>> rendered(scenes.size());
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  size_t failed_at = scenes.size();
  std::mutex failure_mutex;
  const auto work = [&] {
    for (size_t i = next++; i < scenes.size(); i = next++) {
      try {
        rendered[i] = writer.RenderScene(*scenes[i], positions[i]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (i < failed_at) failure = std::current_exception(), failed_at = i;
      }
    }
  };
  std::vector<std::thread> workers;
  const int count = std::max(1, std::min<int>(threads, int(scenes.size())));
  for (int t = 1; t < count; ++t) workers.emplace_back(work);
  work();
  for (std::thread& t : workers) t.join();
  int64_t added = 0;
  for (size_t i = 0; i < failed_at; ++i, ++added) writer.Add(*rendered[i]);
  if (failure) std::rethrow_exception(failure);
  return added;
}

}  // namespace prs::dataset
