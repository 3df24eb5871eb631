// Test helper: prints an AST as a compact S-expression so tests can compare node shapes.
#pragma once

#include <fmt/format.h>

#include <string>

#include "lang/ast.h"

namespace prs::lang::testing {

std::string Dump(const Expr& e);
std::string Dump(const Stmt& s);

inline std::string DumpOpt(const ExprPtr& e) { return e ? Dump(*e) : "null"; }

inline std::string DumpList(const std::vector<ExprPtr>& v) {
  std::string out;
  for (const ExprPtr& e : v) out += " " + Dump(*e);
  return out;
}

inline std::string DumpBlock(const std::vector<StmtPtr>& v) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i) out += (i ? " " : "") + Dump(*v[i]);
  return out + "]";
}

inline std::string DumpSpecifier(const Specifier& s) {
  std::string out = fmt::format("({}", SpecifierName(s.kind));
  if (s.property) out += " " + s.property->name;
  out += " " + DumpOpt(s.target);
  if (s.distance) out += " by " + Dump(*s.distance);
  if (s.from) out += " from " + Dump(*s.from);
  if (s.axis) out += " axis " + s.axis->name;
  return out + ")";
}

inline std::string Dump(const Expr& e) {
  return std::visit(
      [](const auto& n) -> std::string {
        using T = std::decay_t<decltype(n)>;
        if constexpr (std::is_same_v<T, NumberLit>) return fmt::format("{}", n.value);
        else if constexpr (std::is_same_v<T, StringLit>) return fmt::format("\"{}\"", n.value);
        else if constexpr (std::is_same_v<T, BoolLit>) return n.value ? "True" : "False";
        else if constexpr (std::is_same_v<T, NoneLit>) return "None";
        else if constexpr (std::is_same_v<T, NameRef>) return n.name;
        else if constexpr (std::is_same_v<T, TupleExpr>) return "(tuple" + DumpList(n.elements) + ")";
        else if constexpr (std::is_same_v<T, ListExpr>) return "(list" + DumpList(n.elements) + ")";
        else if constexpr (std::is_same_v<T, DictExpr>) {
          std::string out = "(dict";
          for (const auto& [k, v] : n.entries) out += " " + Dump(*k) + ":" + Dump(*v);
          return out + ")";
        } else if constexpr (std::is_same_v<T, UnaryExpr>) {
          const char* op = n.op == UnaryOp::kNeg ? "neg" : n.op == UnaryOp::kPos ? "pos" : "not";
          return fmt::format("({} {})", op, Dump(*n.operand));
        } else if constexpr (std::is_same_v<T, BinaryExpr>) {
          return fmt::format("({} {} {})", BinaryOpName(n.op), Dump(*n.lhs), Dump(*n.rhs));
        } else if constexpr (std::is_same_v<T, CompareChain>) {
          std::string out = "(chain " + Dump(*n.operands[0]);
          for (size_t i = 0; i < n.ops.size(); ++i) {
            out += fmt::format(" {} {}", BinaryOpName(n.ops[i]), Dump(*n.operands[i + 1]));
          }
          return out + ")";
        } else if constexpr (std::is_same_v<T, ConditionalExpr>) {
          return fmt::format("(if {} {} {})", Dump(*n.condition), Dump(*n.then_value),
                             Dump(*n.else_value));
        } else if constexpr (std::is_same_v<T, CallExpr>) {
          std::string out = "(call " + Dump(*n.callee);
          for (const CallArg& a : n.args) {
            out += " " + (a.keyword ? a.keyword->name + "=" : "") + Dump(*a.value);
          }
          return out + ")";
        } else if constexpr (std::is_same_v<T, AttributeExpr>) {
          return fmt::format("(. {} {})", Dump(*n.object), n.attribute.name);
        } else if constexpr (std::is_same_v<T, IndexExpr>) {
          return fmt::format("(index {} {})", Dump(*n.object), Dump(*n.index));
        } else if constexpr (std::is_same_v<T, SidePointExpr>) {
          return fmt::format("(side {} {})", SideName(n.side), Dump(*n.object));
        } else if constexpr (std::is_same_v<T, RelativeToExpr>) {
          return fmt::format("(relative {} {})", Dump(*n.value), Dump(*n.base));
        } else if constexpr (std::is_same_v<T, OffsetByExpr>) {
          return fmt::format("(offset {} {})", Dump(*n.value), Dump(*n.offset));
        } else if constexpr (std::is_same_v<T, DistanceExpr>) {
          return fmt::format("(distance {} {})", Dump(*n.from), Dump(*n.to));
        } else if constexpr (std::is_same_v<T, ClassRef>) {
          return "(class " + n.name + ")";
        } else {
          static_assert(std::is_same_v<T, CreateObject>);
          std::string out = "(create " + n.class_name.name;
          for (const Specifier& s : n.specifiers) out += " " + DumpSpecifier(s);
          return out + ")";
        }
      },
      e.node);
}

