// ClassifyRequirement: the naive-mode reason for a failed `require`, from the expression's form.
#include "lang/requirement_form.h"

#include <string_view>

namespace prs::lang {
namespace {

bool IsComparison(BinaryOp op) {
  switch (op) {
    case BinaryOp::kEq: case BinaryOp::kNe: case BinaryOp::kLt:
    case BinaryOp::kLe: case BinaryOp::kGt: case BinaryOp::kGe: return true;
    default: return false;
  }
}

// True when EXPR, or anything inside it, reads where something is.
bool ReadsPosition(const Expr& expr) {
  if (std::holds_alternative<DistanceExpr>(expr.node)) return true;
  if (const auto* attribute = std::get_if<AttributeExpr>(&expr.node)) {
    const std::string_view name = attribute->attribute.name;
    if (name == "x" || name == "y" || name == "z" || name == "position") return true;
  }
  bool found = false;
  ForEachChild(expr, [&](const Expr& child) { found = found || ReadsPosition(child); });
  return found;
}

bool IsContainsCall(const CallExpr& call) {
  const auto* callee = call.callee ? std::get_if<AttributeExpr>(&call.callee->node) : nullptr;
  return callee && callee->attribute.name == "contains";
}

}  // namespace

RejectionKind ClassifyRequirement(const Expr& condition) {
  if (const auto* call = std::get_if<CallExpr>(&condition.node)) {
    return IsContainsCall(*call) ? RejectionKind::kContainment : RejectionKind::kRequirement;
  }
  if (const auto* chain = std::get_if<CompareChain>(&condition.node)) {
    for (const ExprPtr& operand : chain->operands) {
      if (operand && ReadsPosition(*operand)) return RejectionKind::kRelativePosition;
    }
    return RejectionKind::kRequirement;
  }
  const auto* binary = std::get_if<BinaryExpr>(&condition.node);
  if (!binary || !binary->lhs || !binary->rhs) return RejectionKind::kRequirement;
  if (binary->op == BinaryOp::kIn) return RejectionKind::kContainment;
  if (IsComparison(binary->op)) {
    return ReadsPosition(*binary->lhs) || ReadsPosition(*binary->rhs)
               ? RejectionKind::kRelativePosition
               : RejectionKind::kRequirement;
  }
  if (binary->op == BinaryOp::kAnd || binary->op == BinaryOp::kOr) {
    const RejectionKind lhs = ClassifyRequirement(*binary->lhs);
    return lhs == ClassifyRequirement(*binary->rhs) ? lhs : RejectionKind::kRequirement;
  }
  return RejectionKind::kRequirement;
}

}  // namespace prs::lang
