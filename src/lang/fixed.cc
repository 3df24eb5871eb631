// Which creation sites are fixed: the same in every scene. A compile-time analysis over the
// modules in execution order. A value is fixed when it is computed, at the top level of a
// module, from literals, fixed names and deterministic built-ins only; anything random,
// any user-function call, anything inside a loop, branch or function is not. The sampler uses
// the result to cut fixed obstacles out of fixed position regions (placement_fixed.cc), which
// is exact because the fraction cut away is then the same in every scene.
#include <map>
#include <set>

#include "lang/builtins.h"
#include "lang/resolve_internal.h"

namespace prs::lang::internal {
namespace {

enum class Kind { kUnknown, kNumber, kVector, kObject, kRegion, kOther };

struct Info {
  bool fixed = false;
  Kind kind = Kind::kUnknown;
};

constexpr Info kRandom{false, Kind::kUnknown};

bool IsDeterministicBuiltin(Builtin id) {
  switch (id) {
    case Builtin::kRange: case Builtin::kDiscreteRange: case Builtin::kNormal:
    case Builtin::kTruncatedNormal: case Builtin::kUniform: case Builtin::kOptions:
    case Builtin::kDiscrete: case Builtin::kResample:
      return false;
    default:
      return true;
  }
}

Kind BuiltinResultKind(Builtin id) {
  switch (id) {
    case Builtin::kVector3D: return Kind::kVector;
    case Builtin::kCuboid: case Builtin::kRect3D: case Builtin::kHalfSpace:
    case Builtin::kConvexPolygon3D: case Builtin::kConvexPolyhedron: case Builtin::kSphere:
    case Builtin::kAll: case Builtin::kEmpty:
      return Kind::kRegion;
    default:
      return Kind::kOther;
  }
}

Kind AttributeKind(const std::string& name) {
  if (name == "position") return Kind::kVector;
  static const char* kNumbers[] = {"x", "y", "z", "width", "length", "height", "yaw", "pitch", "roll"};
  for (const char* n : kNumbers) {
    if (name == n) return Kind::kNumber;
  }
  return Kind::kUnknown;
}

class FixedAnalysis {
 public:
  explicit FixedAnalysis(CompiledProgram& program)
      : program_(program), envs_(program.modules.size()), done_(program.modules.size(), false) {}

  void Run() { RunModule(program_.main_module); }

  // Per module, the names whose value after the module ran is the same in every scene.
  std::vector<std::set<std::string>> FixedNames() const {
    std::vector<std::set<std::string>> names(envs_.size());
    for (size_t m = 0; m < envs_.size(); ++m) {
      for (const auto& [name, info] : envs_[m]) {
        if (info.fixed) names[m].insert(name);
      }
    }
    return names;
  }

 private:
  using Env = std::map<std::string, Info>;

  void RunModule(int m) {
    if (done_[m]) return;
    done_[m] = true;
    for (const StmtPtr& stmt : program_.modules[m]->ast.body) TopLevel(*stmt, m);
  }

  void TopLevel(const Stmt& stmt, int m) {
    Env& env = envs_[m];
    std::visit(
        [&](const auto& node) {
          using T = std::decay_t<decltype(node)>;
          if constexpr (std::is_same_v<T, ExprStmt>) {
            Analyze(*node.expr, m, /*top_level_creation=*/true);
          } else if constexpr (std::is_same_v<T, AssignStmt>) {
            const Info value = Analyze(*node.value, m, !node.is_tuple_unpack);
            for (const Identifier& target : node.targets) {
              env[target.name] = node.is_tuple_unpack ? kRandom : value;
            }
          } else if constexpr (std::is_same_v<T, AugAssignStmt>) {
            const Info value = Analyze(*node.value, m, false);
            Info& target = env[node.target.name];
            target = {target.fixed && value.fixed, target.kind};
          } else if constexpr (std::is_same_v<T, ParamStmt>) {
            for (const auto& [name, expr] : node.params) {
              env[name.name] = expr ? Analyze(*expr, m, false) : Info{true, Kind::kOther};
            }
          } else if constexpr (std::is_same_v<T, ClassDef> || std::is_same_v<T, FunctionDef>) {
            env[node.name.name] = Info{true, Kind::kOther};
          } else if constexpr (std::is_same_v<T, ImportStmt>) {
            env[node.module.name] = Info{true, Kind::kOther};
          } else if constexpr (std::is_same_v<T, FromImportStmt>) {
            auto it = program_.import_targets.find(&node);
            if (it == program_.import_targets.end()) return;
            RunModule(it->second);
            for (const auto& [name, info] : envs_[it->second]) env[name] = info;
          } else if constexpr (std::is_same_v<T, IfStmt> || std::is_same_v<T, ForStmt> ||
                               std::is_same_v<T, WhileStmt>) {
            // What a block binds depends on how often and whether it ran: not fixed.
            std::set<std::string> bound;
            CollectBlockNames(node, bound);
            for (const std::string& name : bound) env[name] = kRandom;
          }
        },
        stmt.node);
  }

