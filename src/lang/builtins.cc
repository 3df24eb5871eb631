// The built-in function table. Arity and signatures live here only.
#include "lang/builtins.h"

#include <cmath>
#include <numbers>

namespace prs::lang {

const std::vector<BuiltinInfo>& GlobalBuiltins() {
  static const std::vector<BuiltinInfo> kTable = {
      {"Vector3D", Builtin::kVector3D, 3, 3, "Vector3D(x, y, z)"},
      {"V3D", Builtin::kVector3D, 3, 3, "V3D(x, y, z)"},
      {"Range", Builtin::kRange, 2, 2, "Range(low, high)"},
      {"DiscreteRange", Builtin::kDiscreteRange, 2, 2, "DiscreteRange(low, high)"},
      {"Normal", Builtin::kNormal, 2, 2, "Normal(mean, std)"},
      {"TruncatedNormal", Builtin::kTruncatedNormal, 4, 4,
       "TruncatedNormal(mean, std, low, high)"},
      {"Uniform", Builtin::kUniform, 1, -1, "Uniform(value, ...)"},
      {"Options", Builtin::kOptions, 1, 1, "Options([value, ...])"},
      {"Discrete", Builtin::kDiscrete, 1, 1, "Discrete({value: weight, ...})"},
      {"resample", Builtin::kResample, 1, 1, "resample(x)"},
      {"Cuboid", Builtin::kCuboid, 5, 5, "Cuboid(center, orientation, width, length, height)"},
      {"Rect3D", Builtin::kRect3D, 4, 4, "Rect3D(width, length, origin, orientation)"},
      {"Rectangle3D", Builtin::kRect3D, 4, 4, "Rectangle3D(width, length, origin, orientation)"},
      {"HalfSpace", Builtin::kHalfSpace, 2, 2, "HalfSpace(point, normal)"},
      {"ConvexPolygon3D", Builtin::kConvexPolygon3D, 1, 1, "ConvexPolygon3D([vertex, ...])"},
      {"ConvexPolyhedron", Builtin::kConvexPolyhedron, 1, 1,
       "ConvexPolyhedron([HalfSpace(point, normal), ...])"},
      {"Sphere", Builtin::kSphere, 0, 2, "Sphere(center, radius) for a region; Sphere() for a shape, sized by the object's width, length and height"},
      {"All", Builtin::kAll, 0, 0, "All()"},
      {"Empty", Builtin::kEmpty, 0, 0, "Empty()"},
      {"Mesh", Builtin::kMesh, 1, 2, "Mesh(file, scale=S)"},
      {"Cylinder", Builtin::kCylinder, 0, 0, "Cylinder(), sized by the object's width, length and height"},
      {"Capsule", Builtin::kCapsule, 0, 0, "Capsule(), sized by the object's width, length and height"},
      {"range", Builtin::kRangeFn, 1, 3, "range([start,] stop[, step])"},
      {"len", Builtin::kLen, 1, 1, "len(x)"},
      {"abs", Builtin::kAbs, 1, 1, "abs(x)"},
      {"min", Builtin::kMin, 1, -1, "min(a, b, ...)"},
      {"max", Builtin::kMax, 1, -1, "max(a, b, ...)"},
      {"round", Builtin::kRound, 1, 2, "round(x[, digits])"},
      {"int", Builtin::kInt, 1, 1, "int(x)"},
      {"float", Builtin::kFloat, 1, 1, "float(x)"},
      {"str", Builtin::kStr, 1, 1, "str(x)"},
      {"bool", Builtin::kBool, 1, 1, "bool(x)"},
      {"list", Builtin::kList, 1, 1, "list(x)"},
      {"sum", Builtin::kSum, 1, 1, "sum(values)"},
  };
  return kTable;
}

const std::vector<BuiltinInfo>& MathBuiltins() {
  static const std::vector<BuiltinInfo> kTable = {
      {"sin", Builtin::kSin, 1, 1, "math.sin(x)"},
      {"cos", Builtin::kCos, 1, 1, "math.cos(x)"},
      {"tan", Builtin::kTan, 1, 1, "math.tan(x)"},
      {"asin", Builtin::kAsin, 1, 1, "math.asin(x)"},
      {"acos", Builtin::kAcos, 1, 1, "math.acos(x)"},
      {"atan", Builtin::kAtan, 1, 1, "math.atan(x)"},
      {"atan2", Builtin::kAtan2, 2, 2, "math.atan2(y, x)"},
      {"sqrt", Builtin::kSqrt, 1, 1, "math.sqrt(x)"},
      {"exp", Builtin::kExp, 1, 1, "math.exp(x)"},
      {"log", Builtin::kLog, 1, 2, "math.log(x[, base])"},
      {"radians", Builtin::kRadians, 1, 1, "math.radians(degrees)"},
      {"degrees", Builtin::kDegrees, 1, 1, "math.degrees(radians)"},
      {"floor", Builtin::kFloor, 1, 1, "math.floor(x)"},
      {"ceil", Builtin::kCeil, 1, 1, "math.ceil(x)"},
      {"fabs", Builtin::kFabs, 1, 1, "math.fabs(x)"},
      {"hypot", Builtin::kHypot, 2, 2, "math.hypot(x, y)"},
  };
  return kTable;
}

namespace {
const BuiltinInfo* FindIn(const std::vector<BuiltinInfo>& table, std::string_view name) {
  for (const BuiltinInfo& info : table) {
    if (name == info.name) return &info;
  }
  return nullptr;
}
}  // namespace

const BuiltinInfo* FindGlobalBuiltin(std::string_view name) {
  return FindIn(GlobalBuiltins(), name);
}
const BuiltinInfo* FindMathBuiltin(std::string_view name) { return FindIn(MathBuiltins(), name); }

const BuiltinInfo& GetBuiltinInfo(Builtin id) {
  for (const auto* table : {&GlobalBuiltins(), &MathBuiltins()}) {
    for (const BuiltinInfo& info : *table) {
      if (info.id == id) return info;
    }
  }
  return GlobalBuiltins().front();  // unreachable: every id is in a table
}

bool FindMathConstant(std::string_view name, double* value) {
  if (name == "pi") *value = std::numbers::pi;
  else if (name == "e") *value = std::numbers::e;
  else if (name == "tau") *value = 2 * std::numbers::pi;
  else if (name == "inf") *value = HUGE_VAL;
  else return false;
  return true;
}

}  // namespace prs::lang
