// Static checks of one module: every name is bound somewhere visible (else "did you mean"),
// `self` only in class defaults, break/continue/return where they belong, and calls to
// built-ins and functions with the right number of arguments. Also plans object creations.
#include <set>

#include "lang/builtins.h"
#include "lang/resolve_internal.h"

namespace prs::lang::internal {
namespace {

class NameChecker {
 public:
  NameChecker(CompiledProgram& program, int m, DiagnosticEngine& diagnostics)
      : program_(program), m_(m), diagnostics_(diagnostics) {
    const ModuleInfo& module = *program.modules[m];
    globals_.insert(module.global_names.begin(), module.global_names.end());
    for (const StmtPtr& stmt : module.ast.body) {
      if (const auto* def = std::get_if<FunctionDef>(&stmt->node)) functions_[def->name.name] = def;
    }
  }

  void CheckBody(const std::vector<StmtPtr>& body) {
    for (const StmtPtr& stmt : body) CheckStmt(*stmt);
  }

 private:
  void CheckStmt(const Stmt& stmt);
  void CheckBlockStmt(const Stmt& stmt);
  void CheckFunction(const FunctionDef& def);
  void CheckClass(const ClassDef& def);
  void CheckExpr(const Expr& expr);
  void CheckName(const std::string& name, SourceSpan span);
  void CheckCall(const CallExpr& call, SourceSpan span);
  void CheckArity(const BuiltinInfo& info, const CallExpr& call, SourceSpan span);
  void CheckFunctionArity(const FunctionDef& def, const CallExpr& call, SourceSpan span);
  void CheckMathAttribute(const AttributeExpr& attr, bool called);
  void CheckCreate(const CreateObject& create);
  std::vector<std::string> VisibleNames() const;