  template <typename Block>
  void CollectBlockNames(const Block& node, std::set<std::string>& bound) {
    if constexpr (std::is_same_v<Block, IfStmt>) {
      for (const auto& [condition, body] : node.branches) CollectBoundNames(program_, body, bound);
      CollectBoundNames(program_, node.else_body, bound);
    } else {
      if constexpr (std::is_same_v<Block, ForStmt>) {
        for (const Identifier& t : node.targets) bound.insert(t.name);
      }
      CollectBoundNames(program_, node.body, bound);
    }
  }

  Info Lookup(const std::string& name, int m) const {
    // `self` appears only in class defaults, whose `self.NAME` reads DefaultFixed checks.
    if (name == "self") return {true, Kind::kObject};
    auto it = envs_[m].find(name);
    if (it != envs_[m].end()) return it->second;
    if (FindGlobalBuiltin(name)) return Info{true, Kind::kOther};
    return kRandom;
  }

  // `creation_ok`: the expression is a whole top-level statement's value, so an object it
  // creates is created exactly once per scene.
  Info Analyze(const Expr& expr, int m, bool creation_ok) {
    return std::visit([&](const auto& node) { return AnalyzeNode(node, expr, m, creation_ok); },
                      expr.node);
  }

  Info AllFixed(std::initializer_list<const Expr*> parts, int m, Kind kind) {
    bool fixed = true;
    for (const Expr* part : parts) fixed = fixed && part && Analyze(*part, m, false).fixed;
    return {fixed, kind};
  }

  Info AnalyzeNode(const NumberLit&, const Expr&, int, bool) { return {true, Kind::kNumber}; }
  Info AnalyzeNode(const StringLit&, const Expr&, int, bool) { return {true, Kind::kOther}; }
  Info AnalyzeNode(const BoolLit&, const Expr&, int, bool) { return {true, Kind::kOther}; }
  Info AnalyzeNode(const NoneLit&, const Expr&, int, bool) { return {true, Kind::kOther}; }
  Info AnalyzeNode(const NameRef& node, const Expr&, int m, bool) { return Lookup(node.name, m); }
  // A tuple of two numbers is a uniform range wherever a number is expected.
  Info AnalyzeNode(const TupleExpr&, const Expr&, int, bool) { return kRandom; }
  Info AnalyzeNode(const ListExpr& node, const Expr&, int m, bool) {
    bool fixed = true;
    for (const ExprPtr& e : node.elements) fixed = fixed && Analyze(*e, m, false).fixed;
    return {fixed, Kind::kOther};
  }
  Info AnalyzeNode(const DictExpr& node, const Expr&, int m, bool) {
    bool fixed = true;
    for (const auto& [k, v] : node.entries) {
      fixed = fixed && Analyze(*k, m, false).fixed && Analyze(*v, m, false).fixed;
    }
    return {fixed, Kind::kOther};
  }
  Info AnalyzeNode(const UnaryExpr& node, const Expr&, int m, bool) {
    const Info operand = Analyze(*node.operand, m, false);
    return {operand.fixed, node.op == UnaryOp::kNot ? Kind::kOther : operand.kind};
  }
  Info AnalyzeNode(const BinaryExpr& node, const Expr&, int m, bool) {
    const Info lhs = Analyze(*node.lhs, m, false), rhs = Analyze(*node.rhs, m, false);
    Kind kind = Kind::kOther;
    const bool arithmetic = node.op == BinaryOp::kAdd || node.op == BinaryOp::kSub ||
                            node.op == BinaryOp::kMul || node.op == BinaryOp::kDiv;
    if (arithmetic && (lhs.kind == Kind::kVector || rhs.kind == Kind::kVector)) {
      kind = Kind::kVector;
    } else if (arithmetic && lhs.kind == Kind::kNumber && rhs.kind == Kind::kNumber) {
      kind = Kind::kNumber;
    }
    return {lhs.fixed && rhs.fixed, kind};
  }
  Info AnalyzeNode(const CompareChain& node, const Expr&, int m, bool) {
    bool fixed = true;
    for (const ExprPtr& e : node.operands) fixed = fixed && Analyze(*e, m, false).fixed;
    return {fixed, Kind::kOther};
  }
  Info AnalyzeNode(const ConditionalExpr& node, const Expr&, int m, bool) {
    const Info a = Analyze(*node.then_value, m, false), b = Analyze(*node.else_value, m, false);
    const bool fixed = Analyze(*node.condition, m, false).fixed && a.fixed && b.fixed;
    return {fixed, a.kind == b.kind ? a.kind : Kind::kUnknown};
  }
  Info AnalyzeNode(const CallExpr& node, const Expr&, int m, bool);
  Info AnalyzeNode(const AttributeExpr& node, const Expr&, int m, bool) {
    const Info object = Analyze(*node.object, m, false);
    return {object.fixed, AttributeKind(node.attribute.name)};
  }
  Info AnalyzeNode(const IndexExpr& node, const Expr&, int m, bool) {
    return AllFixed({node.object.get(), node.index.get()}, m, Kind::kUnknown);
  }
  Info AnalyzeNode(const SidePointExpr& node, const Expr&, int m, bool) {
    return {Analyze(*node.object, m, false).fixed, Kind::kVector};
  }
  Info AnalyzeNode(const RelativeToExpr& node, const Expr&, int m, bool) {
    return AllFixed({node.value.get(), node.base.get()}, m, Kind::kUnknown);
  }
  Info AnalyzeNode(const OffsetByExpr& node, const Expr&, int m, bool) {
    return AllFixed({node.value.get(), node.offset.get()}, m, Kind::kUnknown);
  }
  Info AnalyzeNode(const DistanceExpr& node, const Expr&, int m, bool) {
    return AllFixed({node.from.get(), node.to.get()}, m, Kind::kNumber);
  }
  Info AnalyzeNode(const ClassRef&, const Expr&, int, bool) { return {false, Kind::kObject}; }
  Info AnalyzeNode(const CreateObject& node, const Expr&, int m, bool creation_ok);

