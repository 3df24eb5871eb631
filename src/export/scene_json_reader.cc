// Reads scenes back from spec §8 JSON Lines, so that `prs export` can take a scenes file written
// by `prs sample` as well as a scenario. Properties become language values and go through the
// same rules as a sampled scene's.
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "export/body_rules.h"
#include "export/export.h"
#include "shapes/mesh_file.h"

namespace prs::exporting {
namespace {

using nlohmann::json;

// Scene JSON from `prs sample` nests values as deeply as the language allows its containers
// (1,000 levels); deeper input is refused before the recursive conversion and dump below.
constexpr int kMaxValueDepth = 1000;

// True when `j` nests arrays or objects more than `limit` levels deep (recursion bounded by
// `limit`).
bool IsNestedDeeper(const json& j, int limit) {
  if (!j.is_structured()) return false;
  if (limit == 0) return true;
  for (const json& element : j) {
    if (IsNestedDeeper(element, limit - 1)) return true;
  }
  return false;
}

lang::Value ToValue(const json& j) {
  if (j.is_string()) return lang::MakeString(j.get<std::string>());
  if (j.is_boolean()) return lang::Value(j.get<bool>());
  if (j.is_number()) return lang::Value(j.get<double>());
  if (j.is_array()) {
    std::vector<lang::Value> elements;
    for (const json& element : j) elements.push_back(ToValue(element));
    return lang::MakeList(std::move(elements));
  }
  if (j.is_null()) return lang::Value();
  return lang::MakeString(j.dump());
}

const json& Field(const json& object, const char* key, const std::string& where) {
  if (!object.is_object() || !object.contains(key))
    throw std::invalid_argument(fmt::format("{} has no \"{}\"", where, key));
  return object.at(key);
}

template <int N>
Eigen::Matrix<double, N, 1> ReadNumbers(const json& object, const char* key,
                                        const std::string& where) {
  const json& array = Field(object, key, where);
  if (!array.is_array() || array.size() != N)
    throw std::invalid_argument(fmt::format("{}: \"{}\" is not {} numbers", where, key, N));
  Eigen::Matrix<double, N, 1> numbers;
  for (int i = 0; i < N; ++i) {
    if (!array[i].is_number())
      throw std::invalid_argument(fmt::format("{}: \"{}\" is not {} numbers", where, key, N));
    numbers[i] = array[i].get<double>();
  }
  return numbers;
}

internal::Properties ReadProperties(const json& object, const std::string& where) {
  internal::Properties properties;
  if (!object.contains("properties")) return properties;
  const json& entries = object.at("properties");
  if (!entries.is_object())
    throw std::invalid_argument(where + ": \"properties\" is not an object");
  for (const auto& [key, value] : entries.items()) {
    if (IsNestedDeeper(value, kMaxValueDepth)) {
      throw std::invalid_argument(fmt::format("{}: property \"{}\" is nested more than {} levels deep",
                                              where, key, kMaxValueDepth));
    }
    properties.emplace_back(key, ToValue(value));
  }
  return properties;
}

// A mesh shape as `prs sample` writes it ({"mesh": NAME, "path": PATH, "scale": S}), read from
// PATH so that exports carry the mesh; nullptr with a warning when the file cannot be used, and
// the object goes out as its bounding box.
std::shared_ptr<const shapes::MeshShape> LoadMeshOfShape(const json& shape, const std::string& where,
                                                         std::vector<std::string>& warnings) {
  const std::string path = shape.at("path").get<std::string>();
  std::string problem;
  if (auto mesh = shapes::LoadRecordedMesh(shape.at("mesh").get<std::string>(), path, problem)) return mesh;
  warnings.push_back(fmt::format("{}: its mesh file '{}' {}; exported as its bounding box", where,
                                 path, problem));
  return nullptr;
}

Body ReadBody(const json& object, int index, internal::NameTable& names,
              std::vector<std::string>& warnings) {
  const std::string where = fmt::format("object {}", index);
  const json& name = Field(object, "name", where);
  const json& cls = Field(object, "class", where);
  if (!cls.is_string()) throw std::invalid_argument(where + ": \"class\" is not a string");
  internal::ObjectFacts facts;
  facts.name = name.is_string() ? name.get<std::string>() : "";
  facts.class_name = cls.get<std::string>();
  facts.index = index;
  facts.p_WO = ReadNumbers<3>(object, "position", where);
  const Eigen::Vector4d q =
      ReadNumbers<4>(Field(object, "orientation", where), "quaternion", where + " orientation");
  if (q.norm() < 1e-9) throw std::invalid_argument(where + ": the quaternion is zero");
  facts.R_WO = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  facts.dimensions = ReadNumbers<3>(object, "dimensions", where);
  facts.properties = ReadProperties(object, where);  // checks their depth before any copy
  for (auto& [key, value] : facts.properties) {
    if (key == "allowCollisions") facts.allow_collisions = value.Is<bool>() && value.As<bool>();
    if (key != "shape") continue;
    const json& shape = object.at("properties").at("shape");
    if (shape.is_object() && shape.size() == 1 && shape.contains("primitive") && shape["primitive"].is_string()) {
      if (auto kind = shapes::ParsePrimitive(shape["primitive"].get<std::string>())) {
        value = lang::PrimitiveRef{*kind};
      } else {
        warnings.push_back(fmt::format("{}: its shape {} is not a built-in shape (\"cylinder\", "
                                       "\"sphere\", \"capsule\"); exported as its box",
                                       where, shape.dump()));
      }
      continue;
    }
    const bool is_mesh = shape.is_object() && shape.contains("mesh") && shape["mesh"].is_string() &&
                         shape.contains("path") && shape["path"].is_string() &&
                         shape.contains("scale") && shape["scale"].is_number() &&
                         shape["scale"].get<double>() > 0;
    if (!is_mesh) continue;
    if (auto mesh = LoadMeshOfShape(shape, where, warnings)) {
      value = lang::MeshRef{std::move(mesh), shape["scale"].get<double>()};
    }
  }
  return internal::MakeBody(facts, names, warnings);
}

}  // namespace

ExportScene ReadSceneJson(std::string_view line) {
  const json scene = json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (scene.is_discarded()) throw std::invalid_argument("not valid JSON");
  if (!scene.is_object() || !scene.contains("format") || scene["format"] != "prs-scene/1")
    throw std::invalid_argument("not a scene: \"format\" is not \"prs-scene/1\"");
  const json& objects = Field(scene, "objects", "the scene");
  if (!objects.is_array()) throw std::invalid_argument("\"objects\" is not an array");
  ExportScene out;
  // By reference: json::value() would copy the member, recursively, however deep it is.
  static const json kMissing;
  const auto seed_it = scene.find("seed"), index_it = scene.find("index");
  const json& seed = seed_it == scene.end() ? kMissing : *seed_it;
  const json& index = index_it == scene.end() ? kMissing : *index_it;
  auto number_text = [](const json& j) { return j.is_number() ? j.dump() : std::string("?"); };
  out.title = fmt::format("seed {} index {}", number_text(seed), number_text(index));
  if (seed.is_number_unsigned()) out.seed = seed.get<uint64_t>();
  if (index.is_number_unsigned()) out.index = index.get<uint64_t>();
  out.settled = scene.contains("settled_s");
  internal::NameTable names;
  for (size_t i = 0; i < objects.size(); ++i)
    out.bodies.push_back(ReadBody(objects[i], int(i), names, out.warnings));
  return out;
}

}  // namespace prs::exporting
