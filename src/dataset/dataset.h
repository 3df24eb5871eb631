// Training data from scenes: each scene seen through its cameras, with labels that are exact by
// construction (MuJoCo's per-object segmentation buffer, never depth thresholds), written as a
// BOP dataset and COCO annotations that the BOP toolkit and pycocotools read unchanged
// (docs/dataset.md). A stage of its own: it uses render (pictures, segmentation), export (the
// objects' models) and output (scene lines); the CLI and campaigns use it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lang/lang.h"
#include "render/render.h"
#include "sampling/batch.h"
#include "sampling/sampler.h"

namespace prs::dataset {

struct DatasetOptions {
  std::string dir;  // written as DIR.partial, renamed to DIR when complete
  /// The camera objects looked through, by name (or class, when one object has it), in the
  /// order of their images; at least one (ListCameraObjects gives the default).
  std::vector<std::string> cameras;
  int width = 0, height = 0;  // 0: each camera's own aspect at 640 pixels wide
  bool bop = true, coco = true;
  bool jpeg = false;  // rgb/IMID.jpg (quality 95) instead of rgb/IMID.png
  /// The classes labelled (empty: every class). Other objects are drawn, not labelled.
  std::vector<std::string> labels;
  int64_t images_per_chunk = 1000;  // BOP's scene folders: train_pbr/000000, ...
};

/// The classes objects get ids by (obj_id and category_id = 1 + place): the program's class
/// table in its order (built-ins first, then as declared; a scenes file's reader's classes in
/// order of appearance), without the abstract Point3D and OrientedPoint3D, so that every run and
/// shard of one program agrees.
std::vector<std::string> ListClassIds(const lang::CompiledProgram& program);

/// The names of the scene's camera objects, in scene order: the cameras a dataset looks
/// through by default. The CLI takes them from scene 0 of the seed (or a file's first scene),
/// so that every shard of a dataset agrees.
std::vector<std::string> ListCameraObjects(const render::RenderScene& scene);

/// The cameras a dataset of `program` looks through by default: the camera objects of scene 0 of
/// `seed` (whatever range is written), so that every run and shard agrees. Throws what the
/// sampler throws (lang::ScenarioError).
std::vector<std::string> ListDefaultCameras(const lang::CompiledProgram& program,
                                            const sampling::SampleOptions& sample, uint64_t seed);

/// A view as a pinhole camera in OpenCV's convention: camera frame x right, y down, z forward;
/// pixel (u, v) is column u, row v from the top-left, the centre of the top-left pixel at
/// (0, 0). A world point p_W (metres) is seen at K (R_CW p_W + p_CW).
struct PinholeCamera {
  int width = 0, height = 0;              // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  Eigen::Matrix3d R_CW = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_CW = Eigen::Vector3d::Zero();  // metres: the world origin in camera frame
};

/// A view's entry of BOP's scene_camera.json as this stage writes it: cam_K (pixels, row-major),
/// cam_R_w2c, cam_t_w2c (mm), depth_scale (mm per depth unit), width and height (pixels). The
/// case study's perception requests carry the same fields (src/controllers).
nlohmann::ordered_json FormatSceneCamera(const PinholeCamera& camera, double depth_scale);

/// The pinhole model of a picture MuJoCo draws from `pose` with vertical field of view
/// `fovy_deg` at width x height (square pixels: the aspect comes from the picture's size).
PinholeCamera CalcPinholeCamera(const render::CameraPose& pose, double fovy_deg, int width,
                                int height);

/// A box [x, y, w, h] in pixels (x, y: the top-left pixel's column and row; BOP's bbox_obj and
/// bbox_visib, COCO's bbox); [-1, -1, -1, -1] for an empty mask (BOP's convention).
using PixelBox = std::array<int, 4>;
PixelBox CalcMaskBox(const std::vector<uint8_t>& mask, int width, int height);

/// COCO's compressed RLE of a mask (width * height values, row-major from the top, nonzero =
/// in): runs over the pixels in column-major order starting with a run of 0s, written as
/// pycocotools' `counts` string.
std::string EncodeCocoRle(const std::vector<uint8_t>& mask, int width, int height);

/// One labelled object in one picture.
struct ObjectLabel {
  int object = 0;  // index in the scene's objects
  int obj_id = 0;  // BOP's obj_id and COCO's category_id: 1 + the class's place in the list
  Eigen::Matrix3d R_CO = Eigen::Matrix3d::Identity();  // cam_R_m2c
  Eigen::Vector3d p_CO_mm = Eigen::Vector3d::Zero();   // cam_t_m2c, millimetres
  PixelBox bbox_obj{-1, -1, -1, -1}, bbox_visib{-1, -1, -1, -1};
  int64_t px_count_all = 0, px_count_valid = 0, px_count_visib = 0;
  double visib_fract = 0;
  std::vector<uint8_t> mask, mask_visib;  // width * height, 1 = in
};

/// What one picture's labels are made of, before any file is written.
struct LabelledView {
  std::string camera;  // the camera object's name
  PinholeCamera pinhole;
  double depth_scale = 1;  // millimetres per unit of the depth PNG (BOP's depth_scale)
  render::LabelledPicture picture;
  std::vector<ObjectLabel> objects;
  double render_s = 0, label_s = 0;  // time drawing (every pass) and making the labels
};

/// Where a dataset's time went, in seconds of the threads that spent it.
struct StageSeconds {
  double render = 0;    // colour, depth and segmentation passes
  double labels = 0;    // masks, counts, boxes, poses, RLE
  double pictures = 0;  // encoding and writing the pictures and masks (PNG, JPEG)
  double json = 0;      // the chunks' JSON files and models
};

/// Renders `scene` through `camera` (a name as DatasetOptions::cameras) and labels every object
/// whose class is in `class_ids` (the obj_id of class_ids[i] is i + 1) and `labels` (empty:
/// all), except points, lights and cameras (not drawn). Throws std::invalid_argument naming
/// the camera when the scene has no such object or it lacks fovy_deg, aspect, near or far.
LabelledView RenderLabelledView(render::Renderer& renderer, const render::RenderScene& scene,
                                const std::string& camera, const DatasetOptions& options,
                                const std::vector<std::string>& class_ids);

/// The pictures and labels of one scene, ready to be added to the dataset in index order.
struct SceneLabels;

/// Writes a dataset (docs/dataset.md) under DatasetOptions::dir: BOP folders with COCO
/// annotations beside them. The scene at `position` (its index when sampled, its place in a
/// scenes file) makes images g = position * cameras + camera number, the same for any thread
/// count or split of the range; image g goes to chunk g / images_per_chunk as im_id
/// g % images_per_chunk.
class DatasetWriter {
 public:
  /// Makes DIR.partial. Throws std::invalid_argument for no camera, a size under 16 pixels or
  /// images_per_chunk under 1. `class_ids`: obj_id i + 1 for class_ids[i] (the program's classes,
  /// so that ids agree across runs of one program). Throws std::runtime_error when DIR exists and
  /// is not empty, when DIR.partial exists (an earlier run's), or when it cannot be made.
  DatasetWriter(DatasetOptions options, std::vector<std::string> class_ids);
  ~DatasetWriter();
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  /// Renders one scene through every camera and writes its pictures and masks. Thread-safe:
  /// each thread draws with its own renderer. Throws std::invalid_argument for a missing
  /// camera (naming the scene), std::runtime_error for a file that cannot be written.
  std::shared_ptr<SceneLabels> RenderScene(const sampling::SampledScene& sampled,
                                           uint64_t position) const;