  bool SpecifierArgumentsFixed(const Specifier& s, int m) {
    for (const ExprPtr* e : {&s.target, &s.distance, &s.from}) {
      if (*e && !Analyze(**e, m, false).fixed) return false;
    }
    for (const SpecifierOption& option : s.options) {
      if (!Analyze(*option.value, m, false).fixed) return false;
    }
    return true;
  }

  // The position is one point (not drawn from a region) when a specifier gives a point.
  bool PositionIsPoint(const ObjectPlan& plan, int m) {
    if (plan.position_specifiers.empty()) return true;  // the class's default position
    for (const Specifier* s : plan.position_specifiers) {
      const bool point_kind = s->kind == SpecifierKind::kAt || s->kind == SpecifierKind::kBeyond ||
                              s->kind == SpecifierKind::kWith;
      if (point_kind) return true;
      if (s->kind == SpecifierKind::kOn && Analyze(*s->target, m, false).kind == Kind::kVector) {
        return true;
      }
    }
    return false;
  }

  bool StepFixed(const PlanStep& step, const std::map<std::string, bool>& props, int m);
  bool DefaultFixed(const PropertyDefault& d, const std::map<std::string, bool>& props);
  void MarkPlan(ObjectPlan& plan, int m);
  static bool AllButPositionFixed(const ObjectPlan& plan, const std::map<std::string, bool>& props);

