// Scene and SceneObject as Python sees them (views over the sampled C++ scene, converted on
// access), and the batch helpers that gather one object's pose over many scenes into numpy.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "output/scene_json.h"

namespace prs::python {
namespace {

// The object named `name` (its variable, or "Class#index" for an anonymous one), or -1.
int FindObject(const Scene& scene, const std::string& name) {
  const auto& objects = scene.sampled.scene.objects;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].name == name) return int(i);
  }
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].DisplayName(int(i)) == name) return int(i);
  }
  return -1;
}

std::string ListObjectNames(const Scene& scene) {
  std::string names;
  const auto& objects = scene.sampled.scene.objects;
  for (size_t i = 0; i < objects.size(); ++i) {
    names += (names.empty() ? "" : ", ") + objects[i].DisplayName(int(i));
  }
  return names.empty() ? "none" : names;
}

[[noreturn]] void ThrowNoObject(const Scene& scene, const std::string& name) {
  throw py::key_error("scene " + std::to_string(scene.sampled.index) + " of seed " +
                      std::to_string(scene.sampled.seed) + " has no object named '" + name +
                      "' (objects: " + ListObjectNames(scene) + ")");
}

SceneObjectView GetObject(const ScenePtr& scene, const std::string& name) {
  const int index = FindObject(*scene, name);
  if (index < 0) ThrowNoObject(*scene, name);
  return {scene, index};
}

// (name, value) pairs: an object's PropertyList or a scene's params.
template <typename Entries>
py::dict ToDict(const Entries& entries, bool skip_core = false) {
  py::dict dict;
  for (const auto& [name, value] : entries) {
    if (skip_core && output::IsCoreProperty(name)) continue;
    dict[py::str(name)] = ToPython(value);
  }
  return dict;
}

py::dict CountRejections(const sampling::RejectionCounts& rejections) {
  py::dict counts;
  for (const auto& [kind, n] : rejections.by_kind) counts[lang::RejectionKindName(kind)] = n;
  return counts;
}

