// Internal to src/dataset: how its JSON files are laid out and written, shared by the writer and
// the merge so that a merged dataset is byte for byte one run's.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "output/line_writer.h"

namespace prs::dataset {

using Json = nlohmann::ordered_json;

/// BOP's files (scene_camera, scene_gt, scene_gt_info, camera, models_info): one space a level.
inline std::string FormatBopJson(const Json& json) { return json.dump(1) + "\n"; }
/// COCO's annotations.json: one line.
inline std::string FormatCocoJson(const Json& json) { return json.dump() + "\n"; }

/// Written whole or not at all (output/line_writer.h). Throws std::runtime_error.
inline void WriteFileAtomically(const std::filesystem::path& path, const std::string& bytes) {
  output::WriteFileAtomically(path.string(), bytes);
}

/// The whole file. Throws std::runtime_error naming it when it cannot be read.
std::string ReadFileBytes(const std::filesystem::path& path);

}  // namespace prs::dataset
