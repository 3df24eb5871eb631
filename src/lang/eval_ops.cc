// Operators and member access: arithmetic on numbers and vectors, comparisons, `in`,
// attributes of objects/vectors/regions, indexing, side points, `relative to`, `offset by`.
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;

namespace {

bool IsVectorLike(const Value& v) {
  return v.Is<Vector3d>() || v.Is<OrientedPoint>() || v.Is<ObjectRef>();
}

bool IsNumberLike(const Value& v) {
  if (v.Is<double>() || v.Is<bool>()) return true;
  const auto* tuple = std::get_if<std::shared_ptr<TupleData>>(&v.data);
  return tuple && (*tuple)->elements.size() == 2 && (*tuple)->elements[0].Is<double>() &&
         (*tuple)->elements[1].Is<double>();
}

// Built by appending: `"'" + std::string(...)` draws GCC 12's false -Wrestrict warning.
std::string OperatorName(BinaryOp op) {
  std::string name = "'";
  name += BinaryOpName(op);
  name += '\'';
  return name;
}

}  // namespace

Value Interpreter::EvalBinary(BinaryOp op, const Value& a, const Value& b, SourceSpan span) {
  if (op >= BinaryOp::kEq) return EvalCompare(op, a, b, span);
  Value result = EvalArithmetic(op, a, b, span);
  // An overflow would otherwise travel on as inf or nan into regions and rotations.
  const bool finite = result.Is<double>()            ? std::isfinite(result.As<double>())
                      : result.Is<Eigen::Vector3d>() ? result.As<Eigen::Vector3d>().allFinite()
                                                     : true;
  if (!finite) {
    Fail(span, "bad-value", "the result of " + OperatorName(op) + " is not a finite number");
  }
  return result;
}

Value Interpreter::EvalArithmetic(BinaryOp op, const Value& a, const Value& b, SourceSpan span) {
  const bool a_vec = IsVectorLike(a), b_vec = IsVectorLike(b);
  if ((op == BinaryOp::kAdd || op == BinaryOp::kSub) && a_vec && b_vec) {
    const Vector3d va = ToVector(a, span, "the left operand"), vb = ToVector(b, span, "");
    return Value(op == BinaryOp::kAdd ? Vector3d(va + vb) : Vector3d(va - vb));
  }
  if ((op == BinaryOp::kMul || op == BinaryOp::kDiv) && a_vec && IsNumberLike(b)) {
    const double k = ToNumber(b, span, "the scale factor");
    if (op == BinaryOp::kDiv && k == 0) Fail(span, "bad-value", "division of a vector by zero");
    const Vector3d v = ToVector(a, span, "");
    return Value(op == BinaryOp::kMul ? Vector3d(v * k) : Vector3d(v / k));
  }
  if (op == BinaryOp::kMul && IsNumberLike(a) && b_vec) {
    return Value(Vector3d(ToNumber(a, span, "") * ToVector(b, span, "")));
  }
  if (op == BinaryOp::kAdd) {
    if (a.Is<StringPtr>() && b.Is<StringPtr>()) return MakeString(*a.As<StringPtr>() + *b.As<StringPtr>());
    if (a.Is<std::shared_ptr<ListData>>() && b.Is<std::shared_ptr<ListData>>()) {
      std::vector<Value> joined = a.As<std::shared_ptr<ListData>>()->elements;
      const auto& tail = b.As<std::shared_ptr<ListData>>()->elements;
      joined.insert(joined.end(), tail.begin(), tail.end());
      return MakeList(std::move(joined));
    }
  }
  if (!IsNumberLike(a) || !IsNumberLike(b)) {
    Fail(span, "type-error", "cannot apply " + OperatorName(op) + " to a " + TypeName(a) +
                                 " and a " + TypeName(b));
  }
  const double x = ToNumber(a, span, ""), y = ToNumber(b, span, "");
  switch (op) {
    case BinaryOp::kAdd: return x + y;
    case BinaryOp::kSub: return x - y;
    case BinaryOp::kMul: return x * y;
    case BinaryOp::kPow: return std::pow(x, y);
    default: break;
  }
  if (y == 0) Fail(span, "bad-value", "division by zero");
  if (op == BinaryOp::kDiv) return x / y;
  if (op == BinaryOp::kFloorDiv) return std::floor(x / y);
  return x - y * std::floor(x / y);  // Python's modulo takes the divisor's sign
}

