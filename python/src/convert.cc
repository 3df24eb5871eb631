// Conversions between the engine's plain data and Python objects, and the located errors.
#include <pybind11/stl.h>

#include "bindings.h"
#include "geometry/rotation.h"

namespace prs::python {
namespace {

py::tuple ToTuple(const std::vector<lang::Value>& elements) {
  py::tuple tuple(elements.size());
  for (size_t i = 0; i < elements.size(); ++i) tuple[i] = ToPython(elements[i]);
  return tuple;
}

py::list ToList(const std::vector<lang::Value>& elements) {
  py::list list(elements.size());
  for (size_t i = 0; i < elements.size(); ++i) list[i] = ToPython(elements[i]);
  return list;
}

}  // namespace

py::array_t<double> MakeArray(std::initializer_list<double> numbers) {
  py::array_t<double> array(static_cast<py::ssize_t>(numbers.size()));
  std::copy(numbers.begin(), numbers.end(), array.mutable_data());
  return array;
}

py::object ToPython(const lang::Value& value) {
  const auto& data = value.data;
  if (value.Is<lang::NoneValue>()) return py::none();
  if (const auto* b = std::get_if<bool>(&data)) return py::bool_(*b);
  if (const auto* x = std::get_if<double>(&data)) return py::float_(*x);
  if (const auto* s = std::get_if<lang::StringPtr>(&data)) return py::str(**s);
  if (const auto* p = std::get_if<Eigen::Vector3d>(&data)) {
    return MakeArray({p->x(), p->y(), p->z()});
  }
  if (const auto* t = std::get_if<std::shared_ptr<lang::TupleData>>(&data)) {
    return ToTuple((*t)->elements);
  }
  if (const auto* l = std::get_if<std::shared_ptr<lang::ListData>>(&data)) {
    return ToList((*l)->elements);
  }
  if (const auto* d = std::get_if<std::shared_ptr<lang::DictData>>(&data)) {
    py::dict dict;
    for (const auto& [key, item] : (*d)->entries) {
      py::object py_key = ToPython(key);
      // Vectors are numpy arrays, which cannot be keys; use the language's description.
      if (!py::isinstance<py::str>(py_key) && !py::isinstance<py::float_>(py_key) &&
          !py::isinstance<py::bool_>(py_key) && !py_key.is_none()) {
        py_key = py::str(lang::Repr(key));
      }
      dict[py_key] = ToPython(item);
    }
    return dict;
  }
  if (const auto* m = std::get_if<lang::MeshRef>(&data)) {  // as the scene JSON writes it
    py::dict dict;
    dict["mesh"] = m->mesh->name;
    dict["path"] = m->mesh->path;
    dict["scale"] = m->scale;
    return dict;
  }
  if (const auto* p = std::get_if<lang::PrimitiveRef>(&data)) {
    py::dict dict;
    dict["primitive"] = shapes::PrimitiveName(p->kind);
    return dict;
  }
  return py::str(lang::Repr(value));
}

Eigen::Vector4d CalcQuaternionWxyz(const lang::SceneObject& object) {
  const Eigen::Quaterniond q = geometry::CanonicalQuaternion(object.R_WO.toRotationMatrix());
  return {q.w(), q.x(), q.y(), q.z()};
}

Eigen::Vector3d CalcObjectYawPitchRoll(const lang::SceneObject& object) {
  return geometry::CalcYawPitchRoll(object.R_WO.toRotationMatrix());
}

void RaiseScenarioError(const lang::Diagnostic& diagnostic, const lang::SourceManager& sources,
                        const std::string& text, const std::string& file_name) {
  const py::module_ errors = py::module_::import("probrobscene._errors");
  const py::object type =
      errors.attr(diagnostic.id == "sampling-failed" ? "SamplingError" : "ScenarioError");
  py::object file = py::none(), line = py::none(), column = py::none();
  if (!file_name.empty()) file = py::str(file_name);
  if (diagnostic.has_span && diagnostic.span.file < sources.file_count()) {
    const lang::LineColumn where =
        sources.CalcLineColumn(diagnostic.span.file, diagnostic.span.begin);
    file = py::str(sources.path(diagnostic.span.file));
    line = py::int_(where.line);
    column = py::int_(where.column);
  }
  const py::object error =
      type(diagnostic.message, py::arg("id") = diagnostic.id, py::arg("file") = file,
           py::arg("line") = line, py::arg("column") = column, py::arg("text") = text);
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

uint64_t ToSceneNumber(const py::object& value, const char* name) {
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value)) {
    throw py::type_error(std::string(name) + " must be an int, got " +
                         std::string(py::str(value.get_type().attr("__name__"))));
  }
  const unsigned long long number = PyLong_AsUnsignedLongLong(value.ptr());
  if (PyErr_Occurred()) {  // negative, or past 64 bits
    PyErr_Clear();
    throw py::value_error(std::string(name) + " must be from 0 to 2**64 - 1, got " +
                          std::string(py::str(value)));
  }
  return number;
}

}  // namespace prs::python
