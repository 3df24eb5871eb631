// MergeDatasets: datasets of disjoint image ranges joined into the one a single run writes.
// Pictures are hard-linked; each chunk's JSON is read back and its entries appended in the
// parts' order (the image order), then written exactly as the writer writes it (files.h).
#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <stdexcept>

#include "dataset/dataset.h"
#include "dataset/files.h"

namespace prs::dataset {
namespace {

namespace fs = std::filesystem;

constexpr const char* kBopFiles[] = {"scene_camera.json", "scene_gt.json", "scene_gt_info.json"};

Json ReadJson(const fs::path& path) {
  try {
    return Json::parse(ReadFileBytes(path));
  } catch (const Json::exception& error) {
    throw std::runtime_error(fmt::format("{} is not JSON: {}", path.string(), error.what()));
  }
}

// A picture or model into the merged tree: a hard link, or a copy where links cannot go.
void PlaceFile(const fs::path& from, const fs::path& to) {
  if (fs::exists(to)) {
    throw std::runtime_error(
        fmt::format("{} is in two of the datasets merged: their ranges overlap", to.string()));
  }
  std::error_code error;
  fs::create_hard_link(from, to, error);
  if (error) fs::copy_file(from, to);
}

// One chunk's files, as they accumulate over the parts.
struct Chunk {
  std::map<std::string, Json> bop;  // file name -> object keyed by image id
  Json coco;                        // null until a part has annotations.json
  std::string scenes;
};

}  // namespace

void MergeDatasets(const std::vector<std::string>& parts, const std::string& out) {
  const fs::path dir = out, partial = out + ".partial";
  if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir))) {
    throw std::runtime_error(fmt::format(
        "{} exists and is not an empty directory: give a new one (a dataset is never written "
        "over another)",
        out));
  }
  fs::remove_all(partial);              // an earlier merge's: everything in it comes from the parts
  std::map<std::string, Chunk> chunks;  // by folder name: "000000", ...
  std::map<int, std::pair<fs::path, Json>> models;  // obj_id -> its first part's file and info
  bool have_camera = false;
  for (const std::string& part : parts) {
    const fs::path root = part;
    if (!fs::is_directory(root / "train_pbr"))
      throw std::runtime_error(fmt::format("{} is not a dataset (no train_pbr/)", part));
    if (!have_camera && fs::exists(root / "camera.json")) {
      fs::create_directories(partial);
      WriteFileAtomically(partial / "camera.json", ReadFileBytes(root / "camera.json"));
      have_camera = true;
    }
    if (fs::exists(root / "models" / "models_info.json")) {
      const Json infos = ReadJson(root / "models" / "models_info.json");
      for (const auto& [id, info] : infos.items()) {
        const int obj_id = std::stoi(id);
        if (!models.count(obj_id))
          models[obj_id] = {root / "models" / fmt::format("obj_{:06d}.ply", obj_id), info};
      }
    }
    for (const auto& folder : fs::directory_iterator(root / "train_pbr")) {
      const std::string name = folder.path().filename().string();
      Chunk& chunk = chunks[name];
      const fs::path target = partial / "train_pbr" / name;
      for (const char* kind : {"rgb", "depth", "mask", "mask_visib"}) {
        if (!fs::is_directory(folder.path() / kind)) continue;
        fs::create_directories(target / kind);
        for (const auto& picture : fs::directory_iterator(folder.path() / kind)) {
          PlaceFile(picture.path(), target / kind / picture.path().filename());
        }
      }
      for (const char* file : kBopFiles) {
        if (!fs::exists(folder.path() / file)) continue;
        Json& merged = chunk.bop[file];
        if (merged.is_null()) merged = Json::object();
        const Json entries = ReadJson(folder.path() / file);
        for (const auto& [key, value] : entries.items()) merged[key] = value;
      }
      if (fs::exists(folder.path() / "annotations.json")) {
        Json coco = ReadJson(folder.path() / "annotations.json");
        if (chunk.coco.is_null()) {
          chunk.coco = std::move(coco);
        } else {
          for (auto& image : coco["images"]) chunk.coco["images"].push_back(image);
          for (auto& a : coco["annotations"]) chunk.coco["annotations"].push_back(a);
        }
      }
      if (fs::exists(folder.path() / "scenes.jsonl"))
        chunk.scenes += ReadFileBytes(folder.path() / "scenes.jsonl");
    }
  }
  for (const auto& [name, chunk] : chunks) {
    const fs::path folder = partial / "train_pbr" / name;
    fs::create_directories(folder);
    for (const auto& [file, json] : chunk.bop)
      WriteFileAtomically(folder / file, FormatBopJson(json));
    if (!chunk.coco.is_null())
      WriteFileAtomically(folder / "annotations.json", FormatCocoJson(chunk.coco));
    WriteFileAtomically(folder / "scenes.jsonl", chunk.scenes);
  }
  if (!models.empty()) {
    fs::create_directories(partial / "models");
    Json info = Json::object();
    for (const auto& [obj_id, model] : models) {
      PlaceFile(model.first, partial / "models" / model.first.filename());
      info[std::to_string(obj_id)] = model.second;
    }
    WriteFileAtomically(partial / "models" / "models_info.json", FormatBopJson(info));
  }
  fs::create_directories(partial / "train_pbr");
  if (fs::exists(dir)) fs::remove(dir);  // empty, as checked
  fs::rename(partial, dir);
}

namespace {

// The categories of the first annotations.json under `root` (null when it has none).
Json FindCategories(const fs::path& root) {
  for (const auto& folder : fs::directory_iterator(root / "train_pbr")) {
    if (fs::exists(folder.path() / "annotations.json"))
      return ReadJson(folder.path() / "annotations.json")["categories"];
  }
  return nullptr;
}

}  // namespace

void AppendDataset(const std::string& dir, const std::string& addition) {
  const Json before = FindCategories(dir), added = FindCategories(addition);
  if (!before.is_null() && !added.is_null() && before != added) {
    throw std::runtime_error(fmt::format(
        "the scenes added to {} number their objects by other classes than its own (another "
        "program?); they are kept in {}",
        dir, addition));
  }
  const std::string merging = dir + ".merging";
  fs::remove_all(merging);
  try {
    MergeDatasets({dir, addition}, merging);
  } catch (const std::exception& error) {
    fs::remove_all(merging + ".partial");
    throw std::runtime_error(fmt::format("{}; {} is unchanged and the new images are in {}",
                                         error.what(), dir, addition));
  }
  // Pictures are hard links: the old tree's removal frees nothing the new one holds.
  const std::string old = dir + ".replaced";
  fs::remove_all(old);
  fs::rename(dir, old);
  fs::rename(merging, dir);
  fs::remove_all(old);
  fs::remove_all(addition);
}

}  // namespace prs::dataset
