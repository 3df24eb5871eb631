// Small helpers over runtime values: constructors for shared containers, type names for
// messages, and a short printable form.
#include "lang/value.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lang/program.h"

namespace prs::lang {

Value MakeString(std::string s) { return StringPtr(std::make_shared<const std::string>(std::move(s))); }

namespace {

int CalcElementsDepth(const std::vector<Value>& elements) {
  int deepest = 0;
  for (const Value& e : elements) deepest = std::max(deepest, CalcContainerDepth(e));
  return deepest + 1;
}

}  // namespace

int CalcContainerDepth(const Value& v) {
  if (const auto* t = std::get_if<std::shared_ptr<TupleData>>(&v.data)) return (*t)->depth;
  if (const auto* l = std::get_if<std::shared_ptr<ListData>>(&v.data)) return (*l)->depth;
  if (const auto* d = std::get_if<std::shared_ptr<DictData>>(&v.data)) return (*d)->depth;
  return 0;
}

Value MakeTuple(std::vector<Value> elements) {
  auto tuple = std::make_shared<TupleData>();
  tuple->depth = CalcElementsDepth(elements);
  tuple->elements = std::move(elements);
  return tuple;
}

Value MakeList(std::vector<Value> elements) {
  auto list = std::make_shared<ListData>();
  list->depth = CalcElementsDepth(elements);
  list->elements = std::move(elements);
  return list;
}

std::string TypeName(const Value& v) {
  static const char* const kNames[] = {
      "None",   "boolean", "number",   "string",   "vector",   "oriented point",
      "orientation", "object", "region", "class", "function", "built-in function",
      "module", "method",  "tuple",    "list",     "dict", "mesh", "shape"};
  static_assert(std::variant_size_v<decltype(v.data)> == std::size(kNames));
  return kNames[v.data.index()];
}

std::string FormatNumber(double x) {
  if (std::isfinite(x) && x == std::trunc(x) && std::fabs(x) < 1e15) {
    return std::to_string(static_cast<long long>(x));
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

namespace {

std::string JoinRepr(const std::vector<Value>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + Repr(items[i]);
  return out;
}
}  // namespace

std::string Repr(const Value& v) {
  if (v.Is<NoneValue>()) return "None";
  if (const auto* b = std::get_if<bool>(&v.data)) return *b ? "True" : "False";
  if (const auto* x = std::get_if<double>(&v.data)) return FormatNumber(*x);
  if (const auto* s = std::get_if<StringPtr>(&v.data)) return "'" + **s + "'";
  if (const auto* p = std::get_if<Eigen::Vector3d>(&v.data)) {
    // Appending to a named string (not "(" + temporary) also avoids a GCC 12 -Wrestrict
    // false positive.
    std::string text = "(";
    text += FormatNumber(p->x()) + ", " + FormatNumber(p->y()) + ", " + FormatNumber(p->z()) + ")";
    return text;
  }
  if (const auto* t = std::get_if<std::shared_ptr<TupleData>>(&v.data)) {
    std::string text = "(";
    text += JoinRepr((*t)->elements) + ((*t)->elements.size() == 1 ? ",)" : ")");
    return text;
  }
  if (const auto* l = std::get_if<std::shared_ptr<ListData>>(&v.data)) {
    std::string text = "[";  // as above: a named string avoids GCC 12's -Wrestrict
    text += JoinRepr((*l)->elements) + "]";
    return text;
  }
  if (const auto* c = std::get_if<const ClassInfo*>(&v.data)) return "class " + (*c)->name;
  if (const auto* r = std::get_if<RegionPtr>(&v.data)) return (*r)->Describe();
  if (const auto* m = std::get_if<MeshRef>(&v.data)) {
    return "Mesh('" + m->mesh->name + "'" + (m->scale == 1 ? "" : ", scale=" + FormatNumber(m->scale)) + ")";
  }
  if (const auto* p = std::get_if<PrimitiveRef>(&v.data)) {
    const char* names[] = {"Cylinder()", "Sphere()", "Capsule()"};
    return names[static_cast<int>(p->kind)];
  }
  return TypeName(v);
}

const PropertyDefault* ClassInfo::FindDefault(const std::string& property) const {
  for (const PropertyDefault& d : defaults) {
    if (d.name == property) return &d;
  }
  return nullptr;
}

bool ClassInfo::IsSubclassOf(const ClassInfo* other) const {
  for (const ClassInfo* c = this; c; c = c->parent) {
    if (c == other) return true;
  }
  return false;
}

}  // namespace prs::lang