  CompiledProgram& program_;
  std::vector<Env> envs_;
  std::vector<bool> done_;
};

Info FixedAnalysis::AnalyzeNode(const CallExpr& node, const Expr&, int m, bool) {
  bool fixed = true;
  for (const CallArg& arg : node.args) fixed = fixed && Analyze(*arg.value, m, false).fixed;
  if (const auto* name = std::get_if<NameRef>(&node.callee->node)) {
    if (envs_[m].count(name->name)) return kRandom;  // a user function, class or rebinding
    const BuiltinInfo* builtin = FindGlobalBuiltin(name->name);
    if (!builtin || !IsDeterministicBuiltin(builtin->id)) return kRandom;
    // Sphere() with no arguments is a shape, not a region.
    if (builtin->id == Builtin::kSphere && node.args.empty()) return {fixed, Kind::kOther};
    return {fixed, BuiltinResultKind(builtin->id)};
  }
  if (const auto* attribute = std::get_if<AttributeExpr>(&node.callee->node)) {
    const auto* module = std::get_if<NameRef>(&attribute->object->node);
    if (module && module->name == "math" && FindMathBuiltin(attribute->attribute.name)) {
      return {fixed && Lookup("math", m).fixed, Kind::kNumber};
    }
  }
  return kRandom;
}

Info FixedAnalysis::AnalyzeNode(const CreateObject& node, const Expr&, int m, bool creation_ok) {
  auto it = program_.plans.find(&node);
  if (it == program_.plans.end()) return kRandom;
  for (const Specifier& s : node.specifiers) {
    for (const ExprPtr* e : {&s.target, &s.distance, &s.from}) {
      if (*e) Analyze(**e, m, false);  // visits nested creations (never fixed)
    }
    for (const SpecifierOption& option : s.options) Analyze(*option.value, m, false);
  }
  if (!creation_ok) return {false, Kind::kObject};
  MarkPlan(it->second, m);
  return {it->second.object_fixed, Kind::kObject};
}

bool FixedAnalysis::DefaultFixed(const PropertyDefault& d,
                                 const std::map<std::string, bool>& props) {
  if (!d.expr) return true;  // a built-in default
  for (const std::string& read : d.self_reads) {
    auto it = props.find(read);
    if (it == props.end() || !it->second) return false;
  }
  return Analyze(*d.expr, d.module_index, false).fixed;
}

bool FixedAnalysis::StepFixed(const PlanStep& step, const std::map<std::string, bool>& props,
                              int m) {
  switch (step.kind) {
    case PlanStepKind::kDefault:
      return DefaultFixed(*step.default_value, props);
    case PlanStepKind::kWith:
      return Analyze(*step.specifier->target, m, false).fixed;
    case PlanStepKind::kOrientation: {
      for (const char* angle : {"yaw", "pitch", "roll"}) {
        auto it = props.find(angle);
        if (it != props.end() && !it->second) return false;
      }
      if (!step.specifier) return true;
      if (step.specifier->kind == SpecifierKind::kFacingToward) {
        auto it = props.find("position");
        if (it == props.end() || !it->second) return false;
      }
      return Analyze(*step.specifier->target, m, false).fixed;
    }
    case PlanStepKind::kPosition:
      return false;  // decided by MarkPlan
  }
  return false;
}

void FixedAnalysis::MarkPlan(ObjectPlan& plan, int m) {
  std::map<std::string, bool> props;
  bool region_inputs_fixed = true;
  for (const PlanStep& step : plan.steps) {
    if (step.kind != PlanStepKind::kPosition) {
      props[step.property] = StepFixed(step, props, m);
      continue;
    }
    if (plan.position_specifiers.empty()) {
      region_inputs_fixed = step.default_value ? DefaultFixed(*step.default_value, props) : true;
    } else {
      for (const Specifier* s : plan.position_specifiers) {
        region_inputs_fixed = region_inputs_fixed && SpecifierArgumentsFixed(*s, m);
      }
    }
    props["position"] = region_inputs_fixed && PositionIsPoint(plan, m);
  }
  bool shape_fixed = true;
  for (const char* p : {"width", "length", "height", "orientation", "allowCollisions"}) {
    auto it = props.find(p);
    shape_fixed = shape_fixed && (it == props.end() || it->second);
  }
  // The region is folded with the module's workspace as bound here (placement.cc): the same in
  // every scene only when that is.
  const auto workspace = envs_[m].find("workspace");
  const bool workspace_fixed = workspace == envs_[m].end() || workspace->second.fixed;
  plan.region_fixed = plan.fold_workspace && shape_fixed && region_inputs_fixed && workspace_fixed;
  bool all_fixed = true;
  for (const auto& [name, fixed] : props) all_fixed = all_fixed && fixed;
  plan.object_fixed = all_fixed;
  plan.template_fixed = !all_fixed && plan.open_turn == ObjectPlan::OpenTurn::kNone &&
                        AllButPositionFixed(plan, props);
}

// Whether every step but the position is fixed, and the steps after the position set only
// properties the placement never reads (so a template made after all steps places the same).
bool FixedAnalysis::AllButPositionFixed(const ObjectPlan& plan,
                                        const std::map<std::string, bool>& props) {
  // (allowCollisions is read from the object's field, which only FinishObject sets.)
  static const std::set<std::string> kReadByPlacement = {
      "width", "length", "height", "orientation", "yaw", "pitch", "roll", "shape"};
  bool has_position = false;
  for (const PlanStep& step : plan.steps) {
    if (step.kind == PlanStepKind::kPosition) {
      has_position = true;
      continue;
    }
    if (!props.at(step.property)) return false;
    if (has_position && kReadByPlacement.count(step.property)) return false;
  }
  return has_position;
}

}  // namespace

std::vector<std::set<std::string>> MarkFixedPlacements(CompiledProgram& program) {
  FixedAnalysis analysis(program);
  analysis.Run();
  return analysis.FixedNames();
}

}  // namespace prs::lang::internal
