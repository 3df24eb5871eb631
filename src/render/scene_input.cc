// Scenes to RenderScene: from the sampler's lang::Scene or from a JSON line, through one
// classification of shapes (box, cylinder, mesh, point, camera) and one colour parser.
#include "render/scene_input.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "lang/program.h"
#include "export/color.h"
#include "shapes/mesh_file.h"

namespace prs::render {
namespace {

bool ContainsWord(std::string text, const char* word) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text.find(word) != std::string::npos;
}

bool ContainsCamera(const std::string& text) { return ContainsWord(text, "camera"); }

// The properties that decide how an object is drawn, as text from either source.
struct DrawProperties {
  std::string model_name;
  std::string shape_type;
  std::string primitive;  // a built-in shape's name ("cylinder", "sphere", "capsule")
  std::optional<Rgba> color;
  std::string color_text;  // what the scene said, for the unknown-colour note
  std::optional<double> fovy_deg, aspect;  // a camera's view, when given as numbers
  std::optional<double> near_m, far_m;     // and the depths it sees
  // A light's (LightProperties), when given as numbers and booleans.
  std::optional<double> intensity, cutoff_deg;
  std::optional<bool> directional, castshadow;
};

ObjectShape ClassifyShape(const RenderObject& object, const DrawProperties& properties) {
  if (ContainsWord(object.class_name, "light")) return ObjectShape::kLight;
  if (ContainsCamera(object.class_name) || ContainsCamera(properties.model_name))
    return ObjectShape::kCamera;
  if (object.dimensions.isZero()) return ObjectShape::kPoint;
  if (properties.primitive == "sphere") return ObjectShape::kSphere;
  if (properties.primitive == "capsule") return ObjectShape::kCapsule;
  if (properties.primitive == "cylinder") return ObjectShape::kCylinder;
  if (object.mesh) return ObjectShape::kMesh;
  if (properties.shape_type == "cylinder") return ObjectShape::kCylinder;
  return ObjectShape::kBox;
}

void ApplyProperties(const DrawProperties& properties, RenderObject& object,
                     std::vector<std::string>* unknown_colors) {
  object.shape = ClassifyShape(object, properties);
  if (object.shape == ObjectShape::kCamera) object.color = {0.18f, 0.18f, 0.2f, 1.0f};
  if (object.shape == ObjectShape::kLight) {
    object.color = {1, 1, 1, 1};
    LightProperties& light = object.light;
    if (properties.intensity && *properties.intensity >= 0 && std::isfinite(*properties.intensity))
      light.intensity = *properties.intensity;
    if (properties.cutoff_deg && *properties.cutoff_deg > 0 && *properties.cutoff_deg <= 90)
      light.cutoff_deg = *properties.cutoff_deg;
    if (properties.directional) light.directional = *properties.directional;
    if (properties.castshadow) light.castshadow = *properties.castshadow;
  }
  if (properties.color) {
    object.color = *properties.color;
  } else if (!properties.color_text.empty() && unknown_colors) {
    unknown_colors->push_back(properties.color_text);
  }
  // Values a program could not have compiled with (prs export warns of them) keep the defaults.
  if (properties.fovy_deg && *properties.fovy_deg > 0 && *properties.fovy_deg < 180)
    object.fovy_deg = *properties.fovy_deg;
  if (properties.aspect && *properties.aspect > 0 && std::isfinite(*properties.aspect))
    object.aspect = *properties.aspect;
  else
    object.missing_view_properties.push_back("aspect");
  if (!(properties.fovy_deg && *properties.fovy_deg > 0 && *properties.fovy_deg < 180))
    object.missing_view_properties.insert(object.missing_view_properties.begin(), "fovy_deg");
  const bool depths = properties.near_m && properties.far_m && *properties.near_m > 0 &&
                      *properties.far_m > *properties.near_m && std::isfinite(*properties.far_m);
  if (depths) {
    object.near_m = *properties.near_m;
    object.far_m = *properties.far_m;
  } else {
    if (!(properties.near_m && *properties.near_m > 0)) object.missing_view_properties.push_back("near");
    if (!(properties.far_m && std::isfinite(*properties.far_m) &&
          *properties.far_m > properties.near_m.value_or(0)))
      object.missing_view_properties.push_back("far");
  }
}

std::optional<Rgba> ToRenderColor(const std::optional<exporting::Rgba>& c) {
  if (!c) return std::nullopt;
  return Rgba{float(c->r), float(c->g), float(c->b), float(c->a)};
}

// A `color` value of the language, read by the export rules' parser (one parser for both).
std::optional<Rgba> ParseColorValue(const lang::Value& value) {
  return ToRenderColor(exporting::ParseColor(value));
}

DrawProperties ReadDrawProperties(const lang::SceneObject& source) {
  DrawProperties properties;
  if (source.primitive) properties.primitive = shapes::PrimitiveName(*source.primitive);
  for (const auto& [name, value] : source.properties) {
    const bool is_string = value.Is<lang::StringPtr>();
    if (name == "model_name" && is_string) properties.model_name = *value.As<lang::StringPtr>();
    if (name == "shape_type" && is_string) properties.shape_type = *value.As<lang::StringPtr>();
    if (name == "color") {
      properties.color = ParseColorValue(value);
      properties.color_text = lang::Repr(value);
    }
    if (name == "fovy_deg" && value.Is<double>()) properties.fovy_deg = value.As<double>();
    if (name == "aspect" && value.Is<double>()) properties.aspect = value.As<double>();
    if (name == "near" && value.Is<double>()) properties.near_m = value.As<double>();
    if (name == "intensity" && value.Is<double>()) properties.intensity = value.As<double>();
    if (name == "cutoff_deg" && value.Is<double>()) properties.cutoff_deg = value.As<double>();
    if (name == "directional" && value.Is<bool>()) properties.directional = value.As<bool>();
    if (name == "castshadow" && value.Is<bool>()) properties.castshadow = value.As<bool>();
    if (name == "far" && value.Is<double>()) properties.far_m = value.As<double>();
  }
  return properties;
}

[[noreturn]] void FailJson(size_t object_index, const std::string& what) {
  throw std::invalid_argument("object " + std::to_string(object_index) + ": " + what);
}

Eigen::Vector3d ReadVector3(const nlohmann::json& object, const char* key, size_t index) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_array() || it->size() != 3)
    FailJson(index, std::string("'") + key + "' is not an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!(*it)[i].is_number()) FailJson(index, std::string("'") + key + "' holds a non-number");
    v[i] = (*it)[i].get<double>();
  }
  return v;
}

