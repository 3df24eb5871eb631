// Exact comparison of object properties across sampled scenes, site by site.
#include "analysis/property_variation.h"

#include <fmt/format.h>

#include <algorithm>

#include "lang/value.h"

namespace prs::analysis {
namespace {

std::string FormatExactNumbers(std::initializer_list<double> numbers) {
  std::string text = "(";
  for (double x : numbers) text += fmt::format("{}{:.17g}", text.size() > 1 ? ", " : "", x);
  return text + ")";
}

std::string FormatExactElements(const std::vector<lang::Value>& elements) {
  std::string text = "(";
  for (const lang::Value& e : elements) text += FormatExactValue(e) + ", ";
  return text + ")";
}

void NoteVaried(const std::string& property, SiteVariation& variation) {
  auto& varied = variation.varied;
  if (std::find(varied.begin(), varied.end(), property) == varied.end()) varied.push_back(property);
}

}  // namespace

std::string FormatExactValue(const lang::Value& value) {
  const auto& data = value.data;
  if (const auto* x = std::get_if<double>(&data)) return fmt::format("{:.17g}", *x);
  if (const auto* p = std::get_if<Eigen::Vector3d>(&data)) {
    return FormatExactNumbers({p->x(), p->y(), p->z()});
  }
  if (const auto* o = std::get_if<lang::Orientation>(&data)) {
    return FormatExactNumbers({o->R_WF.w(), o->R_WF.x(), o->R_WF.y(), o->R_WF.z()});
  }
  if (const auto* op = std::get_if<lang::OrientedPoint>(&data)) {
    return FormatExactNumbers({op->p_W.x(), op->p_W.y(), op->p_W.z(), op->R_WF.w(), op->R_WF.x(),
                               op->R_WF.y(), op->R_WF.z()});
  }
  if (const auto* ref = std::get_if<lang::ObjectRef>(&data)) {
    return "object " + std::to_string(ref->index);
  }
  if (const auto* t = std::get_if<std::shared_ptr<lang::TupleData>>(&data)) {
    return FormatExactElements((*t)->elements);
  }
  if (const auto* l = std::get_if<std::shared_ptr<lang::ListData>>(&data)) {
    return "list " + FormatExactElements((*l)->elements);
  }
  return lang::Repr(value);  // strings, booleans, None, classes; regions by their description
}

void VariationObserver::Observe(const lang::Scene& scene) {
  std::map<SiteKey, std::vector<const lang::SceneObject*>> by_site;
  for (const lang::SceneObject& o : scene.objects)
    by_site[{o.span.file, o.span.begin}].push_back(&o);
  for (const auto& [key, objects] : by_site) {
    SiteVariation& variation = sites_[key];
    const auto n = static_cast<int64_t>(objects.size());
    variation.min_objects = variation.scenes_present == 0 ? n : std::min(variation.min_objects, n);
    variation.max_objects = std::max(variation.max_objects, n);
    ++variation.scenes_present;
    for (size_t k = 0; k < objects.size(); ++k) {
      CompareObject(*objects[k], k, baselines_[key], variation);
    }
  }
  ++scenes_;
}

void VariationObserver::CompareObject(const lang::SceneObject& object, size_t k, Baseline& baseline,
                                      SiteVariation& variation) {
  PropertyValues values;
  for (const auto& [name, value] : object.properties)
    values.emplace_back(name, FormatExactValue(value));
  if (k >= baseline.objects.size()) {  // the first scene with a k-th object from this site
    baseline.objects.push_back(std::move(values));
    return;
  }
  const PropertyValues& first = baseline.objects[k];
  for (const auto& property : values) {
    if (std::find(first.begin(), first.end(), property) == first.end()) {
      NoteVaried(property.first, variation);
    }
  }
  for (const auto& property : first) {
    auto same_name = [&](const auto& p) { return p.first == property.first; };
    if (std::none_of(values.begin(), values.end(), same_name))
      NoteVaried(property.first, variation);
  }
}

}  // namespace prs::analysis
