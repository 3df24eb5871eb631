// The abstract syntax tree of a .prs program: plain data (std::variant of node structs)
// produced by the parser and walked by later passes (resolver, interpreter).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "lang/source.h"

namespace prs::lang {

struct Expr;
struct Stmt;
using ExprPtr = std::unique_ptr<Expr>;
using StmtPtr = std::unique_ptr<Stmt>;

struct Identifier {
  std::string name;
  SourceSpan span;
};

// ---------------------------------------------------------------------------
// Expressions
// ---------------------------------------------------------------------------
struct NumberLit {
  double value;
};
struct StringLit {
  std::string value;  // already unescaped; adjacent literals concatenated
};
struct BoolLit {
  bool value;
};
struct NoneLit {};
struct NameRef {
  std::string name;
};
struct TupleExpr {  // (a, b), (a,), () and a bare `a, b` where Python allows one
  std::vector<ExprPtr> elements;
};
struct ListExpr {
  std::vector<ExprPtr> elements;
};
struct DictExpr {
  std::vector<std::pair<ExprPtr, ExprPtr>> entries;
};

enum class UnaryOp { kNeg, kPos, kNot };
struct UnaryExpr {
  UnaryOp op;
  ExprPtr operand;
};

enum class BinaryOp {
  kAdd, kSub, kMul, kDiv, kFloorDiv, kMod, kPow,
  kEq, kNe, kLt, kLe, kGt, kGe,
  kAnd, kOr, kIn, kNotIn, kIs, kIsNot
};
// A single comparison `a < b` is a BinaryExpr. A chain of two or more comparisons
// (`a < b < c`) is a CompareChain instead, so the middle operands are evaluated once
// (this matters for random values, which are drawn when evaluated).
struct BinaryExpr {
  BinaryOp op;
  ExprPtr lhs, rhs;
  SourceSpan op_span;
};
struct CompareChain {  // operands.size() == ops.size() + 1 >= 3; true when every pair holds
  std::vector<ExprPtr> operands;
  std::vector<BinaryOp> ops;
  std::vector<SourceSpan> op_spans;
};
struct ConditionalExpr {  // then_value if condition else else_value
  ExprPtr condition, then_value, else_value;
};
struct CallArg {
  std::optional<Identifier> keyword;  // f(x=1)
  ExprPtr value;
};
struct CallExpr {
  ExprPtr callee;
  std::vector<CallArg> args;
  SourceSpan paren_span;  // from '(' to ')' inclusive
};
struct AttributeExpr {  // a.b
  ExprPtr object;
  Identifier attribute;
};
struct IndexExpr {  // a[i]
  ExprPtr object;
  ExprPtr index;
};

// ProbRobScene operators.
enum class Side {
  kFront, kBack, kLeft, kRight, kTop, kBottom,
  kFrontLeft, kFrontRight, kBackLeft, kBackRight, kTopFront, kTopBack
};
struct SidePointExpr {  // `top back of t`, `(top back t)`, `front of X`
  Side side;
  ExprPtr object;
  SourceSpan keyword_span;  // the side word(s), e.g. `top back`
};
struct RelativeToExpr {  // value relative to base
  ExprPtr value, base;
};
struct OffsetByExpr {  // value offset by offset
  ExprPtr value, offset;
};
struct DistanceExpr {  // distance from A to B
  ExprPtr from, to;
};

// Object creation: a known class name followed by zero or more specifiers.
enum class SpecifierKind {
  kWith, kAt, kIn, kOn, kCompletelyOn, kLeftOf, kRightOf, kAheadOf, kBehind,
  kAbove, kBelow, kAlignedWith, kBeyond, kFacing, kFacingToward,
  // Robot- and camera-aware specifiers (spec §10).
  kReachableBy, kInViewOf, kCompletelyInViewOf, kVisibleFrom, kCompletelyVisibleFrom,
  kNotInViewOf, kNotVisibleFrom
};
struct SpecifierOption {  // `reachable by ARM with margin 0.02`: name "margin", value 0.02
  Identifier name;
  ExprPtr value;
};
struct Specifier {
  SpecifierKind kind;
  SourceSpan span;                    // the whole specifier, for carets
  std::optional<Identifier> property; // `with PROP value`
  ExprPtr target;    // the main argument (value for with/at; region/object/vector otherwise)
  ExprPtr distance;  // `by d` (left of/right of/ahead of/behind/above/below/beyond), may be null
  ExprPtr from;      // `beyond X by d from Y`
  std::optional<Identifier> axis;  // aligned with X on|along x|y|z, or by "x" (the string's span)
  std::vector<SpecifierOption> options;  // `reachable by`: with margin|approach|grasp VALUE
};
struct ClassRef {  // a class name used with no specifiers
  std::string name;
};
struct CreateObject {
  Identifier class_name;
  std::vector<Specifier> specifiers;  // at least one
};

struct Expr {
  SourceSpan span;
  std::variant<NumberLit, StringLit, BoolLit, NoneLit, NameRef, TupleExpr, ListExpr, DictExpr,
               UnaryExpr, BinaryExpr, ConditionalExpr, CallExpr, AttributeExpr, IndexExpr,
               SidePointExpr, RelativeToExpr, OffsetByExpr, DistanceExpr, ClassRef,
               CreateObject, CompareChain>
      node;
  /// The height of this subtree: 1 for a leaf, one more than the tallest child otherwise. The
  /// parser keeps it under a limit, which bounds every later recursive walk over the tree.
  uint32_t height = 1;
};

// ---------------------------------------------------------------------------
// Statements
// ---------------------------------------------------------------------------
struct ExprStmt {
  ExprPtr expr;
};
struct AssignStmt {  // a = e ; a, b = e ; (a, b) = e
  std::vector<Identifier> targets;
  bool is_tuple_unpack;
  ExprPtr value;
};
struct AugAssignStmt {  // a += e (op is kAdd, kSub, kMul or kDiv)
  Identifier target;
  BinaryOp op;
  ExprPtr value;
};
struct PropertyDecl {  // `name: default_value` inside a class body
  Identifier name;
  ExprPtr default_value;
};
struct ClassDef {
  Identifier name;
  std::optional<Identifier> parent;
  std::vector<PropertyDecl> properties;
};
struct Param {
  Identifier name;
  ExprPtr default_value;  // may be null
};
struct FunctionDef {
  Identifier name;
  std::vector<Param> params;
  std::vector<StmtPtr> body;
};
struct ReturnStmt {
  ExprPtr value;  // may be null
};
struct IfStmt {  // if/elif branches in order, then else
  std::vector<std::pair<ExprPtr, std::vector<StmtPtr>>> branches;
  std::vector<StmtPtr> else_body;
};
struct ForStmt {
  std::vector<Identifier> targets;  // `for a in` -> 1, `for a, b in` -> 2 (unpacking)
  ExprPtr iterable;
  std::vector<StmtPtr> body;
};
struct WhileStmt {
  ExprPtr condition;
  std::vector<StmtPtr> body;
};
struct BreakStmt {};
struct ContinueStmt {};
struct PassStmt {};
struct RequireStmt {
  ExprPtr condition;
  ExprPtr probability;  // null for a hard requirement
  bool settled = false;  // `require settled`: checked on the scene at rest (--settle)
};
struct ParamStmt {
  std::vector<std::pair<Identifier, ExprPtr>> params;
};
struct ImportStmt {  // import math
  Identifier module;
};
struct FromImportStmt {  // from NAME import *   (NAME is a plain name, not dotted)
  Identifier module;
};

struct Stmt {
  SourceSpan span;
  std::variant<ExprStmt, AssignStmt, AugAssignStmt, ClassDef, FunctionDef, ReturnStmt, IfStmt,
               ForStmt, WhileStmt, BreakStmt, ContinueStmt, PassStmt, RequireStmt, ParamStmt,
               ImportStmt, FromImportStmt>
      node;
};

struct Module {
  FileId file = 0;
  std::vector<StmtPtr> body;
};

/// Calls `visit` on each direct child expression of `expr` (specifier arguments included).
void ForEachChild(const Expr& expr, const std::function<void(const Expr&)>& visit);
/// Returns 1 + the largest `height` among `expr`'s direct children (1 for a leaf).
uint32_t CalcExprHeight(const Expr& expr);

/// Returns the source spelling of a side, e.g. "top back".
std::string_view SideName(Side side);
/// Returns the source spelling of a specifier's keywords, e.g. "completely on".
std::string_view SpecifierName(SpecifierKind kind);
/// left of, right of, ahead of, behind, above, below: a half-space beside the target.
bool IsSideSpecifier(SpecifierKind kind);
/// in view of, completely in view of, visible from, ... (a camera as the target).
bool IsViewSpecifier(SpecifierKind kind);
/// Returns the source spelling of a binary operator, e.g. "not in".
std::string_view BinaryOpName(BinaryOp op);

}  // namespace prs::lang
