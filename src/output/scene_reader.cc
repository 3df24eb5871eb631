// Reads spec §8 scene lines back into lang::Scene: the fields scene_json.cc writes, in the same
// order, so that writing a read scene gives its line again. Values become language values
// (numbers, booleans, strings, None, lists; a shape object its mesh or built-in shape).
#include "output/scene_reader.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "lang/program.h"
#include "output/scene_json.h"
#include "shapes/mesh_file.h"
#include "shapes/primitive.h"

namespace prs::output {
namespace {

using json = nlohmann::ordered_json;

// The writer nests values at most as deeply as the language's containers (1,000 levels).
constexpr int kMaxValueDepth = 1000;

[[noreturn]] void Fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where.empty() ? what : where + ": " + what);
}

const json& Field(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) Fail(where, fmt::format("no \"{}\"", key));
  return *it;
}

template <int N>
Eigen::Matrix<double, N, 1> ReadNumbers(const json& array, const char* key,
                                        const std::string& where) {
  if (!array.is_array() || array.size() != N)
    Fail(where, fmt::format("\"{}\" is not {} numbers", key, N));
  Eigen::Matrix<double, N, 1> numbers;
  for (int i = 0; i < N; ++i) {
    if (!array[i].is_number()) Fail(where, fmt::format("\"{}\" is not {} numbers", key, N));
    numbers[i] = array[i].get<double>();
  }
  return numbers;
}

lang::Value ToValue(const json& j, int depth, const std::string& where) {
  if (depth > kMaxValueDepth)
    Fail(where, fmt::format("a value nests more than {} levels", kMaxValueDepth));
  if (j.is_string()) return lang::MakeString(j.get<std::string>());
  if (j.is_boolean()) return lang::Value(j.get<bool>());
  if (j.is_number()) return lang::Value(j.get<double>());
  if (j.is_null()) return lang::Value();
  if (j.is_array()) {
    std::vector<lang::Value> elements;
    elements.reserve(j.size());
    for (const json& element : j) elements.push_back(ToValue(element, depth + 1, where));
    return lang::MakeList(std::move(elements));
  }
  return lang::MakeString(j.dump());  // an object the writer did not write: as text
}

// A shape property: {"primitive": KIND} or {"mesh": NAME, "path": PATH, "scale": S}; nullopt
// for anything else (then it stays a plain value and the object a box).
std::optional<lang::Value> ReadShape(const json& shape, const std::string& where,
                                     std::vector<std::string>* warnings) {
  if (!shape.is_object()) return std::nullopt;
  if (shape.size() == 1 && shape.contains("primitive") && shape["primitive"].is_string()) {
    if (auto kind = shapes::ParsePrimitive(shape["primitive"].get<std::string>())) {
      return lang::Value(lang::PrimitiveRef{*kind});
    }
    Fail(where, "its shape " + shape.dump() +
                    " is not a built-in shape (\"cylinder\", \"sphere\", "
                    "\"capsule\")");
  }
  const bool is_mesh = shape.contains("mesh") && shape["mesh"].is_string() &&
                       shape.contains("path") && shape["path"].is_string() &&
                       shape.contains("scale") && shape["scale"].is_number() &&
                       shape["scale"].get<double>() > 0;
  if (!is_mesh) return std::nullopt;
  std::string problem;
  const std::string path = shape["path"].get<std::string>();
  auto mesh = shapes::LoadRecordedMesh(shape["mesh"].get<std::string>(), path, problem);
  if (!mesh) {
    if (warnings)
      warnings->push_back(
          fmt::format("{}: its mesh file '{}' {}; it is a box here", where, path, problem));
    return std::nullopt;
  }
  return lang::Value(lang::MeshRef{std::move(mesh), shape["scale"].get<double>()});
}

}  // namespace

SceneReader::SceneReader() : classes_(std::make_shared<lang::CompiledProgram>()) {}

const lang::ClassInfo* SceneReader::FindOrMakeClass(const std::string& name) {
  if (auto it = by_name_.find(name); it != by_name_.end()) return it->second;
  auto info = std::make_unique<lang::ClassInfo>();
  info->name = name;
  info->has_orientation = true;
  info->has_box = true;
  const lang::ClassInfo* made = info.get();
  classes_->classes.push_back(std::move(info));
  by_name_.emplace(name, made);
  return made;
}