  CompiledProgram& program_;
  int m_;
  DiagnosticEngine& diagnostics_;
  std::set<std::string> globals_;
  std::set<std::string> locals_;
  std::map<std::string, const FunctionDef*> functions_;
  const ClassInfo* self_class_ = nullptr;  // set while checking a class's defaults
  bool in_function_ = false;
  int loop_depth_ = 0;
};

void NameChecker::CheckStmt(const Stmt& stmt) {
  std::visit(
      [&](const auto& node) {
        using T = std::decay_t<decltype(node)>;
        if constexpr (std::is_same_v<T, ExprStmt>) {
          CheckExpr(*node.expr);
        } else if constexpr (std::is_same_v<T, AssignStmt>) {
          CheckExpr(*node.value);
        } else if constexpr (std::is_same_v<T, AugAssignStmt>) {
          CheckName(node.target.name, node.target.span);
          CheckExpr(*node.value);
        } else if constexpr (std::is_same_v<T, ClassDef>) {
          if (in_function_) {
            diagnostics_.Error("misplaced-definition", node.name.span,
                               "classes must be defined at the top level of a module");
          }
          CheckClass(node);
        } else if constexpr (std::is_same_v<T, FunctionDef>) {
          if (in_function_) {
            diagnostics_.Error("misplaced-definition", node.name.span,
                               "functions must be defined at the top level of a module");
            return;
          }
          CheckFunction(node);
        } else if constexpr (std::is_same_v<T, ReturnStmt>) {
          if (!in_function_) {
            diagnostics_.Error("misplaced-statement", stmt.span, "'return' outside a function");
          }
          if (node.value) CheckExpr(*node.value);
        } else if constexpr (std::is_same_v<T, BreakStmt> || std::is_same_v<T, ContinueStmt>) {
          if (loop_depth_ == 0) {
            diagnostics_.Error("misplaced-statement", stmt.span,
                               std::string(std::is_same_v<T, BreakStmt> ? "'break'" : "'continue'") +
                                   " outside a loop");
          }
        } else if constexpr (std::is_same_v<T, RequireStmt>) {
          CheckExpr(*node.condition);
          if (node.probability) CheckExpr(*node.probability);
        } else if constexpr (std::is_same_v<T, ParamStmt>) {
          for (const auto& [name, value] : node.params) CheckExpr(*value);
        } else if constexpr (std::is_same_v<T, ImportStmt>) {
          if (node.module.name != "math") {
            diagnostics_.Error("unknown-module", node.module.span,
                               "'import " + node.module.name +
                                   "' is not available: only 'import math' is; load a .prs "
                                   "module with 'from " + node.module.name + " import *'");
          }
        } else if constexpr (std::is_same_v<T, FromImportStmt>) {
          if (in_function_) {
            diagnostics_.Error("misplaced-statement", stmt.span,
                               "imports must be at the top level of a module");
          }
        } else {
          CheckBlockStmt(stmt);
        }
      },
      stmt.node);
}

// if / for / while (and pass).
void NameChecker::CheckBlockStmt(const Stmt& stmt) {
  if (const auto* node = std::get_if<IfStmt>(&stmt.node)) {
    for (const auto& [condition, body] : node->branches) {
      CheckExpr(*condition);
      CheckBody(body);
    }
    CheckBody(node->else_body);
  } else if (const auto* node = std::get_if<ForStmt>(&stmt.node)) {
    CheckExpr(*node->iterable);
    ++loop_depth_;
    CheckBody(node->body);
    --loop_depth_;
  } else if (const auto* node = std::get_if<WhileStmt>(&stmt.node)) {
    CheckExpr(*node->condition);
    ++loop_depth_;
    CheckBody(node->body);
    --loop_depth_;
  }
}

void NameChecker::CheckFunction(const FunctionDef& def) {
  std::set<std::string> locals;
  for (const Param& param : def.params) {
    if (param.default_value) CheckExpr(*param.default_value);
    locals.insert(param.name.name);
  }
  CollectBoundNames(program_, def.body, locals);
  locals_ = std::move(locals);
  in_function_ = true;
  const int saved_loops = loop_depth_;
  loop_depth_ = 0;
  CheckBody(def.body);
  loop_depth_ = saved_loops;
  in_function_ = false;
  locals_.clear();
}

void NameChecker::CheckClass(const ClassDef& def) {
  auto it = program_.class_scopes[m_].find(def.name.name);
  if (it == program_.class_scopes[m_].end()) return;
  self_class_ = it->second;
  for (const PropertyDecl& decl : def.properties) {
    CheckExpr(*decl.default_value);
  }
  self_class_ = nullptr;
}

void NameChecker::CheckExpr(const Expr& expr) {
  if (const auto* name = std::get_if<NameRef>(&expr.node)) {
    CheckName(name->name, expr.span);
    return;
  }
  if (const auto* call = std::get_if<CallExpr>(&expr.node)) {
    CheckCall(*call, expr.span);
  } else if (const auto* attr = std::get_if<AttributeExpr>(&expr.node)) {
    const auto* base = std::get_if<NameRef>(&attr->object->node);
    if (base && base->name == "math" && globals_.count("math") && !locals_.count("math")) {
      CheckMathAttribute(*attr, false);
    }
    if (base && base->name == "self" && self_class_ &&
        !self_class_->FindDefault(attr->attribute.name)) {
      std::vector<std::string> names;
      for (const PropertyDefault& d : self_class_->defaults) names.push_back(d.name);
      const std::string suggestion = SuggestClosest(attr->attribute.name, names);
      diagnostics_.Error("unknown-property", attr->attribute.span,
                         "class '" + self_class_->name + "' has no property '" +
                             attr->attribute.name + "'" +
                             (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"),
                         suggestion);
    }
  } else if (const auto* create = std::get_if<CreateObject>(&expr.node)) {
    CheckCreate(*create);
  }
  ForEachChild(expr, [&](const Expr& child) { CheckExpr(child); });
}

void NameChecker::CheckName(const std::string& name, SourceSpan span) {
  if (name == "self") {
    if (!self_class_) {
      diagnostics_.Error("misplaced-self", span,
                         "'self' can only be used in a class's property defaults");
    }
    return;
  }
  if (locals_.count(name) || globals_.count(name) || FindGlobalBuiltin(name) ||
      program_.class_scopes[m_].count(name)) {
    return;
  }
  const std::string suggestion = SuggestClosest(name, VisibleNames());
  diagnostics_.Error("unknown-name", span,
                     "unknown name '" + name + "'" +
                         (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"),
                     suggestion);
}

std::vector<std::string> NameChecker::VisibleNames() const {
  std::vector<std::string> names(locals_.begin(), locals_.end());
  names.insert(names.end(), globals_.begin(), globals_.end());
  for (const BuiltinInfo& info : GlobalBuiltins()) names.push_back(info.name);
  for (const auto& [name, cls] : program_.class_scopes[m_]) names.push_back(name);
  return names;
}

void NameChecker::CheckCall(const CallExpr& call, SourceSpan span) {
  if (const auto* name = std::get_if<NameRef>(&call.callee->node)) {
    if (locals_.count(name->name)) return;
    auto fn = functions_.find(name->name);
    if (fn != functions_.end()) {
      CheckFunctionArity(*fn->second, call, span);
    } else if (!globals_.count(name->name)) {
      if (const BuiltinInfo* info = FindGlobalBuiltin(name->name)) CheckArity(*info, call, span);
    }
  } else if (const auto* attr = std::get_if<AttributeExpr>(&call.callee->node)) {
    const auto* base = std::get_if<NameRef>(&attr->object->node);
    if (base && base->name == "math" && globals_.count("math")) {
      if (const BuiltinInfo* info = FindMathBuiltin(attr->attribute.name)) {
        CheckArity(*info, call, span);
      }
    }
  }
}

void NameChecker::CheckArity(const BuiltinInfo& info, const CallExpr& call, SourceSpan span) {
  for (size_t i = 0; i < call.args.size(); ++i) {
    const CallArg& arg = call.args[i];
    // Mesh's scale may be named (`Mesh("mug.obj", scale=0.001)`), as the second argument.
    if (arg.keyword && info.id == Builtin::kMesh && arg.keyword->name == "scale" && i == 1) continue;
    if (arg.keyword && info.id == Builtin::kMesh) {
      diagnostics_.Error("bad-argument", arg.keyword->span,
                         "Mesh takes the file and then its scale, as in Mesh(\"mug.obj\", "
                         "scale=0.001); '" + arg.keyword->name + "' is not one of its arguments");
      return;
    }
    if (arg.keyword) {
      diagnostics_.Error("bad-argument", arg.keyword->span,
                         std::string(info.name) + " takes no keyword arguments; call it as " +
                             info.signature);
      return;
    }
  }
  const int n = static_cast<int>(call.args.size());
  const bool one_sphere_argument = info.id == Builtin::kSphere && n == 1;  // 0: shape, 2: region
  if (n >= info.min_args && (info.max_args < 0 || n <= info.max_args) && !one_sphere_argument) return;
  std::string expected = std::to_string(info.min_args);
  if (info.max_args < 0) expected = "at least " + expected;
  else if (one_sphere_argument) expected = "0 or 2";
  else if (info.max_args != info.min_args) expected += " to " + std::to_string(info.max_args);
  diagnostics_.Error("wrong-argument-count", span,
                     std::string(info.name) + " takes " + expected + " argument" +
                         (info.min_args == 1 && info.max_args == 1 ? "" : "s") + " (" +
                         info.signature + "), but " + std::to_string(n) +
                         (n == 1 ? " was" : " were") + " given");
}

void NameChecker::CheckFunctionArity(const FunctionDef& def, const CallExpr& call,
                                     SourceSpan span) {
  size_t positional = 0;
  std::set<std::string> given;
  for (const CallArg& arg : call.args) {
    if (!arg.keyword) {
      ++positional;
      continue;
    }
    bool known = false;
    for (const Param& p : def.params) known |= p.name.name == arg.keyword->name;
    if (!known) {
      diagnostics_.Error("bad-argument", arg.keyword->span,
                         "'" + def.name.name + "' has no parameter named '" + arg.keyword->name + "'");
    }
    given.insert(arg.keyword->name);
  }
  size_t required = 0;
  for (const Param& p : def.params) required += p.default_value ? 0 : 1;
  bool missing = false;
  for (size_t i = positional; i < def.params.size(); ++i) {
    missing |= !def.params[i].default_value && !given.count(def.params[i].name.name);
  }
  if (positional > def.params.size() || missing) {
    diagnostics_.Error("wrong-argument-count", span,
                       "'" + def.name.name + "' takes " + std::to_string(required) +
                           (required == def.params.size()
                                ? ""
                                : " to " + std::to_string(def.params.size())) +
                           " arguments, but " + std::to_string(call.args.size()) +
                           (call.args.size() == 1 ? " was" : " were") + " given");
  }
}

void NameChecker::CheckMathAttribute(const AttributeExpr& attr, bool /*called*/) {
  double constant = 0;
  const std::string& name = attr.attribute.name;
  if (FindMathBuiltin(name) || FindMathConstant(name, &constant)) return;
  std::vector<std::string> names{"pi", "e", "tau", "inf"};
  for (const BuiltinInfo& info : MathBuiltins()) names.push_back(info.name);
  const std::string suggestion = SuggestClosest(name, names);
  diagnostics_.Error("unknown-name", attr.attribute.span,
                     "module 'math' has no '" + name + "'" +
                         (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"),
                     suggestion);
}

void NameChecker::CheckCreate(const CreateObject& create) {
  auto it = program_.class_scopes[m_].find(create.class_name.name);
  if (it == program_.class_scopes[m_].end()) return;  // the parser already reported it
  ObjectPlan plan;
  if (BuildObjectPlan(create, *it->second, plan, diagnostics_)) {
    program_.plans.emplace(&create, std::move(plan));
  }
}

}  // namespace

void CheckModule(CompiledProgram& program, int m, DiagnosticEngine& diagnostics) {
  NameChecker checker(program, m, diagnostics);
  checker.CheckBody(program.modules[m]->ast.body);
}

}  // namespace prs::lang::internal
