// Writes scenes as spec §8 JSON with nlohmann-json: objects in creation order, quaternions
// (w, x, y, z) mapping local to world, yaw/pitch/roll, dimensions, and the other properties.
#include "output/scene_json.h"

#include <nlohmann/json.hpp>

#include "geometry/rotation.h"

namespace prs::output {
namespace {

using nlohmann::json;

json ValueToJson(const lang::Value& v) {
  if (const auto* x = std::get_if<double>(&v.data)) return *x;
  if (const auto* b = std::get_if<bool>(&v.data)) return *b;
  if (const auto* s = std::get_if<lang::StringPtr>(&v.data)) return **s;
  if (const auto* p = std::get_if<Eigen::Vector3d>(&v.data)) return {p->x(), p->y(), p->z()};
  if (v.Is<lang::NoneValue>()) return nullptr;
  auto elements = [](const std::vector<lang::Value>& items) {
    json array = json::array();
    for (const lang::Value& item : items) array.push_back(ValueToJson(item));
    return array;
  };
  if (const auto* t = std::get_if<std::shared_ptr<lang::TupleData>>(&v.data)) return elements((*t)->elements);
  if (const auto* l = std::get_if<std::shared_ptr<lang::ListData>>(&v.data)) return elements((*l)->elements);
  return lang::Repr(v);
}

bool IsCoreProperty(const std::string& name) {
  return name == "position" || name == "orientation" || name == "width" || name == "length" ||
         name == "height" || name == "yaw" || name == "pitch" || name == "roll";
}

json ObjectToJson(const lang::SceneObject& o) {
  const Eigen::Quaterniond q = geometry::CanonicalQuaternion(o.R_WO.toRotationMatrix());
  const Eigen::Vector3d ypr = geometry::CalcYawPitchRoll(o.R_WO.toRotationMatrix());
  json properties = json::object();
  for (const auto& [name, value] : o.properties) {
    if (!IsCoreProperty(name)) properties[name] = ValueToJson(value);
  }
  return {{"name", o.name ? json(*o.name) : json(nullptr)},
          {"class", o.cls->name},
          {"position", {o.p_WO.x(), o.p_WO.y(), o.p_WO.z()}},
          {"orientation",
           {{"quaternion", {q.w(), q.x(), q.y(), q.z()}}, {"yaw_pitch_roll", {ypr.x(), ypr.y(), ypr.z()}}}},
          {"dimensions", {o.dimensions.x(), o.dimensions.y(), o.dimensions.z()}},
          {"properties", properties}};
}

}  // namespace

std::string FormatSceneJson(const sampling::SampledScene& sampled) {
  json rejections = json::object();
  for (const auto& [kind, n] : sampled.rejections.by_kind) rejections[lang::RejectionKindName(kind)] = n;
  json params = json::object();
  for (const auto& [name, value] : sampled.scene.params) params[name] = ValueToJson(value);
  json objects = json::array();
  for (const lang::SceneObject& o : sampled.scene.objects) objects.push_back(ObjectToJson(o));
  json scene = {{"format", "prs-scene/1"}, {"seed", sampled.seed},      {"index", sampled.index},
                {"attempts", sampled.attempts}, {"rejections", rejections}, {"params", params},
                {"objects", objects}};
  return scene.dump();
}

}  // namespace prs::output
