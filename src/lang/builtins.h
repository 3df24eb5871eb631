// The table of built-in functions (global ones and the `math` module's): names, arities and
// one-line signatures, shared by the resolver (arity checks, suggestions) and the interpreter.
#pragma once

#include <string_view>
#include <vector>

namespace prs::lang {

enum class Builtin : int {
  // Vectors and distributions.
  kVector3D, kRange, kDiscreteRange, kNormal, kTruncatedNormal, kUniform, kOptions, kDiscrete,
  kResample,
  // Regions.
  kCuboid, kRect3D, kHalfSpace, kConvexPolygon3D, kConvexPolyhedron, kSphere, kAll, kEmpty,
  // Python-like helpers.
  kRangeFn, kLen, kAbs, kMin, kMax, kRound, kInt, kFloat, kStr, kBool, kList, kSum,
  // Object shapes.
  kMesh, kCylinder, kCapsule,  // and kSphere with no arguments
  // The math module.
  kSin, kCos, kTan, kAsin, kAcos, kAtan, kAtan2, kSqrt, kExp, kLog, kRadians, kDegrees,
  kFloor, kCeil, kFabs, kHypot,
};

struct BuiltinInfo {
  const char* name;
  Builtin id;
  int min_args;
  int max_args;  // -1: any number
  const char* signature;  // for messages, e.g. "Range(low, high)"
};

/// Functions callable by bare name (Vector3D and its alias V3D, Range, Cuboid, len, ...).
const std::vector<BuiltinInfo>& GlobalBuiltins();
/// Functions of `import math` (math.pi and math.e are constants, see MathConstant).
const std::vector<BuiltinInfo>& MathBuiltins();

const BuiltinInfo* FindGlobalBuiltin(std::string_view name);
const BuiltinInfo* FindMathBuiltin(std::string_view name);
const BuiltinInfo& GetBuiltinInfo(Builtin id);
/// math.pi, math.e (and math.tau, math.inf); returns false for other names.
bool FindMathConstant(std::string_view name, double* value);

}  // namespace prs::lang