Value Interpreter::EvalCompare(BinaryOp op, const Value& a, const Value& b, SourceSpan span) {
  switch (op) {
    case BinaryOp::kEq: case BinaryOp::kIs: return ValuesEqual(a, b);
    case BinaryOp::kNe: case BinaryOp::kIsNot: return !ValuesEqual(a, b);
    case BinaryOp::kIn: case BinaryOp::kNotIn: {
      bool found = false;
      if (const auto* region = std::get_if<RegionPtr>(&b.data)) {
        found = (*region)->Contains(ToVector(a, span, "the left side of 'in'"));
      } else if (const auto* s = std::get_if<StringPtr>(&b.data); s && a.Is<StringPtr>()) {
        found = (*s)->find(*a.As<StringPtr>()) != std::string::npos;
      } else {
        for (const Value& item : Iterate(b, span)) found |= ValuesEqual(a, item);
      }
      return op == BinaryOp::kIn ? found : !found;
    }
    default: break;
  }
  if (a.Is<StringPtr>() && b.Is<StringPtr>()) {
    const int c = a.As<StringPtr>()->compare(*b.As<StringPtr>());
    switch (op) {
      case BinaryOp::kLt: return c < 0;
      case BinaryOp::kLe: return c <= 0;
      case BinaryOp::kGt: return c > 0;
      default: return c >= 0;
    }
  }
  if (!IsNumberLike(a) || !IsNumberLike(b)) {
    Fail(span, "type-error", "cannot compare a " + TypeName(a) + " and a " + TypeName(b) +
                                 " with " + OperatorName(op));
  }
  const double x = ToNumber(a, span, ""), y = ToNumber(b, span, "");
  switch (op) {
    case BinaryOp::kLt: return x < y;
    case BinaryOp::kLe: return x <= y;
    case BinaryOp::kGt: return x > y;
    default: return x >= y;
  }
}

Value Interpreter::EvalAttribute(const Value& object, const Identifier& attribute,
                                 SourceSpan span) {
  const std::string& name = attribute.name;
  if (const auto* ref = std::get_if<ObjectRef>(&object.data)) {
    const SceneObject& o = scene_.objects[ref->index];
    if (name == "x" || name == "y" || name == "z") return o.p_WO[name[0] - 'x'];
    return GetProperty(ref->index, name, attribute.span);
  }
  if (const auto* v = std::get_if<Vector3d>(&object.data)) {
    if (name == "x" || name == "y" || name == "z") return (*v)[name[0] - 'x'];
    if (name == "norm" || name == "normalized" || name == "dot" || name == "cross") {
      return BoundMethod{std::make_shared<const Value>(object), name};
    }
  }
  if (const auto* p = std::get_if<OrientedPoint>(&object.data)) {
    if (name == "x" || name == "y" || name == "z") return p->p_W[name[0] - 'x'];
    if (name == "position") return Value(p->p_W);
    if (name == "orientation") return Orientation{p->R_WF};
  }
  if (const auto* o = std::get_if<Orientation>(&object.data)) {
    const Vector3d ypr = geometry::CalcYawPitchRoll(o->R_WF.toRotationMatrix());
    if (name == "yaw") return ypr.x();
    if (name == "pitch") return ypr.y();
    if (name == "roll") return ypr.z();
  }
  if (const auto* r = std::get_if<RegionPtr>(&object.data)) {
    if (name == "contains" || name == "intersect") {
      return BoundMethod{std::make_shared<const Value>(object), name};
    }
    if (name == "volume" || name == "area") {
      if (!(*r)->IsBounded()) Fail(span, "bad-value", "this region is unbounded, so it has no " + name);
      try {
        return (*r)->CalcMeasure();
      } catch (const std::exception& e) {
        Fail(span, "bad-value", "cannot compute the " + name + " of this region: " + e.what());
      }
    }
  }
  if (object.Is<ModuleRef>()) {
    double constant = 0;
    if (FindMathConstant(name, &constant)) return constant;
    if (const BuiltinInfo* info = FindMathBuiltin(name)) return BuiltinRef{info->id};
  }
  Fail(attribute.span, "unknown-attribute",
       "a " + TypeName(object) + " has no attribute '" + name + "'");
}

