// Builds the static outline: creation sites from the plans (and bare class names used as
// statements), variable names from the assignments that bind them, region kinds from the
// position specifiers' syntax.
#include "analysis/scenario_outline.h"

#include <algorithm>
#include <map>

namespace prs::analysis {
namespace {

using lang::SpecifierKind;

// What the statement walk finds: names bound to creations, and bare class names creating
// default objects (`c = Cube`, or `Cube` alone).
struct StatementFindings {
  std::map<const lang::CreateObject*, std::string> variables;
  std::vector<CreationSite> class_ref_sites;
};

void WalkBody(const std::vector<lang::StmtPtr>& body, const lang::CompiledProgram& program,
              int module_index, StatementFindings& found);

void NoteClassRef(const lang::Expr& value, std::optional<std::string> variable,
                  const lang::CompiledProgram& program, int module_index,
                  StatementFindings& found) {
  const auto* ref = std::get_if<lang::ClassRef>(&value.node);
  if (!ref || module_index >= int(program.class_scopes.size())) return;
  const auto& scope = program.class_scopes[module_index];
  const auto cls = scope.find(ref->name);
  if (cls == scope.end()) return;
  const auto plan = program.default_plans.find(cls->second);
  CreationSite site{{value.span.file, value.span.begin}, ref->name, std::move(variable), {}, ""};
  if (plan != program.default_plans.end()) {
    site.position_region = DescribePositionRegion(plan->second, program.sources);
  }
  found.class_ref_sites.push_back(std::move(site));
}

void NoteAssignment(const lang::AssignStmt& assign, const lang::CompiledProgram& program,
                    int module_index, StatementFindings& found) {
  if (!assign.value || assign.is_tuple_unpack || assign.targets.size() != 1) return;
  const std::string& name = assign.targets.front().name;
  if (const auto* create = std::get_if<lang::CreateObject>(&assign.value->node)) {
    found.variables.emplace(create, name);
  }
  NoteClassRef(*assign.value, name, program, module_index, found);
}

void WalkStatement(const lang::Stmt& stmt, const lang::CompiledProgram& program, int module_index,
                   StatementFindings& found) {
  std::visit(
      [&](const auto& node) {
        using T = std::decay_t<decltype(node)>;
        if constexpr (std::is_same_v<T, lang::AssignStmt>) {
          NoteAssignment(node, program, module_index, found);
        } else if constexpr (std::is_same_v<T, lang::ExprStmt>) {
          if (node.expr) NoteClassRef(*node.expr, std::nullopt, program, module_index, found);
        } else if constexpr (std::is_same_v<T, lang::IfStmt>) {
          for (const auto& branch : node.branches)
            WalkBody(branch.second, program, module_index, found);
          WalkBody(node.else_body, program, module_index, found);
        } else if constexpr (std::is_same_v<T, lang::ForStmt> ||
                             std::is_same_v<T, lang::WhileStmt> ||
                             std::is_same_v<T, lang::FunctionDef>) {
          WalkBody(node.body, program, module_index, found);
        }
      },
      stmt.node);
}

void WalkBody(const std::vector<lang::StmtPtr>& body, const lang::CompiledProgram& program,
              int module_index, StatementFindings& found) {
  for (const lang::StmtPtr& stmt : body) {
    if (stmt) WalkStatement(*stmt, program, module_index, found);
  }
}

std::vector<CreationSite> CollectSites(const lang::CompiledProgram& program) {
  StatementFindings found;
  for (size_t m = 0; m < program.modules.size(); ++m) {
    WalkBody(program.modules[m]->ast.body, program, static_cast<int>(m), found);
  }
  std::vector<CreationSite> sites = std::move(found.class_ref_sites);
  for (const auto& [create, plan] : program.plans) {
    CreationSite site{{create->class_name.span.file, create->class_name.span.begin},
                      create->class_name.name,
                      std::nullopt,
                      {},
                      ""};
    if (const auto variable = found.variables.find(create); variable != found.variables.end()) {
      site.variable = variable->second;
    }
    for (const lang::Specifier* s : plan.position_specifiers) {
      site.position_specifiers.emplace_back(lang::SpecifierName(s->kind));
    }
    site.position_region = DescribePositionRegion(plan, program.sources);
    sites.push_back(std::move(site));
  }
  std::sort(sites.begin(), sites.end(),
            [](const CreationSite& a, const CreationSite& b) { return a.key < b.key; });
  return sites;
}

// A parent's default that the class inherits unchanged is not the class's own property.
std::vector<std::string> ListOwnProperties(const lang::ClassInfo& cls) {
  std::vector<std::string> own;
  for (const lang::PropertyDefault& d : cls.defaults) {
    const lang::PropertyDefault* inherited = cls.parent ? cls.parent->FindDefault(d.name) : nullptr;
    if (d.expr && (!inherited || inherited->expr != d.expr)) own.push_back(d.name);
  }
  return own;
}

std::vector<ClassOutline> CollectClasses(const lang::CompiledProgram& program) {
  std::vector<ClassOutline> classes;
  for (const auto& cls : program.classes) {
    if (!cls->has_span) continue;  // built-in
    classes.push_back(
        {cls->name, cls->parent ? cls->parent->name : "", cls->span, ListOwnProperties(*cls)});
  }
  return classes;
}

// `on V3D(...)`, `on (top back t) - V3D(...)`: expressions that are certainly vectors or
// oriented points. A plain name may hold either a vector or an object; it counts as a surface.
bool IsVectorShaped(const lang::Expr& e) {
  if (const auto* call = std::get_if<lang::CallExpr>(&e.node)) {
    const auto* callee = call->callee ? std::get_if<lang::NameRef>(&call->callee->node) : nullptr;
    return callee && (callee->name == "V3D" || callee->name == "Vector3D");
  }
  if (const auto* unary = std::get_if<lang::UnaryExpr>(&e.node)) {
    return unary->operand && IsVectorShaped(*unary->operand);
  }
  if (const auto* binary = std::get_if<lang::BinaryExpr>(&e.node)) {
    const bool arithmetic =
        binary->op == lang::BinaryOp::kAdd || binary->op == lang::BinaryOp::kSub ||
        binary->op == lang::BinaryOp::kMul || binary->op == lang::BinaryOp::kDiv;
    return arithmetic && ((binary->lhs && IsVectorShaped(*binary->lhs)) ||
                          (binary->rhs && IsVectorShaped(*binary->rhs)));
  }
  if (const auto* attribute = std::get_if<lang::AttributeExpr>(&e.node)) {
    return attribute->attribute.name == "position";
  }
  return std::holds_alternative<lang::SidePointExpr>(e.node) ||
         std::holds_alternative<lang::RelativeToExpr>(e.node) ||
         std::holds_alternative<lang::OffsetByExpr>(e.node);
}

// How an `in` region is named in the outline: `Cuboid(...)` for a constructor call, else its
// source text, shortened.
std::string NameGivenRegion(const lang::Expr& e, const lang::SourceManager& sources) {
  constexpr size_t kMaxLength = 30;
  if (const auto* call = std::get_if<lang::CallExpr>(&e.node)) {
    const auto* callee = call->callee ? std::get_if<lang::NameRef>(&call->callee->node) : nullptr;
    if (callee) return callee->name + "(...)";
  }
  if (e.span.file >= sources.file_count()) return "region";
  std::string text(sources.text(e.span.file).substr(e.span.begin, e.span.end - e.span.begin));
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text.size() > kMaxLength ? text.substr(0, kMaxLength - 3) + "..." : text;
}

// A specifier's target as written (an arm's or camera's name), shortened.
std::string Target(const lang::Specifier& s, const lang::SourceManager& sources) {
  return s.target ? NameGivenRegion(*s.target, sources) : "?";
}

// The parts of a position region, counted as the specifiers contribute them.
struct RegionParts {
  bool point = false;
  int planes = 0;
  int half_spaces = 0;
  std::vector<std::string> given_regions;  // `in R`: R's source text