// object[key] by reference, or an empty object when it is missing. json::value() would copy
// the member, recursively, and a scenes file may nest a member arbitrarily deep.
const nlohmann::json& MemberOrEmpty(const nlohmann::json& object, const char* key) {
  static const nlohmann::json kEmpty = nlohmann::json::object();
  const auto it = object.find(key);
  return it == object.end() ? kEmpty : *it;
}

Eigen::Quaterniond ReadQuaternion(const nlohmann::json& object, size_t index) {
  const nlohmann::json& orientation = MemberOrEmpty(object, "orientation");
  if (!orientation.is_object())
    FailJson(index, "'orientation.quaternion' is not an array of 4 numbers [w, x, y, z]");
  const auto it = orientation.find("quaternion");
  if (it == orientation.end() || !it->is_array() || it->size() != 4 ||
      !std::all_of(it->begin(), it->end(), [](const auto& x) { return x.is_number(); }))
    FailJson(index, "'orientation.quaternion' is not an array of 4 numbers [w, x, y, z]");
  Eigen::Quaterniond q((*it)[0].get<double>(), (*it)[1].get<double>(), (*it)[2].get<double>(),
                       (*it)[3].get<double>());
  if (q.norm() < 1e-9) FailJson(index, "'orientation.quaternion' is zero");
  return q.normalized();
}

std::optional<Rgba> ParseColorJson(const nlohmann::json& color) {
  if (color.is_string()) return ToRenderColor(exporting::ParseColorText(color.get<std::string>()));
  if (color.is_number()) return ToRenderColor(exporting::ParseColorNumbers({color.get<double>()}));
  if (!color.is_array()) return std::nullopt;
  std::vector<double> numbers;
  for (const auto& x : color) {
    if (!x.is_number()) return std::nullopt;
    numbers.push_back(x.get<double>());
  }
  return ToRenderColor(exporting::ParseColorNumbers(numbers));
}

DrawProperties ReadDrawProperties(const nlohmann::json& object) {
  DrawProperties properties;
  const nlohmann::json& json = MemberOrEmpty(object, "properties");
  if (!json.is_object()) return properties;
  if (json.contains("model_name") && json["model_name"].is_string())
    properties.model_name = json["model_name"].get<std::string>();
  if (json.contains("shape_type") && json["shape_type"].is_string())
    properties.shape_type = json["shape_type"].get<std::string>();
  if (json.contains("shape") && json["shape"].is_object() && json["shape"].contains("primitive") &&
      json["shape"]["primitive"].is_string())
    properties.primitive = json["shape"]["primitive"].get<std::string>();
  if (json.contains("fovy_deg") && json["fovy_deg"].is_number())
    properties.fovy_deg = json["fovy_deg"].get<double>();
  if (json.contains("aspect") && json["aspect"].is_number())
    properties.aspect = json["aspect"].get<double>();
  if (json.contains("near") && json["near"].is_number()) properties.near_m = json["near"].get<double>();
  if (json.contains("intensity") && json["intensity"].is_number())
    properties.intensity = json["intensity"].get<double>();
  if (json.contains("cutoff_deg") && json["cutoff_deg"].is_number())
    properties.cutoff_deg = json["cutoff_deg"].get<double>();
  if (json.contains("directional") && json["directional"].is_boolean())
    properties.directional = json["directional"].get<bool>();
  if (json.contains("castshadow") && json["castshadow"].is_boolean())
    properties.castshadow = json["castshadow"].get<bool>();
  if (json.contains("far") && json["far"].is_number()) properties.far_m = json["far"].get<double>();
  if (json.contains("color")) {
    properties.color = ParseColorJson(json["color"]);
    // For the "unknown color" note; a nested value is not dumped (it may be arbitrarily deep).
    const nlohmann::json& color = json["color"];
    const bool flat = !color.is_structured() ||
                      std::none_of(color.begin(), color.end(),
                                   [](const nlohmann::json& e) { return e.is_structured(); });
    properties.color_text = flat ? color.dump() : "a nested value";
  }
  return properties;
}

