// The interpreter's expression layer: literals, names, operators (with a 2-tuple of numbers
// drawn as a uniform range where a number is expected), attributes, side points of objects,
// `relative to`, `offset by` and `distance from`.
#include <algorithm>
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;

// The parser bounds each tree's height and block depth, but calls nest trees and blocks inside
// each other: bound the sum, so evaluation stays within a thread's stack.
void Interpreter::EnterNested(SourceSpan span) {
  if (eval_depth_ >= options_.limits.max_eval_depth) {
    Fail(span, "limit-exceeded",
         "expressions, blocks and function calls nested deeper than " +
             std::to_string(options_.limits.max_eval_depth) +
             " levels while evaluating; is this recursion meant to end?");
  }
  ++eval_depth_;
}

// A container nested in containers beyond the limit (built by a loop, `x = (x,)`) would
// overflow the stack when printed, converted or freed: refuse it where it is built.
Value Interpreter::CheckNesting(Value container, SourceSpan span) {
  if (CalcContainerDepth(container) > kMaxContainerDepth) {
    Fail(span, "limit-exceeded",
         "tuples, lists or dicts nested more than " + std::to_string(kMaxContainerDepth) +
             " levels deep; is a loop wrapping a value in itself?");
  }
  return container;
}

Value Interpreter::Eval(const Expr& expr) {
  EnterNested(expr.span);
  Value value = EvalNode(expr);
  --eval_depth_;  // not restored on an exception: the attempt is over then
  return value;
}

Value Interpreter::EvalNode(const Expr& expr) {
  return std::visit(
      [&](const auto& node) -> Value {
        using T = std::decay_t<decltype(node)>;
        if constexpr (std::is_same_v<T, NumberLit>) {
          return node.value;
        } else if constexpr (std::is_same_v<T, StringLit>) {
          return MakeString(node.value);
        } else if constexpr (std::is_same_v<T, BoolLit>) {
          return node.value;
        } else if constexpr (std::is_same_v<T, NoneLit>) {
          return Value();
        } else if constexpr (std::is_same_v<T, NameRef>) {
          return Lookup(node.name, expr.span);
        } else if constexpr (std::is_same_v<T, TupleExpr> || std::is_same_v<T, ListExpr>) {
          std::vector<Value> elements;
          elements.reserve(node.elements.size());
          for (const ExprPtr& e : node.elements) elements.push_back(Eval(*e));
          if constexpr (std::is_same_v<T, TupleExpr>)
            return CheckNesting(MakeTuple(std::move(elements)), expr.span);
          else
            return CheckNesting(MakeList(std::move(elements)), expr.span);
        } else if constexpr (std::is_same_v<T, DictExpr>) {
          auto dict = std::make_shared<DictData>();
          for (const auto& [k, v] : node.entries) {
            dict->entries.emplace_back(Eval(*k), Eval(*v));
            dict->depth = std::max({dict->depth, CalcContainerDepth(dict->entries.back().first) + 1,
                                    CalcContainerDepth(dict->entries.back().second) + 1});
          }
          return CheckNesting(Value(std::move(dict)), expr.span);
        } else if constexpr (std::is_same_v<T, UnaryExpr>) {
          const Value operand = Eval(*node.operand);
          if (node.op == UnaryOp::kNot) return !Truthy(operand, expr.span);
          if (const auto* v = std::get_if<Vector3d>(&operand.data)) {
            return node.op == UnaryOp::kNeg ? Value(Vector3d(-*v)) : operand;
          }
          const double x = ToNumber(operand, node.operand->span, "the operand of unary minus");
          return node.op == UnaryOp::kNeg ? -x : x;
        } else if constexpr (std::is_same_v<T, BinaryExpr>) {
          if (node.op == BinaryOp::kAnd || node.op == BinaryOp::kOr) {
            Value lhs = Eval(*node.lhs);
            const bool lhs_true = Truthy(lhs, node.lhs->span);
            if ((node.op == BinaryOp::kAnd) != lhs_true) return lhs;
            return Eval(*node.rhs);
          }
          const Value lhs = Eval(*node.lhs);
          return EvalBinary(node.op, lhs, Eval(*node.rhs), node.op_span);
        } else if constexpr (std::is_same_v<T, CompareChain>) {
          Value lhs = Eval(*node.operands[0]);
          for (size_t i = 0; i < node.ops.size(); ++i) {
            Value rhs = Eval(*node.operands[i + 1]);
            if (!Truthy(EvalCompare(node.ops[i], lhs, rhs, node.op_spans[i]), expr.span)) {
              return false;
            }
            lhs = std::move(rhs);
          }
          return true;
        } else if constexpr (std::is_same_v<T, ConditionalExpr>) {
          return Truthy(Eval(*node.condition), node.condition->span) ? Eval(*node.then_value)
                                                                     : Eval(*node.else_value);
        } else if constexpr (std::is_same_v<T, CallExpr>) {
          return EvalCall(node, expr.span);
        } else if constexpr (std::is_same_v<T, AttributeExpr>) {
          return EvalAttribute(Eval(*node.object), node.attribute, expr.span);
        } else if constexpr (std::is_same_v<T, IndexExpr>) {
          const Value object = Eval(*node.object);
          return EvalIndex(object, Eval(*node.index), node.index->span);
        } else if constexpr (std::is_same_v<T, SidePointExpr>) {
          return EvalSidePoint(node, expr.span);
        } else if constexpr (std::is_same_v<T, RelativeToExpr>) {
          const Value value = Eval(*node.value);
          return EvalRelativeTo(value, Eval(*node.base), expr.span);
        } else if constexpr (std::is_same_v<T, OffsetByExpr>) {
          const Value value = Eval(*node.value);
          return EvalOffsetBy(value, Eval(*node.offset), expr.span);
        } else if constexpr (std::is_same_v<T, DistanceExpr>) {
          const Vector3d a = EvalVector(*node.from, "'distance from'");
          return (EvalVector(*node.to, "'distance ... to'") - a).norm();
        } else if constexpr (std::is_same_v<T, ClassRef>) {
          return program_.class_scopes[current_module_].at(node.name);
        } else {
          static_assert(std::is_same_v<T, prs::lang::CreateObject>);
          return CreateObject(program_.plans.at(&node), expr.span);
        }
      },
      expr.node);
}