inline std::string DumpIdentifiers(const std::vector<Identifier>& ids) {
  std::string out;
  for (size_t i = 0; i < ids.size(); ++i) out += (i ? "," : "") + ids[i].name;
  return out;
}

inline std::string Dump(const Stmt& s) {
  return std::visit(
      [](const auto& n) -> std::string {
        using T = std::decay_t<decltype(n)>;
        if constexpr (std::is_same_v<T, ExprStmt>) return "(expr " + Dump(*n.expr) + ")";
        else if constexpr (std::is_same_v<T, AssignStmt>) {
          return fmt::format("(= {}{} {})", DumpIdentifiers(n.targets),
                             n.is_tuple_unpack ? " unpack" : "", Dump(*n.value));
        } else if constexpr (std::is_same_v<T, AugAssignStmt>) {
          return fmt::format("({}= {} {})", BinaryOpName(n.op), n.target.name, Dump(*n.value));
        } else if constexpr (std::is_same_v<T, ClassDef>) {
          std::string out = "(class " + n.name.name;
          if (n.parent) out += "(" + n.parent->name + ")";
          for (const PropertyDecl& p : n.properties) out += " " + p.name.name + ":" + Dump(*p.default_value);
          return out + ")";
        } else if constexpr (std::is_same_v<T, FunctionDef>) {
          std::string out = "(def " + n.name.name + " (";
          for (size_t i = 0; i < n.params.size(); ++i) {
            out += (i ? " " : "") + n.params[i].name.name;
            if (n.params[i].default_value) out += "=" + Dump(*n.params[i].default_value);
          }
          return out + ") " + DumpBlock(n.body) + ")";
        } else if constexpr (std::is_same_v<T, ReturnStmt>) {
          return "(return " + DumpOpt(n.value) + ")";
        } else if constexpr (std::is_same_v<T, IfStmt>) {
          std::string out = "(if";
          for (const auto& [c, b] : n.branches) out += " " + Dump(*c) + " " + DumpBlock(b);
          if (!n.else_body.empty()) out += " else " + DumpBlock(n.else_body);
          return out + ")";
        } else if constexpr (std::is_same_v<T, ForStmt>) {
          return fmt::format("(for {} {} {})", DumpIdentifiers(n.targets), Dump(*n.iterable),
                             DumpBlock(n.body));
        } else if constexpr (std::is_same_v<T, WhileStmt>) {
          return fmt::format("(while {} {})", Dump(*n.condition), DumpBlock(n.body));
        } else if constexpr (std::is_same_v<T, BreakStmt>) return "(break)";
        else if constexpr (std::is_same_v<T, ContinueStmt>) return "(continue)";
        else if constexpr (std::is_same_v<T, PassStmt>) return "(pass)";
        else if constexpr (std::is_same_v<T, RequireStmt>) {
          return fmt::format("(require{} {} {})", n.settled ? " settled" : "",
                             DumpOpt(n.probability), Dump(*n.condition));
        } else if constexpr (std::is_same_v<T, ParamStmt>) {
          std::string out = "(param";
          for (const auto& [name, v] : n.params) out += " " + name.name + "=" + Dump(*v);
          return out + ")";
        } else if constexpr (std::is_same_v<T, ImportStmt>) return "(import " + n.module.name + ")";
        else {
          static_assert(std::is_same_v<T, FromImportStmt>);
          return "(from " + n.module.name + ")";
        }
      },
      s.node);
}

}  // namespace prs::lang::testing
