// The resolver's driver: builds the class table (built-ins, then each module's classes in
// import order) and the set of global names per module, then runs the name checks and the
// creation planner (check_names.cc, plan.cc).
#include "lang/resolve.h"

#include <set>

#include "lang/resolve_internal.h"

namespace prs::lang {
namespace {

// Collects `self.NAME` reads in a class default expression.
void CollectSelfReads(const Expr& expr, std::vector<std::string>& reads);

void CollectSelfReadsIn(const ExprPtr& e, std::vector<std::string>& reads) {
  if (e) CollectSelfReads(*e, reads);
}

void CollectSelfReads(const Expr& expr, std::vector<std::string>& reads) {
  if (const auto* attr = std::get_if<AttributeExpr>(&expr.node)) {
    if (const auto* name = std::get_if<NameRef>(&attr->object->node); name && name->name == "self") {
      reads.push_back(attr->attribute.name);
      return;
    }
  }
  ForEachChild(expr, [&](const Expr& child) { CollectSelfReads(child, reads); });
}

ClassInfo* AddBuiltinClass(CompiledProgram& program, const std::string& name,
                           const ClassInfo* parent, std::vector<std::string> new_properties) {
  auto cls = std::make_unique<ClassInfo>();
  cls->name = name;
  cls->parent = parent;
  if (parent) {
    cls->defaults = parent->defaults;
    cls->has_orientation = parent->has_orientation;
    cls->has_box = parent->has_box;
  }
  for (std::string& property : new_properties) {
    PropertyDefault d;
    d.name = std::move(property);
    cls->defaults.push_back(std::move(d));
  }
  program.classes.push_back(std::move(cls));
  return program.classes.back().get();
}

void AddBuiltinClasses(CompiledProgram& program) {
  ClassInfo* point = AddBuiltinClass(program, "Point3D", nullptr, {"position"});
  ClassInfo* oriented =
      AddBuiltinClass(program, "OrientedPoint3D", point, {"orientation", "yaw", "pitch", "roll"});
  oriented->has_orientation = true;
  ClassInfo* object =
      AddBuiltinClass(program, "Object", oriented, {"width", "length", "height", "allowCollisions"});
  object->has_box = true;
}

// Defines one user class in module `m`'s class scope.
void DefineClass(CompiledProgram& program, int m, const ClassDef& def,
                 std::map<std::string, const ClassInfo*>& scope, DiagnosticEngine& diagnostics) {
  const ClassInfo* parent = scope.at("Object");
  if (def.parent) {
    auto it = scope.find(def.parent->name);
    if (it == scope.end()) {
      std::vector<std::string> names;
      for (const auto& [name, cls] : scope) names.push_back(name);
      const std::string suggestion = SuggestClosest(def.parent->name, names);
      diagnostics.Error("unknown-class", def.parent->span,
                        "unknown parent class '" + def.parent->name + "'" +
                            (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"),
                        suggestion);
    } else {
      parent = it->second;
    }
  }
  auto cls = std::make_unique<ClassInfo>();
  cls->name = def.name.name;
  cls->parent = parent;
  cls->span = def.name.span;
  cls->has_span = true;
  cls->has_orientation = parent->has_orientation;
  cls->has_box = parent->has_box;
  cls->defaults = parent->defaults;
  for (const PropertyDecl& decl : def.properties) {
    PropertyDefault value{decl.name.name, decl.default_value.get(), m, {}, decl.name.span};
    CollectSelfReadsIn(decl.default_value, value.self_reads);
    bool replaced = false;
    for (PropertyDefault& existing : cls->defaults) {
      if (existing.name == value.name) {
        existing = value;
        replaced = true;
      }
    }
    if (!replaced) cls->defaults.push_back(std::move(value));
  }
  scope[cls->name] = cls.get();
  program.classes.push_back(std::move(cls));
}

void BuildClassScopes(CompiledProgram& program, DiagnosticEngine& diagnostics) {
  std::map<std::string, const ClassInfo*> builtins;
  for (const auto& cls : program.classes) builtins[cls->name] = cls.get();
  program.class_scopes.assign(program.modules.size(), builtins);
  for (int m = 0; m < static_cast<int>(program.modules.size()); ++m) {
    auto& scope = program.class_scopes[m];
    for (const StmtPtr& stmt : program.modules[m]->ast.body) {
      if (const auto* import = std::get_if<FromImportStmt>(&stmt->node)) {
        auto it = program.import_targets.find(import);
        if (it == program.import_targets.end()) continue;
        for (const auto& entry : program.class_scopes[it->second]) scope.insert(entry);
      } else if (const auto* def = std::get_if<ClassDef>(&stmt->node)) {
        DefineClass(program, m, *def, scope, diagnostics);
      }
    }
  }
}

void MapImports(CompiledProgram& program, const std::map<std::string, int>& loaded) {
  for (const auto& module : program.modules) {
    for (const StmtPtr& stmt : module->ast.body) {
      if (const auto* import = std::get_if<FromImportStmt>(&stmt->node)) {
        auto it = loaded.find(import->module.name);
        if (it != loaded.end()) program.import_targets[import] = it->second;
      }
    }
  }
}

}  // namespace

namespace internal {

// Names bound at a module's (or function's) top level, descending into if/for/while blocks
// but not into nested functions.
void CollectBoundNames(const CompiledProgram& program, const std::vector<StmtPtr>& body,
                       std::set<std::string>& names) {
  for (const StmtPtr& stmt : body) {
    std::visit(
        [&](const auto& node) {
          using T = std::decay_t<decltype(node)>;
          if constexpr (std::is_same_v<T, AssignStmt>) {
            for (const Identifier& target : node.targets) names.insert(target.name);
          } else if constexpr (std::is_same_v<T, AugAssignStmt>) {
            names.insert(node.target.name);
          } else if constexpr (std::is_same_v<T, ClassDef> || std::is_same_v<T, FunctionDef>) {
            names.insert(node.name.name);
          } else if constexpr (std::is_same_v<T, ParamStmt>) {
            for (const auto& [name, value] : node.params) names.insert(name.name);
          } else if constexpr (std::is_same_v<T, ImportStmt>) {
            names.insert(node.module.name);
          } else if constexpr (std::is_same_v<T, FromImportStmt>) {
            auto it = program.import_targets.find(&node);
            if (it == program.import_targets.end()) return;
            const auto& inner = program.modules[it->second]->global_names;
            names.insert(inner.begin(), inner.end());
          } else if constexpr (std::is_same_v<T, ForStmt>) {
            for (const Identifier& target : node.targets) names.insert(target.name);
            CollectBoundNames(program, node.body, names);
          } else if constexpr (std::is_same_v<T, WhileStmt>) {
            CollectBoundNames(program, node.body, names);
          } else if constexpr (std::is_same_v<T, IfStmt>) {
            for (const auto& [condition, branch] : node.branches) {
              CollectBoundNames(program, branch, names);
            }
            CollectBoundNames(program, node.else_body, names);
          }
        },
        stmt->node);
  }
}

}  // namespace internal

bool ResolveProgram(CompiledProgram& program, const std::map<std::string, int>& loaded,
                    DiagnosticEngine& diagnostics) {
  MapImports(program, loaded);
  AddBuiltinClasses(program);
  BuildClassScopes(program, diagnostics);
  for (auto& module : program.modules) {
    std::set<std::string> names;
    internal::CollectBoundNames(program, module->ast.body, names);
    module->global_names.assign(names.begin(), names.end());
  }
  for (int m = 0; m < static_cast<int>(program.modules.size()); ++m) {
    internal::CheckModule(program, m, diagnostics);
  }
  for (const auto& cls : program.classes) {
    ObjectPlan plan;
    if (internal::BuildDefaultPlan(*cls, plan, diagnostics)) {
      program.default_plans.emplace(cls.get(), std::move(plan));
    }
  }
  if (!diagnostics.has_errors()) {
    internal::MarkOwnDrawSites(program, internal::MarkFixedPlacements(program));
  }
  return !diagnostics.has_errors();
}

}  // namespace prs::lang