sampling::SampledScene SceneReader::Read(std::string_view line,
                                         std::vector<std::string>* warnings) {
  const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) Fail("", "not valid JSON");
  if (!j.is_object() || !j.contains("format") || j["format"] != "prs-scene/1") {
    Fail("", "not a scene: \"format\" is not \"prs-scene/1\"");
  }
  sampling::SampledScene sampled;
  const json& seed = Field(j, "seed", "the scene");
  const json& index = Field(j, "index", "the scene");
  if (!seed.is_number_unsigned() || !index.is_number_unsigned()) {
    Fail("the scene", "\"seed\" and \"index\" must be whole numbers from 0");
  }
  sampled.seed = seed.get<uint64_t>();
  sampled.index = index.get<uint64_t>();
  if (j.contains("attempts") && j["attempts"].is_number_integer()) {
    sampled.attempts = j["attempts"].get<int64_t>();
  }
  if (j.contains("rejections") && j["rejections"].is_object()) {
    for (const auto& [name, count] : j["rejections"].items()) {
      for (int k = 0; k <= int(lang::RejectionKind::kUnsettled); ++k) {
        const auto kind = lang::RejectionKind(k);
        if (name == lang::RejectionKindName(kind) && count.is_number_integer()) {
          sampled.rejections.by_kind[kind] = count.get<int64_t>();
          sampled.rejections.total += count.get<int64_t>();
        }
      }
    }
  }
  if (j.contains("settled_s") && j["settled_s"].is_number()) {
    sampled.scene.settled_s = j["settled_s"].get<double>();
  }
  if (j.contains("params") && j["params"].is_object()) {
    for (const auto& [name, value] : j["params"].items()) {
      sampled.scene.params.emplace_back(name, ToValue(value, 0, "param " + name));
    }
  }
  const json& objects = Field(j, "objects", "the scene");
  if (!objects.is_array()) Fail("", "\"objects\" is not an array");
  for (size_t i = 0; i < objects.size(); ++i) {
    sampled.scene.objects.push_back(ReadObject(objects[i], int(i), warnings));
  }
  return sampled;
}

lang::SceneObject SceneReader::ReadObject(const nlohmann::ordered_json& object, int index,
                                          std::vector<std::string>* warnings) {
  const std::string where = fmt::format("object {}", index);
  if (!object.is_object()) Fail(where, "is not a JSON object");
  lang::SceneObject o;
  const json& name = Field(object, "name", where);
  if (name.is_string()) o.name = name.get<std::string>();
  const json& cls = Field(object, "class", where);
  if (!cls.is_string()) Fail(where, "\"class\" is not a string");
  o.cls = FindOrMakeClass(cls.get<std::string>());
  o.p_WO = ReadNumbers<3>(Field(object, "position", where), "position", where);
  const json& orientation = Field(object, "orientation", where);
  if (!orientation.is_object()) Fail(where, "\"orientation\" is not an object");
  const Eigen::Vector4d q =
      ReadNumbers<4>(Field(orientation, "quaternion", where), "quaternion", where);
  if (!(q.norm() > 1e-9)) Fail(where, "its quaternion is zero");
  o.R_WO = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  o.dimensions = ReadNumbers<3>(Field(object, "dimensions", where), "dimensions", where);
  std::vector<lang::PropertyList::Entry>& properties = o.properties.Mutable();
  properties.emplace_back("position", lang::Value(o.p_WO));
  properties.emplace_back("orientation", lang::Value(lang::Orientation{o.R_WO}));
  properties.emplace_back("width", lang::Value(o.dimensions.x()));
  properties.emplace_back("length", lang::Value(o.dimensions.y()));
  properties.emplace_back("height", lang::Value(o.dimensions.z()));
  if (object.contains("properties")) {
    const json& entries = object["properties"];
    if (!entries.is_object()) Fail(where, "\"properties\" is not an object");
    for (const auto& [key, value] : entries.items()) {
      if (IsCoreProperty(key)) continue;  // the writer never puts them here
      std::optional<lang::Value> shape;
      if (key == "shape") shape = ReadShape(value, where, warnings);
      properties.emplace_back(key, shape ? *std::move(shape) : ToValue(value, 0, where));
      if (key == "allowCollisions") o.allow_collisions = value.is_boolean() && value.get<bool>();
    }
  }
  SetShape(o);
  return o;
}

// The object's mesh and primitive from its shape property, as the interpreter sets them.
void SceneReader::SetShape(lang::SceneObject& o) {
  const lang::Value* shape = o.FindProperty("shape");
  if (!shape) return;
  if (const auto* mesh = std::get_if<lang::MeshRef>(&shape->data)) {
    o.mesh = mesh->mesh;
    o.mesh_scale = mesh->scale;
  } else if (const auto* primitive = std::get_if<lang::PrimitiveRef>(&shape->data)) {
    o.primitive = primitive->kind;
    if (o.dimensions.minCoeff() > 0)
      o.mesh = shapes::MakePrimitiveShape(primitive->kind, o.dimensions);
  }
}

}  // namespace prs::output