  /// Adds a rendered scene's labels; call in index order, on one thread. Writes a chunk's JSON
  /// files when its last image is in.
  void Add(const SceneLabels& labels);

  /// Writes the last chunk's JSON, camera.json and the models, then renames DIR.partial to
  /// DIR. Returns the number of images.
  int64_t Finish();

  /// The directory written to until Finish: DIR.partial.
  std::string partial_dir() const;
  /// The scenes added so far.
  int64_t scenes_added() const;
  /// The time spent so far, by stage.
  StageSeconds stage_seconds() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Renders `scenes` (scenes[k] at position positions[k]) on `threads` threads and adds them to
/// `writer` in order. On an error, the scenes before the first failing one are added and the
/// error is rethrown. Returns how many scenes were added.
int64_t AddScenes(DatasetWriter& writer, const std::vector<const sampling::SampledScene*>& scenes,
                  const std::vector<uint64_t>& positions, int threads);

/// Samples scenes batch.start .. start + count - 1 of `program` on the batch's threads, renders
/// each on the thread that sampled it and adds it to `writer` in index order. `callbacks` may
/// add a `tick` and a `consume` (run after each scene is added: progress); its `prepare` and
/// `format` must be empty. Throws what SampleBatch throws; the scenes before a failing one are
/// added.
void AddSampledScenes(DatasetWriter& writer, const lang::CompiledProgram& program,
                      const sampling::BatchOptions& batch, sampling::BatchCallbacks callbacks = {});

/// Merges datasets of disjoint image ranges (a campaign's shards, in index order) into `out`
/// (written as OUT.partial, renamed when complete): the pictures hard-linked (copied across
/// file systems), each chunk's JSON and scene lines joined in order, camera.json and each
/// model from the first part that has it. The result is the files one run over the union
/// writes, byte for byte. Throws std::runtime_error when `out` exists and is not empty, or two
/// parts hold the same picture.
void MergeDatasets(const std::vector<std::string>& parts, const std::string& out);

/// Grows the dataset `dir` by `addition` (a dataset of other images, numbered by the same
/// classes): the two merged as MergeDatasets does into DIR.merging, which then takes DIR's
/// place; `addition` is removed. Throws std::runtime_error, with DIR unchanged and `addition`
/// kept, when their COCO categories differ or their images overlap.
void AppendDataset(const std::string& dir, const std::string& addition);

}  // namespace prs::dataset
