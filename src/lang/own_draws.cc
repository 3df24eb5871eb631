// Which creation sites make an object that is a function of its own draws alone: a
// compile-time analysis beside the fixed-site one (fixed.cc), over every creation, in loops
// too. A site qualifies when everything its specifiers and its class's defaults read is the
// same in every scene — literals, built-ins, `math`, `self`, and module names that are fixed
// (MarkFixedPlacements) and bound only by top-level statements before the site (so
// `workspace = ...` after `from model import *` is read as the fixed value it has from then
// on) — and it creates nothing and
// calls no user function; its specifiers are among those that only place the object (not
// `visible from` or `reachable by`, which register checks for later), and the module's
// `workspace`, which placement reads unnamed, is fixed too. Sites inside functions
// never qualify: a local may shadow a module name. The Gibbs sampler (sampling/gibbs.h) runs a
// program many times at points that differ in one object's numbers; such objects are then
// copied from the previous run instead of made again (RunOptions::reuse_objects).
#include <climits>
#include <map>
#include <set>

#include "lang/builtins.h"
#include "lang/resolve_internal.h"

namespace prs::lang::internal {
namespace {

class OwnDrawAnalysis {
 public:
  OwnDrawAnalysis(CompiledProgram& program, const std::vector<std::set<std::string>>& fixed)
      : program_(program),
        fixed_(fixed),
        stable_(program.modules.size()),
        bound_(program.modules.size()) {}

  void Run() {
    for (size_t m = 0; m < program_.modules.size(); ++m) FindStableNames(static_cast<int>(m));
    for (size_t m = 0; m < program_.modules.size(); ++m) {
      visiting_module_ = static_cast<int>(m);
      const std::vector<StmtPtr>& body = program_.modules[m]->ast.body;
      for (size_t i = 0; i < body.size(); ++i) {
        visiting_statement_ = static_cast<int>(i);
        VisitStmt(*body[i], static_cast<int>(m));
      }
    }
  }

 private:
  // Names fixed after the module ran and bound only by its top-level statements, in no block,
  // each with the last of those statements: from there on (to the module's end and after it)
  // the name holds the value it ends with, so sites after it read that fixed value. (Sites
  // before it may see an earlier value, which need not be fixed: they do not qualify.)
  void FindStableNames(int m) {
    std::map<std::string, int> last_binding;  // the top-level statement that binds it last
    std::set<std::string> in_blocks;
    const std::vector<StmtPtr>& body = program_.modules[m]->ast.body;
    for (size_t i = 0; i < body.size(); ++i) {
      auto bind = [&](const std::string& name) { last_binding[name] = static_cast<int>(i); };
      std::visit(
          [&](const auto& node) {
            using T = std::decay_t<decltype(node)>;
            if constexpr (std::is_same_v<T, AssignStmt>) {
              for (const Identifier& t : node.targets) bind(t.name);
            } else if constexpr (std::is_same_v<T, AugAssignStmt>) {
              bind(node.target.name);
            } else if constexpr (std::is_same_v<T, ClassDef> || std::is_same_v<T, FunctionDef>) {
              bind(node.name.name);
            } else if constexpr (std::is_same_v<T, ParamStmt>) {
              for (const auto& [name, value] : node.params) bind(name.name);
            } else if constexpr (std::is_same_v<T, ImportStmt>) {
              bind(node.module.name);
            } else if constexpr (std::is_same_v<T, FromImportStmt>) {
              auto it = program_.import_targets.find(&node);
              if (it == program_.import_targets.end()) return;
              // Bound here to whatever the module left it as (fixed_ says whether that is
              // the same in every scene).
              for (const std::string& name : program_.modules[it->second]->global_names) {
                bind(name);
              }
            } else if constexpr (std::is_same_v<T, ForStmt>) {
              for (const Identifier& t : node.targets) in_blocks.insert(t.name);
              CollectBoundNames(program_, node.body, in_blocks);
            } else if constexpr (std::is_same_v<T, WhileStmt>) {
              CollectBoundNames(program_, node.body, in_blocks);
            } else if constexpr (std::is_same_v<T, IfStmt>) {
              for (const auto& [condition, body] : node.branches) {
                CollectBoundNames(program_, body, in_blocks);
              }
              CollectBoundNames(program_, node.else_body, in_blocks);
            }
          },
          body[i]->node);
    }
    for (const auto& [name, statement] : last_binding) {
      bound_[m].insert(name);
      if (!in_blocks.count(name) && fixed_[m].count(name)) stable_[m][name] = statement;
    }
    for (const std::string& name : in_blocks) bound_[m].insert(name);
  }