// Rows of `width` numbers, one per scene, from the object `name` of each scene.
template <typename Row>
py::array_t<double> GatherRows(const py::iterable& scenes, const std::string& name, int width,
                               Row row) {
  std::vector<double> values;
  size_t position = 0;
  for (const py::handle item : scenes) {
    if (!py::isinstance<Scene>(item)) {
      throw py::type_error("expected Scene objects, got " +
                           std::string(py::str(py::type::of(item).attr("__name__"))) +
                           " at position " + std::to_string(position));
    }
    ++position;
    const Scene& scene = item.cast<const Scene&>();
    const int index = FindObject(scene, name);
    if (index < 0) ThrowNoObject(scene, name);
    const auto numbers = row(scene.sampled.scene.objects[index]);
    values.insert(values.end(), numbers.data(), numbers.data() + width);
  }
  py::array_t<double> array({py::ssize_t(values.size() / width), py::ssize_t(width)});
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

void BindSceneObject(py::module_& m) {
  using View = SceneObjectView;
  py::class_<View>(m, "SceneObject", "One object of a sampled scene (units: metres, radians).")
      .def_property_readonly(
          "name", [](const View& v) { return v.object().name; },
          "The variable the object was first bound to, or None for an anonymous object.")
      .def_property_readonly(
          "display_name", [](const View& v) { return v.object().DisplayName(v.index); },
          "The name, or 'Class#index' for an anonymous object.")
      .def_property_readonly(
          "class_name", [](const View& v) { return v.object().cls->name; }, "The class name.")
      .def_property_readonly(
          "position", [](const View& v) { return Eigen::Vector3d(v.object().p_WO); },
          "Centre of the object in the world frame, a numpy array (3,).")
      .def_property_readonly(
          "dimensions", [](const View& v) { return Eigen::Vector3d(v.object().dimensions); },
          "(width, length, height) along the object's x, y, z axes, a numpy array (3,).")
      .def_property_readonly(
          "quaternion", [](const View& v) { return CalcQuaternionWxyz(v.object()); },
          "Orientation as a unit quaternion (w, x, y, z) mapping object to world, w >= 0.")
      .def_property_readonly(
          "yaw_pitch_roll", [](const View& v) { return CalcObjectYawPitchRoll(v.object()); },
          "Intrinsic Z-Y'-X'' angles (yaw, pitch, roll), a numpy array (3,).")
      .def_property_readonly(
          "yaw", [](const View& v) { return CalcObjectYawPitchRoll(v.object()).x(); }, "Yaw.")
      .def_property_readonly(
          "pitch", [](const View& v) { return CalcObjectYawPitchRoll(v.object()).y(); }, "Pitch.")
      .def_property_readonly(
          "roll", [](const View& v) { return CalcObjectYawPitchRoll(v.object()).z(); }, "Roll.")
      .def_property_readonly(
          "properties", [](const View& v) { return ToDict(v.object().properties, true); },
          "The other properties (color, user properties, ...) in definition order.")
      .def("__repr__", [](const View& v) {
        const auto& p = v.object().p_WO;
        return "<SceneObject " + v.object().DisplayName(v.index) + " (" + v.object().cls->name +
               ") at (" + lang::FormatNumber(p.x()) + ", " + lang::FormatNumber(p.y()) + ", " +
               lang::FormatNumber(p.z()) + ")>";
      });
}

void BindSceneClass(py::module_& m) {
  py::class_<Scene, ScenePtr> scene(m, "Scene", "One sampled scene: scene `index` of `seed`.");
  BindSceneFiles(scene);
  scene
      .def_property_readonly("seed", [](const Scene& s) { return s.sampled.seed; })
      .def_property_readonly("index", [](const Scene& s) { return s.sampled.index; })
      .def_property_readonly(
          "attempts", [](const Scene& s) { return s.sampled.attempts; },
          "Attempts the sampler made, the accepted one included.")
      .def_property_readonly(
          "rejections", [](const Scene& s) { return CountRejections(s.sampled.rejections); },
          "Rejected attempts by reason ('collision', 'requirement', ...).")
      .def_property_readonly(
          "params", [](const Scene& s) { return ToDict(s.sampled.scene.params); },
          "The scenario's params with their values in this scene.")
      .def_property_readonly(
          "objects",
          [](const ScenePtr& s) {
            std::vector<SceneObjectView> views;
            for (size_t i = 0; i < s->sampled.scene.objects.size(); ++i) {
              views.push_back({s, int(i)});
            }
            return views;
          },
          "The objects in creation order.")
      .def("__getitem__", &GetObject, py::arg("name"),
           "The object with this variable name (or 'Class#index'); KeyError if none.")
      .def("__contains__",
           [](const Scene& s, const std::string& name) { return FindObject(s, name) >= 0; })
      .def("__len__", [](const Scene& s) { return s.sampled.scene.objects.size(); })
      .def(
          "to_json", [](const Scene& s) { return output::FormatSceneJson(s.sampled); },
          "The scene as one line of spec §8 JSON, exactly as `prs sample` writes it.")
      .def(
          "to_dict",
          [](const Scene& s) {
            return py::module_::import("json").attr("loads")(output::FormatSceneJson(s.sampled));
          },
          "The spec §8 JSON object as Python dicts and lists (to_json(), parsed).")
      .def("__repr__", [](const Scene& s) {
        return "<Scene seed=" + std::to_string(s.sampled.seed) +
               " index=" + std::to_string(s.sampled.index) +
               " objects=" + std::to_string(s.sampled.scene.objects.size()) + ">";
      });
}

void BindBatchHelpers(py::module_& m) {
  m.def(
      "positions",
      [](const py::iterable& scenes, const std::string& name) {
        return GatherRows(scenes, name, 3, [](const lang::SceneObject& o) { return o.p_WO; });
      },
      py::arg("scenes"), py::arg("name"),
      "Positions of object `name` in each scene, an (n, 3) array. KeyError if a scene lacks it.");
  m.def(
      "dimensions",
      [](const py::iterable& scenes, const std::string& name) {
        return GatherRows(scenes, name, 3, [](const lang::SceneObject& o) { return o.dimensions; });
      },
      py::arg("scenes"), py::arg("name"), "(width, length, height) of `name` per scene, (n, 3).");
  m.def(
      "quaternions",
      [](const py::iterable& scenes, const std::string& name) {
        return GatherRows(scenes, name, 4, &CalcQuaternionWxyz);
      },
      py::arg("scenes"), py::arg("name"), "Quaternions (w, x, y, z) of `name` per scene, (n, 4).");
  m.def(
      "yaw_pitch_roll",
      [](const py::iterable& scenes, const std::string& name) {
        return GatherRows(scenes, name, 3, &CalcObjectYawPitchRoll);
      },
      py::arg("scenes"), py::arg("name"), "(yaw, pitch, roll) of `name` per scene, (n, 3).");
}

}  // namespace

void BindScene(py::module_& m) {
  BindSceneObject(m);
  BindSceneClass(m);
  BindBatchHelpers(m);
}

}  // namespace prs::python