  void Add(const lang::Specifier& s, const lang::SourceManager& sources) {
    switch (s.kind) {
      case SpecifierKind::kAt:
      case SpecifierKind::kBeyond:
        point = true;
        break;
      case SpecifierKind::kOn:
      case SpecifierKind::kCompletelyOn:
        if (s.kind == SpecifierKind::kOn && s.target && IsVectorShaped(*s.target)) {
          point = true;
        } else {
          ++planes;
          half_spaces += 2;  // the surface's edges bound it
        }
        break;
      case SpecifierKind::kIn:
        given_regions.push_back(s.target ? NameGivenRegion(*s.target, sources) : "region");
        break;
      case SpecifierKind::kAlignedWith:
        ++planes;
        break;
      case SpecifierKind::kReachableBy:
        given_regions.push_back("the set reachable by " + Target(s, sources));
        break;
      case SpecifierKind::kInViewOf:
      case SpecifierKind::kCompletelyInViewOf:
      case SpecifierKind::kVisibleFrom:
      case SpecifierKind::kCompletelyVisibleFrom:
        given_regions.push_back("the view of " + Target(s, sources));
        break;
      case SpecifierKind::kNotInViewOf:
        given_regions.push_back("outside the view of " + Target(s, sources));
        break;
      case SpecifierKind::kNotVisibleFrom:
        break;  // a line-of-sight test once the scene is complete, not a region
      default:
        if (lang::IsSideSpecifier(s.kind)) ++half_spaces;
        break;
    }
  }

  std::vector<std::string> Names(bool workspace) const {
    std::vector<std::string> names = given_regions;
    if (planes > 0) names.push_back(planes == 1 ? "plane" : std::to_string(planes) + " planes");
    if (half_spaces > 0) names.push_back(half_spaces == 1 ? "half-space" : "half-spaces");
    if (workspace) names.push_back("workspace");
    return names;
  }
};

std::string Join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : separator) + part;
  return text;
}

}  // namespace

std::string DescribePositionRegion(const lang::ObjectPlan& plan,
                                   const lang::SourceManager& sources) {
  if (plan.position_specifiers.empty()) return "class default";
  RegionParts parts;
  for (const lang::Specifier* s : plan.position_specifiers) parts.Add(*s, sources);
  if (parts.point) {
    const std::vector<std::string> checks = parts.Names(false);
    return checks.empty() ? "point" : "point, checked against " + Join(checks, " ∩ ");
  }
  return "region (" + Join(parts.Names(plan.fold_workspace), " ∩ ") + ")";
}

ScenarioOutline OutlineScenario(const lang::CompiledProgram& program) {
  return {CollectSites(program), CollectClasses(program)};
}

}  // namespace prs::analysis