  void VisitStmt(const Stmt& stmt, int m) {
    std::visit(
        [&](const auto& node) {
          using T = std::decay_t<decltype(node)>;
          if constexpr (std::is_same_v<T, ExprStmt>) {
            VisitExpr(*node.expr, m);
          } else if constexpr (std::is_same_v<T, AssignStmt> || std::is_same_v<T, AugAssignStmt>) {
            VisitExpr(*node.value, m);
          } else if constexpr (std::is_same_v<T, ForStmt>) {
            VisitExpr(*node.iterable, m);
            for (const StmtPtr& s : node.body) VisitStmt(*s, m);
          } else if constexpr (std::is_same_v<T, WhileStmt>) {
            VisitExpr(*node.condition, m);
            for (const StmtPtr& s : node.body) VisitStmt(*s, m);
          } else if constexpr (std::is_same_v<T, IfStmt>) {
            for (const auto& [condition, body] : node.branches) {
              VisitExpr(*condition, m);
              for (const StmtPtr& s : body) VisitStmt(*s, m);
            }
            for (const StmtPtr& s : node.else_body) VisitStmt(*s, m);
          }
          // Function bodies are skipped (their sites never qualify); requirements and the
          // rest create nothing that matters here.
        },
        stmt.node);
  }

  // Finds creation sites in an expression (nested ones too) and marks each.
  void VisitExpr(const Expr& expr, int m) {
    if (const auto* create = std::get_if<CreateObject>(&expr.node)) Mark(*create, m);
    ForEachChild(expr, [&](const Expr& child) { VisitExpr(child, m); });
  }

  void Mark(const CreateObject& create, int m) {
    auto it = program_.plans.find(&create);
    if (it == program_.plans.end()) return;
    ObjectPlan& plan = it->second;
    // Placement reads the module's `workspace` without naming it (it bounds the region).
    bool pure = !bound_[m].count("workspace") || IsStableName("workspace", m);
    for (const Specifier& s : create.specifiers) {
      pure = pure && static_cast<int>(s.kind) <= static_cast<int>(SpecifierKind::kFacingToward);
      for (const ExprPtr* e : {&s.target, &s.distance, &s.from}) {
        pure = pure && (!*e || IsPure(**e, m));
      }
      for (const SpecifierOption& option : s.options) pure = pure && IsPure(*option.value, m);
    }
    for (const PlanStep& step : plan.steps) {
      if (step.default_value && step.default_value->expr) {
        pure = pure && IsPure(*step.default_value->expr, step.default_value->module_index);
      }
    }
    plan.own_draws_only = pure;
  }

  // Whether evaluating `expr` in module m reads only what is the same in every scene (its
  // random draws aside) and has no effect but drawing.
  bool IsPure(const Expr& expr, int m) {
    if (std::holds_alternative<CreateObject>(expr.node) ||
        std::holds_alternative<ClassRef>(expr.node)) {
      return false;  // makes an object
    }
    if (const auto* name = std::get_if<NameRef>(&expr.node)) return IsStableName(name->name, m);
    if (const auto* call = std::get_if<CallExpr>(&expr.node)) {
      bool callee_ok = false;
      if (const auto* name = std::get_if<NameRef>(&call->callee->node)) {
        callee_ok = !bound_[m].count(name->name) && FindGlobalBuiltin(name->name);
      } else if (const auto* attribute = std::get_if<AttributeExpr>(&call->callee->node)) {
        const auto* module = std::get_if<NameRef>(&attribute->object->node);
        callee_ok = module && module->name == "math" && IsStableName("math", m) &&
                    FindMathBuiltin(attribute->attribute.name);
      }
      if (!callee_ok) return false;
      for (const CallArg& arg : call->args) {
        if (!IsPure(*arg.value, m)) return false;
      }
      return true;
    }
    bool pure = true;
    ForEachChild(expr, [&](const Expr& child) { pure = pure && IsPure(child, m); });
    return pure;
  }

  // In the site's own module, a name is read as the site's statement runs: after its last
  // binding it stays; a class default evaluated in another module reads that module's final
  // value (it ran to its end first).
  bool IsStableName(const std::string& name, int m) const {
    if (name == "self") return true;
    if (auto it = stable_[m].find(name); it != stable_[m].end()) {
      const int reading = m == visiting_module_ ? visiting_statement_ : INT_MAX;
      return it->second < reading;
    }
    return !bound_[m].count(name) && FindGlobalBuiltin(name);
  }

  CompiledProgram& program_;
  const std::vector<std::set<std::string>>& fixed_;
  // Per module: stable names, each with the top-level statement that binds it last.
  std::vector<std::map<std::string, int>> stable_;
  std::vector<std::set<std::string>> bound_;  // per module: every name bound anywhere at its level
  int visiting_module_ = -1;                  // the module and top-level statement of the
  int visiting_statement_ = -1;               // sites being marked
};

}  // namespace

void MarkOwnDrawSites(CompiledProgram& program, const std::vector<std::set<std::string>>& fixed) {
  OwnDrawAnalysis(program, fixed).Run();
}

}  // namespace prs::lang::internal