double Interpreter::ToNumber(const Value& v, SourceSpan span, const std::string& what) {
  if (const auto* x = std::get_if<double>(&v.data)) return *x;
  if (const auto* b = std::get_if<bool>(&v.data)) return *b ? 1 : 0;
  if (const auto* tuple = std::get_if<std::shared_ptr<TupleData>>(&v.data)) {
    const auto& elements = (*tuple)->elements;
    if (elements.size() == 2 && elements[0].Is<double>() && elements[1].Is<double>()) {
      if (!(*tuple)->drawn) {
        const double lo = elements[0].As<double>(), hi = elements[1].As<double>();
        (*tuple)->drawn = DrawUniform(std::min(lo, hi), std::max(lo, hi), span, "interval");
      }
      return *(*tuple)->drawn;
    }
  }
  Fail(span, "type-error", what + " must be a number, but this is a " + TypeName(v));
}

Vector3d Interpreter::ToVector(const Value& v, SourceSpan span, const std::string& what) {
  if (const auto* vec = std::get_if<Vector3d>(&v.data)) return *vec;
  if (const auto* point = std::get_if<OrientedPoint>(&v.data)) return point->p_W;
  if (const auto* object = std::get_if<ObjectRef>(&v.data)) {
    return scene_.objects[object->index].p_WO;
  }
  Fail(span, "type-error", what + " must be a vector, an oriented point or an object, but this is a " +
                               TypeName(v));
}

