// A generic visitor over an expression's direct children, so passes that only care about a
// few node kinds (tree heights, self-reads, name checks) need not list every other kind.
#include <algorithm>
#include <functional>

#include "lang/ast.h"

namespace prs::lang {
namespace {

void VisitIf(const ExprPtr& e, const std::function<void(const Expr&)>& visit) {
  if (e) visit(*e);
}

}  // namespace

void ForEachChild(const Expr& expr, const std::function<void(const Expr&)>& visit) {
  std::visit(
      [&](const auto& node) {
        using T = std::decay_t<decltype(node)>;
        if constexpr (std::is_same_v<T, TupleExpr> || std::is_same_v<T, ListExpr>) {
          for (const ExprPtr& e : node.elements) VisitIf(e, visit);
        } else if constexpr (std::is_same_v<T, DictExpr>) {
          for (const auto& [k, v] : node.entries) {
            VisitIf(k, visit);
            VisitIf(v, visit);
          }
        } else if constexpr (std::is_same_v<T, UnaryExpr>) {
          VisitIf(node.operand, visit);
        } else if constexpr (std::is_same_v<T, BinaryExpr>) {
          VisitIf(node.lhs, visit);
          VisitIf(node.rhs, visit);
        } else if constexpr (std::is_same_v<T, CompareChain>) {
          for (const ExprPtr& e : node.operands) VisitIf(e, visit);
        } else if constexpr (std::is_same_v<T, ConditionalExpr>) {
          VisitIf(node.condition, visit);
          VisitIf(node.then_value, visit);
          VisitIf(node.else_value, visit);
        } else if constexpr (std::is_same_v<T, CallExpr>) {
          VisitIf(node.callee, visit);
          for (const CallArg& arg : node.args) VisitIf(arg.value, visit);
        } else if constexpr (std::is_same_v<T, AttributeExpr>) {
          VisitIf(node.object, visit);
        } else if constexpr (std::is_same_v<T, IndexExpr>) {
          VisitIf(node.object, visit);
          VisitIf(node.index, visit);
        } else if constexpr (std::is_same_v<T, SidePointExpr>) {
          VisitIf(node.object, visit);
        } else if constexpr (std::is_same_v<T, RelativeToExpr>) {
          VisitIf(node.value, visit);
          VisitIf(node.base, visit);
        } else if constexpr (std::is_same_v<T, OffsetByExpr>) {
          VisitIf(node.value, visit);
          VisitIf(node.offset, visit);
        } else if constexpr (std::is_same_v<T, DistanceExpr>) {
          VisitIf(node.from, visit);
          VisitIf(node.to, visit);
        } else if constexpr (std::is_same_v<T, CreateObject>) {
          for (const Specifier& s : node.specifiers) {
            VisitIf(s.target, visit);
            VisitIf(s.distance, visit);
            VisitIf(s.from, visit);
            for (const SpecifierOption& option : s.options) VisitIf(option.value, visit);
          }
        }
      },
      expr.node);
}

uint32_t CalcExprHeight(const Expr& expr) {
  uint32_t tallest_child = 0;
  ForEachChild(expr,
               [&](const Expr& child) { tallest_child = std::max(tallest_child, child.height); });
  return tallest_child + 1;
}

}  // namespace prs::lang
