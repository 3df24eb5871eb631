// Runtime values of the ProbRobScene interpreter: numbers, strings, vectors, oriented points,
// objects, regions, classes, functions and containers, plus the provenance that `resample`
// needs (which distribution a random value came from).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "geometry/region.h"
#include "shapes/primitive.h"

namespace prs::lang {

struct ClassInfo;
struct FunctionDef;
struct Value;
struct Distribution;

struct NoneValue {
  bool operator==(const NoneValue&) const = default;
};

/// A position with an orientation (the result of `top back of t`, or an object seen as a frame).
struct OrientedPoint {
  Eigen::Vector3d p_W;
  Eigen::Quaterniond R_WF;  // maps the point's local frame to the world
};

/// An orientation value (an object's `.orientation`).
struct Orientation {
  Eigen::Quaterniond R_WF;
};

/// A reference to an object of the scene being built (index into the scene's object list).
struct ObjectRef {
  int index;
};

/// A tuple. A 2-tuple of numbers used where a number is expected is a uniform range; the
/// draw is cached in the tuple so that a name bound to it keeps one value per scene.
/// Containers are immutable once built and record how deeply containers nest inside them
/// (`depth`, 1 for a container of plain values), so the interpreter can refuse values nested
/// too deeply for the recursive walks over them (printing, conversion, destruction).
struct TupleData {
  std::vector<Value> elements;
  mutable std::optional<double> drawn;
  int depth = 1;
};
struct ListData {
  std::vector<Value> elements;
  int depth = 1;
};
struct DictData {
  std::vector<std::pair<Value, Value>> entries;  // insertion order, as Python
  int depth = 1;
};

/// Built-in functions and modules, identified by a small enum for fast dispatch.
enum class Builtin : int;
struct BuiltinRef {
  Builtin id;
};
struct ModuleRef {  // `math`
  int id;
};
/// A method bound to its receiver, e.g. `v.norm` or `region.contains`.
struct BoundMethod {
  std::shared_ptr<const Value> receiver;
  std::string name;
};
/// A user function, with the module its globals live in.
struct FunctionRef {
  const FunctionDef* def;
  int module_index;
};

/// An object shape from a mesh file (`Mesh("mug.obj", scale=0.001)`, spec §10): the mesh as
/// loaded when the program was compiled, and the factor its file units are multiplied by.
struct MeshRef {
  std::shared_ptr<const shapes::MeshShape> mesh;
  double scale = 1;
};
/// A built-in shape (`Cylinder()`, `Sphere()`, `Capsule()`, spec §10) filling the object's box.
struct PrimitiveRef {
  shapes::Primitive kind;
};

using RegionPtr = std::shared_ptr<const geometry::ConvexRegion>;
using StringPtr = std::shared_ptr<const std::string>;

struct Value {
  std::variant<NoneValue, bool, double, StringPtr, Eigen::Vector3d, OrientedPoint, Orientation,
               ObjectRef, RegionPtr, const ClassInfo*, FunctionRef, BuiltinRef, ModuleRef,
               BoundMethod, std::shared_ptr<TupleData>, std::shared_ptr<ListData>,
               std::shared_ptr<DictData>, MeshRef, PrimitiveRef>
      data;
  /// The distribution this value was drawn from (for `resample`); null otherwise.
  std::shared_ptr<const Distribution> origin;

  Value() : data(NoneValue{}) {}
  template <typename T>
    requires(!std::is_same_v<std::decay_t<T>, Value>)
  Value(T v) : data(std::move(v)) {}  // NOLINT: implicit by design, values are plain data

  template <typename T>
  bool Is() const { return std::holds_alternative<T>(data); }
  template <typename T>
  const T& As() const { return std::get<T>(data); }
};

/// A distribution expression's kind and (evaluated) arguments, kept so `resample` can redraw.
enum class DistributionKind {
  kRange, kDiscreteRange, kNormal, kTruncatedNormal, kUniformChoice, kDiscrete
};
struct Distribution {
  DistributionKind kind;
  std::vector<Value> args;      // numbers, or the options for a choice
  std::vector<double> weights;  // kDiscrete only (normalised)
};

Value MakeString(std::string s);
Value MakeTuple(std::vector<Value> elements);
/// How deeply containers nest in `v`: 0 for a plain value, else the container's `depth`.
int CalcContainerDepth(const Value& v);
Value MakeList(std::vector<Value> elements);

/// The user-facing name of a value's type, for messages ("number", "vector", "object", …).
std::string TypeName(const Value& v);
/// A short rendering of a value for messages and for output of unknown property kinds.
std::string Repr(const Value& v);
/// A number as messages show it: integers without a decimal point, others to 6 digits.
std::string FormatNumber(double x);

}  // namespace prs::lang