Eigen::Quaterniond Interpreter::ToOrientation(const Value& v, SourceSpan span,
                                              const std::string& what) {
  if (const auto* o = std::get_if<Orientation>(&v.data)) return o->R_WF;
  if (const auto* point = std::get_if<OrientedPoint>(&v.data)) return point->R_WF;
  if (const auto* object = std::get_if<ObjectRef>(&v.data)) {
    return scene_.objects[object->index].R_WO;
  }
  if (const auto* vec = std::get_if<Vector3d>(&v.data)) {
    // Compatibility with existing .prs files: a vector is Euler angles (spec §4).
    return Eigen::Quaterniond(geometry::CalcRotationFromEulerVector(*vec));
  }
  Fail(span, "type-error", what + " must be an orientation or a vector of Euler angles, but this is a " +
                               TypeName(v));
}

OrientedPoint Interpreter::ToOrientedPoint(const Value& v, SourceSpan span,
                                           const std::string& what) {
  if (const auto* point = std::get_if<OrientedPoint>(&v.data)) return *point;
  if (const auto* object = std::get_if<ObjectRef>(&v.data)) {
    return {scene_.objects[object->index].p_WO, scene_.objects[object->index].R_WO};
  }
  return {ToVector(v, span, what), Eigen::Quaterniond::Identity()};
}

bool Interpreter::Truthy(const Value& v, SourceSpan span) {
  if (const auto* b = std::get_if<bool>(&v.data)) return *b;
  if (const auto* x = std::get_if<double>(&v.data)) return *x != 0;
  if (v.Is<NoneValue>()) return false;
  if (const auto* s = std::get_if<StringPtr>(&v.data)) return !(*s)->empty();
  if (const auto* list = std::get_if<std::shared_ptr<ListData>>(&v.data)) {
    return !(*list)->elements.empty();
  }
  if (const auto* tuple = std::get_if<std::shared_ptr<TupleData>>(&v.data)) {
    return !(*tuple)->elements.empty();
  }
  if (v.Is<Vector3d>() || v.Is<RegionPtr>()) {
    Fail(span, "type-error", "a " + TypeName(v) + " is neither true nor false here; compare it "
                             "with something (e.g. 'v.norm() > 0', 'r.contains(p)')");
  }
  return true;
}

bool Interpreter::ValuesEqual(const Value& a, const Value& b) {
  if ((a.Is<double>() || a.Is<bool>()) && (b.Is<double>() || b.Is<bool>())) {
    return ToNumber(a, {}, "") == ToNumber(b, {}, "");
  }
  if (a.data.index() != b.data.index()) return false;
  if (const auto* s = std::get_if<StringPtr>(&a.data)) return **s == *b.As<StringPtr>();
  if (const auto* v = std::get_if<Vector3d>(&a.data)) return *v == b.As<Vector3d>();
  if (const auto* o = std::get_if<ObjectRef>(&a.data)) return o->index == b.As<ObjectRef>().index;
  if (const auto* c = std::get_if<const ClassInfo*>(&a.data)) return *c == b.As<const ClassInfo*>();
  if (a.Is<NoneValue>()) return true;
  auto same_elements = [&](const std::vector<Value>& x, const std::vector<Value>& y) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i) {
      if (!ValuesEqual(x[i], y[i])) return false;
    }
    return true;
  };
  if (const auto* t = std::get_if<std::shared_ptr<TupleData>>(&a.data)) {
    return same_elements((*t)->elements, b.As<std::shared_ptr<TupleData>>()->elements);
  }
  if (const auto* l = std::get_if<std::shared_ptr<ListData>>(&a.data)) {
    return same_elements((*l)->elements, b.As<std::shared_ptr<ListData>>()->elements);
  }
  if (const auto* r = std::get_if<RegionPtr>(&a.data)) return *r == b.As<RegionPtr>();
  if (const auto* m = std::get_if<MeshRef>(&a.data)) {
    return m->mesh == b.As<MeshRef>().mesh && m->scale == b.As<MeshRef>().scale;
  }
  if (const auto* p = std::get_if<PrimitiveRef>(&a.data)) return p->kind == b.As<PrimitiveRef>().kind;
  return false;
}

}  // namespace prs::lang::internal