// A mesh shape as `prs sample` writes it ({"mesh": NAME, "path": PATH, "scale": S}), read from
// PATH; when the file cannot be read here the object is drawn as its box.
void ReadMesh(const nlohmann::json& shape, RenderObject& object) {
  if (!shape.is_object()) return;
  const auto mesh = shape.find("mesh"), path = shape.find("path"), scale = shape.find("scale");
  if (mesh == shape.end() || path == shape.end() || scale == shape.end() || !mesh->is_string() ||
      !path->is_string() || !scale->is_number() || !(scale->get<double>() > 0))
    return;
  std::string problem;
  object.mesh = shapes::LoadRecordedMesh(mesh->get<std::string>(), path->get<std::string>(), problem);
  object.mesh_scale = scale->get<double>();
}

RenderObject ReadJsonObject(const nlohmann::json& json, size_t index,
                            std::vector<std::string>* unknown_colors) {
  if (!json.is_object()) FailJson(index, "is not a JSON object");
  RenderObject object;
  const nlohmann::json& class_name = MemberOrEmpty(json, "class");
  object.class_name = class_name.is_string() ? class_name.get<std::string>() : "Object";
  const auto name = json.find("name");
  object.name = name != json.end() && name->is_string()
                    ? name->get<std::string>()
                    : object.class_name + "#" + std::to_string(index);
  object.p_WO = ReadVector3(json, "position", index);
  object.R_WO = ReadQuaternion(json, index);
  object.dimensions = ReadVector3(json, "dimensions", index);
  ReadMesh(MemberOrEmpty(MemberOrEmpty(json, "properties"), "shape"), object);
  ApplyProperties(ReadDrawProperties(json), object, unknown_colors);
  return object;
}

}  // namespace

RenderScene MakeRenderScene(const lang::Scene& scene, std::vector<std::string>* unknown_colors) {
  RenderScene result;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const lang::SceneObject& source = scene.objects[i];
    RenderObject object;
    object.name = source.DisplayName(static_cast<int>(i));
    object.class_name = source.cls ? source.cls->name : "Object";
    object.p_WO = source.p_WO;
    object.R_WO = source.R_WO.normalized();
    object.dimensions = source.dimensions;
    if (!source.primitive) {  // a built-in shape is drawn by MuJoCo's own geoms, not its polytope
      object.mesh = source.mesh;
      object.mesh_scale = source.mesh_scale;
    }
    ApplyProperties(ReadDrawProperties(source), object, unknown_colors);
    result.objects.push_back(std::move(object));
  }
  if (scene.workspace) result.workspace_edges = CalcOutlineEdges(*scene.workspace);
  for (const lang::PlacedRegion& region : scene.regions) {
    RegionOutline outline{region.what, region.what.starts_with("view"), {}};
    for (const geometry::ConvexRegion& piece : region.pieces_W) {
      for (const Segment& edge : CalcOutlineEdges(piece)) outline.edges.push_back(edge);
    }
    result.regions.push_back(std::move(outline));
  }
  return result;
}

RenderScene ParseRenderSceneJson(std::string_view line, std::vector<std::string>* unknown_colors) {
  const nlohmann::json json = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) throw std::invalid_argument("not valid JSON");
  if (!json.is_object() || MemberOrEmpty(json, "format") != "prs-scene/1")
    throw std::invalid_argument("not a prs-scene/1 object (no \"format\": \"prs-scene/1\")");
  const auto objects = json.find("objects");
  if (objects == json.end() || !objects->is_array())
    throw std::invalid_argument("'objects' is not an array");
  RenderScene scene;
  for (size_t i = 0; i < objects->size(); ++i)
    scene.objects.push_back(ReadJsonObject((*objects)[i], i, unknown_colors));
  return scene;
}

}  // namespace prs::render
