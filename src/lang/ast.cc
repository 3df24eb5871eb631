// Spellings of AST enums, for messages and debugging output.
#include "lang/ast.h"

namespace prs::lang {

std::string_view SideName(Side side) {
  switch (side) {
    case Side::kFront: return "front";
    case Side::kBack: return "back";
    case Side::kLeft: return "left";
    case Side::kRight: return "right";
    case Side::kTop: return "top";
    case Side::kBottom: return "bottom";
    case Side::kFrontLeft: return "front left";
    case Side::kFrontRight: return "front right";
    case Side::kBackLeft: return "back left";
    case Side::kBackRight: return "back right";
    case Side::kTopFront: return "top front";
    case Side::kTopBack: return "top back";
  }
  return "?";
}

bool IsSideSpecifier(SpecifierKind kind) {
  return kind == SpecifierKind::kLeftOf || kind == SpecifierKind::kRightOf ||
         kind == SpecifierKind::kAheadOf || kind == SpecifierKind::kBehind ||
         kind == SpecifierKind::kAbove || kind == SpecifierKind::kBelow;
}

bool IsViewSpecifier(SpecifierKind kind) {
  return kind == SpecifierKind::kInViewOf || kind == SpecifierKind::kCompletelyInViewOf ||
         kind == SpecifierKind::kVisibleFrom || kind == SpecifierKind::kCompletelyVisibleFrom ||
         kind == SpecifierKind::kNotInViewOf || kind == SpecifierKind::kNotVisibleFrom;
}

std::string_view SpecifierName(SpecifierKind kind) {
  switch (kind) {
    case SpecifierKind::kWith: return "with";
    case SpecifierKind::kAt: return "at";
    case SpecifierKind::kIn: return "in";
    case SpecifierKind::kOn: return "on";
    case SpecifierKind::kCompletelyOn: return "completely on";
    case SpecifierKind::kLeftOf: return "left of";
    case SpecifierKind::kRightOf: return "right of";
    case SpecifierKind::kAheadOf: return "ahead of";
    case SpecifierKind::kBehind: return "behind";
    case SpecifierKind::kAbove: return "above";
    case SpecifierKind::kBelow: return "below";
    case SpecifierKind::kAlignedWith: return "aligned with";
    case SpecifierKind::kBeyond: return "beyond";
    case SpecifierKind::kFacing: return "facing";
    case SpecifierKind::kFacingToward: return "facing toward";
    case SpecifierKind::kReachableBy: return "reachable by";
    case SpecifierKind::kInViewOf: return "in view of";
    case SpecifierKind::kCompletelyInViewOf: return "completely in view of";
    case SpecifierKind::kVisibleFrom: return "visible from";
    case SpecifierKind::kCompletelyVisibleFrom: return "completely visible from";
    case SpecifierKind::kNotInViewOf: return "not in view of";
    case SpecifierKind::kNotVisibleFrom: return "not visible from";
  }
  return "?";
}

std::string_view BinaryOpName(BinaryOp op) {
  switch (op) {
    case BinaryOp::kAdd: return "+";
    case BinaryOp::kSub: return "-";
    case BinaryOp::kMul: return "*";
    case BinaryOp::kDiv: return "/";
    case BinaryOp::kFloorDiv: return "//";
    case BinaryOp::kMod: return "%";
    case BinaryOp::kPow: return "**";
    case BinaryOp::kEq: return "==";
    case BinaryOp::kNe: return "!=";
    case BinaryOp::kLt: return "<";
    case BinaryOp::kLe: return "<=";
    case BinaryOp::kGt: return ">";
    case BinaryOp::kGe: return ">=";
    case BinaryOp::kAnd: return "and";
    case BinaryOp::kOr: return "or";
    case BinaryOp::kIn: return "in";
    case BinaryOp::kNotIn: return "not in";
    case BinaryOp::kIs: return "is";
    case BinaryOp::kIsNot: return "is not";
  }
  return "?";
}

}  // namespace prs::lang
