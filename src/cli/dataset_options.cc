// --camera, --size, --format and --label of `prs dataset` and `prs campaign init --dataset`.
#include "cli/dataset_options.h"

#include <tuple>

#include "render/render.h"

namespace prs::cli {

void AddDatasetPictureOptions(CLI::App& command, DatasetPictureArgs& args) {
  command
      .add_option("--camera", args.cameras,
                  "look through this camera object (repeatable; default: every camera object)")
      ->type_name("NAME");
  command
      .add_option("--size", args.size,
                  "picture size (default: each camera's aspect at 640 pixels wide)")
      ->type_name("WxH");
  command.add_option("--format", args.format, "what to write: BOP, COCO or both")
      ->type_name("bop|coco|both")
      ->check(CLI::IsMember({"bop", "coco", "both"}))
      ->capture_default_str();
  command
      .add_option("--label", args.labels,
                  "label only objects of this class (repeatable; default: every class)")
      ->type_name("CLASS");
  command.add_flag("--jpeg", args.jpeg,
                   "colour pictures as JPEG (quality 95, BOP's train_pbr habit) instead of PNG");
}

std::string ReadDatasetPictureArgs(const DatasetPictureArgs& args,
                                   dataset::DatasetOptions& options) {
  if (!args.size.empty()) {
    try {
      std::tie(options.width, options.height) = render::ParseSize(args.size);
    } catch (const std::invalid_argument& error) {
      return std::string("--size: ") + error.what();
    }
  }
  options.bop = args.format != "coco";
  options.coco = args.format != "bop";
  options.labels = args.labels;
  options.cameras = args.cameras;
  options.jpeg = args.jpeg;
  return "";
}

std::string DescribeNoCamera(const std::string& where) {
  return where +
         " has no camera object to look through: add one (examples/model.prs's Camera class "
         "has the fovy_deg, aspect, near and far a dataset needs) or name an object with "
         "--camera NAME";
}

}  // namespace prs::cli