Value Interpreter::EvalIndex(const Value& object, const Value& index, SourceSpan span) {
  if (const auto* dict = std::get_if<std::shared_ptr<DictData>>(&object.data)) {
    for (const auto& [key, value] : (*dict)->entries) {
      if (ValuesEqual(key, index)) return value;
    }
    Fail(span, "bad-index", "key " + Repr(index) + " is not in this dict");
  }
  std::vector<Value> items = Iterate(object, span);
  const double i = ToNumber(index, span, "an index");
  const double n = static_cast<double>(items.size());
  const double k = i < 0 ? i + n : i;
  if (k != std::floor(k) || k < 0 || k >= n) {
    Fail(span, "bad-index", "index " + Repr(index) + " is out of range for " +
                                std::to_string(items.size()) + " elements");
  }
  return items[static_cast<size_t>(k)];
}

// The centre of a face, edge or corner of an object's box, with the object's orientation.
Value Interpreter::EvalSidePoint(const SidePointExpr& node, SourceSpan span) {
  const Value target = Eval(*node.object);
  const auto* ref = std::get_if<ObjectRef>(&target.data);
  if (!ref || !scene_.objects[ref->index].cls->has_box) {
    std::string message = "'";
    message += SideName(node.side);
    message += " of' needs an object with a size, but this is a " + TypeName(target);
    Fail(node.object->span, "type-error", std::move(message));
  }
  const SceneObject& o = scene_.objects[ref->index];
  const Vector3d h = o.dimensions / 2;
  Vector3d local = Vector3d::Zero();
  switch (node.side) {
    case Side::kFront: local = {0, h.y(), 0}; break;
    case Side::kBack: local = {0, -h.y(), 0}; break;
    case Side::kLeft: local = {-h.x(), 0, 0}; break;
    case Side::kRight: local = {h.x(), 0, 0}; break;
    case Side::kTop: local = {0, 0, h.z()}; break;
    case Side::kBottom: local = {0, 0, -h.z()}; break;
    case Side::kFrontLeft: local = {-h.x(), h.y(), 0}; break;
    case Side::kFrontRight: local = {h.x(), h.y(), 0}; break;
    case Side::kBackLeft: local = {-h.x(), -h.y(), 0}; break;
    case Side::kBackRight: local = {h.x(), -h.y(), 0}; break;
    case Side::kTopFront: local = {0, h.y(), h.z()}; break;
    case Side::kTopBack: local = {0, -h.y(), h.z()}; break;
  }
  (void)span;
  return OrientedPoint{o.p_WO + o.R_WO * local, o.R_WO};
}

// `V relative to B`: B a vector adds it; B an oriented point or object reads V in B's frame.
Value Interpreter::EvalRelativeTo(const Value& value, const Value& base, SourceSpan span) {
  const Vector3d v = ToVector(value, span, "the left side of 'relative to'");
  if (const auto* b = std::get_if<Vector3d>(&base.data)) return Value(Vector3d(v + *b));
  const OrientedPoint frame = ToOrientedPoint(base, span, "the right side of 'relative to'");
  return OrientedPoint{frame.p_W + frame.R_WF * v, frame.R_WF};
}

// `A offset by V`: A a vector adds V; A an oriented point or object adds V in A's frame.
Value Interpreter::EvalOffsetBy(const Value& value, const Value& offset, SourceSpan span) {
  const Vector3d v = ToVector(offset, span, "the offset of 'offset by'");
  if (const auto* a = std::get_if<Vector3d>(&value.data)) return Value(Vector3d(*a + v));
  const OrientedPoint frame = ToOrientedPoint(value, span, "the left side of 'offset by'");
  return OrientedPoint{frame.p_W + frame.R_WF * v, frame.R_WF};
}

}  // namespace prs::lang::internal
