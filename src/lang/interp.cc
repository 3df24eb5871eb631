// The interpreter's statement layer: runs modules (imports once per attempt), binds names,
// executes control flow within the run limits, and turns requirements into rejections.
#include <cmath>
#include <stdexcept>

#include "lang/interp_internal.h"
#include "lang/requirement_form.h"

namespace prs::lang {

AttemptResult RunAttempt(const CompiledProgram& program, geometry::Rng& rng,
                         const RunOptions& options) {
  internal::Interpreter interpreter(program, rng, options);
  return interpreter.Run();
}

const char* RejectionKindName(RejectionKind kind) {
  switch (kind) {
    case RejectionKind::kCollision: return "collision";
    case RejectionKind::kRequirement: return "requirement";
    case RejectionKind::kWorkspace: return "workspace";
    case RejectionKind::kEmptyRegion: return "empty-region";
    case RejectionKind::kOutsideRegion: return "outside-region";
    case RejectionKind::kRelativePosition: return "relative-position";
    case RejectionKind::kContainment: return "containment";
    case RejectionKind::kOccluded: return "occluded";
    case RejectionKind::kVisible: return "visible";
    case RejectionKind::kUnstable: return "unstable";
    case RejectionKind::kUnsettled: return "unsettled";
  }
  return "unknown";
}

namespace internal {

Interpreter::Interpreter(const CompiledProgram& program, geometry::Rng& rng,
                         const RunOptions& options)
    : program_(program), rng_(rng), options_(options),
      module_envs_(program.modules.size()), module_ran_(program.modules.size(), false),
      module_shared_(program.modules.size(), false),
      imports_unshared_(program.modules.size(), false) {
  // Most programs create each creation site's object once: room for that without regrowing.
  scene_.objects.reserve(program.plans.size());
  completed_.reserve(program.plans.size());
}

AttemptResult Interpreter::Run() {
  try {
    RunModule(program_.main_module);
    CheckWorkspace();
    CheckSightLines();
    if (naive_violation_) throw RejectSignal{std::move(*naive_violation_)};
  } catch (RejectSignal& signal) {
    signal.rejection.certain = draws_ == 0;
    return std::move(signal.rejection);
  } catch (const std::logic_error& e) {
    // A geometry constructor refused a value no check caught earlier (e.g. a huge number):
    // still a located error, never an abort.
    Fail(current_statement_, "bad-value", std::string("this statement computes a value the "
                                                      "geometry cannot use: ") + e.what());
  }
  return std::move(scene_);
}

void Interpreter::RunModule(int module_index) {
  if (module_ran_[module_index]) return;
  module_ran_[module_index] = true;
  const bool cacheable = options_.cache && module_index != program_.main_module;
  if (cacheable) {
    auto it = options_.cache->module_globals.find(module_index);
    if (it != options_.cache->module_globals.end()) {
      module_envs_[module_index].shared = &it->second;
      module_shared_[module_index] = true;
      return;
    }
  }
  const int64_t draws_before = draws_;
  const size_t objects_before = scene_.objects.size(), params_before = scene_.params.size();
  const int saved = current_module_;
  current_module_ = module_index;
  ExecBody(program_.modules[module_index]->ast.body);
  current_module_ = saved;
  if (stopped_) return;  // a probe run ended inside this module: it did not run to its end
  // A module that imports an unshared one may hold its draws (`from random import *`).
  if (!cacheable || draws_ != draws_before || scene_.objects.size() != objects_before ||
      scene_.params.size() != params_before || imports_unshared_[module_index]) {
    return;
  }
  Env globals = module_envs_[module_index].Flatten();
  if (!IsSameInEveryScene(globals)) return;
  // Scenes carry these regions (Scene::workspace) to other threads: fill their lazily
  // computed caches now, so that reading them there races with nothing.
  for (const auto& [name, value] : globals) {
    if (!value.Is<RegionPtr>()) continue;
    value.As<RegionPtr>()->Finalize();
    options_.cache->kept_regions.insert(value.As<RegionPtr>().get());
  }
  const Env& kept = options_.cache->module_globals[module_index] = std::move(globals);
  module_envs_[module_index] = ModuleEnv{&kept, {}};
  module_shared_[module_index] = true;
}

// Whether a value can be shared by later scenes: not one that a scene can change (lists,
// dicts), that refers to this scene's objects, or that remembers a draw (tuples).
bool Interpreter::IsSameInEveryScene(const Value& value) {
  return std::visit(
      [](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        return !std::is_same_v<T, ObjectRef> && !std::is_same_v<T, BoundMethod> &&
               !std::is_same_v<T, std::shared_ptr<TupleData>> &&
               !std::is_same_v<T, std::shared_ptr<ListData>> &&
               !std::is_same_v<T, std::shared_ptr<DictData>>;
      },
      value.data);
}

bool Interpreter::IsSameInEveryScene(const Env& env) {
  for (const auto& [name, value] : env) {
    if (!IsSameInEveryScene(value)) return false;
  }
  return true;
}

Flow Interpreter::ExecBody(const std::vector<StmtPtr>& body) {
  if (!body.empty()) EnterNested(body.front()->span);
  Flow flow = Flow::kNormal;
  for (const StmtPtr& stmt : body) {
    flow = Exec(*stmt);
    if (stopped_) flow = Flow::kStop;
    if (flow != Flow::kNormal) break;
  }
  if (!body.empty()) --eval_depth_;
  return flow;
}

Flow Interpreter::Exec(const Stmt& stmt) {
  current_statement_ = stmt.span;
  if (const auto* node = std::get_if<ExprStmt>(&stmt.node)) {
    EvalStatementValue(*node->expr);
  } else if (const auto* node = std::get_if<AssignStmt>(&stmt.node)) {
    ExecAssign(*node, stmt.span);
  } else if (const auto* node = std::get_if<AugAssignStmt>(&stmt.node)) {
    Value current = Lookup(node->target.name, node->target.span);
    Bind(node->target.name, EvalBinary(node->op, current, Eval(*node->value), stmt.span));
  } else if (const auto* node = std::get_if<ClassDef>(&stmt.node)) {
    Bind(node->name.name, program_.class_scopes[current_module_].at(node->name.name));
  } else if (const auto* node = std::get_if<FunctionDef>(&stmt.node)) {
    Bind(node->name.name, FunctionRef{node, current_module_});
  } else if (const auto* node = std::get_if<ReturnStmt>(&stmt.node)) {
    return_value_ = node->value ? Eval(*node->value) : Value();
    return Flow::kReturn;
  } else if (const auto* node = std::get_if<IfStmt>(&stmt.node)) {
    for (const auto& [condition, body] : node->branches) {
      if (Truthy(Eval(*condition), condition->span)) return ExecBody(body);
    }
    return ExecBody(node->else_body);
  } else if (const auto* node = std::get_if<ForStmt>(&stmt.node)) {
    return ExecFor(*node, stmt.span);
  } else if (const auto* node = std::get_if<WhileStmt>(&stmt.node)) {
    return ExecWhile(*node, stmt.span);
  } else if (std::holds_alternative<BreakStmt>(stmt.node)) {
    return Flow::kBreak;
  } else if (std::holds_alternative<ContinueStmt>(stmt.node)) {
    return Flow::kContinue;
  } else if (const auto* node = std::get_if<RequireStmt>(&stmt.node)) {
    ExecRequire(*node, stmt.span);
  } else if (const auto* node = std::get_if<ParamStmt>(&stmt.node)) {
    ExecParam(*node);
  } else if (const auto* node = std::get_if<ImportStmt>(&stmt.node)) {
    Bind(node->module.name, ModuleRef{0});
  } else if (const auto* node = std::get_if<FromImportStmt>(&stmt.node)) {
    const int target = program_.import_targets.at(node);
    RunModule(target);
    if (stopped_) return Flow::kStop;
    if (!module_shared_[target]) imports_unshared_[current_module_] = true;
    const ModuleEnv& from = module_envs_[target];
    ModuleEnv& into = module_envs_[current_module_];
    if (into.empty() && from.own.empty()) {
      into.shared = from.shared;  // the same values, not copied
    } else {
      for (const auto& [name, value] : from.Flatten()) into.own[name] = value;
    }
  }
  return Flow::kNormal;
}

Flow Interpreter::ExecFor(const ForStmt& node, SourceSpan span) {
  // `for i in range(...)`: the numbers one at a time, no list made (a run that stops early, as
  // the probe runs of --sampler partial-rejection do, pays for the iterations it runs).
  if (node.targets.size() == 1) {
    if (const std::optional<NumberRange> range = EvalRangeCall(*node.iterable)) {
      for (int64_t i = 0; i < range->count; ++i) {
        CountLoopIteration(span);
        Bind(node.targets[0].name, range->At(i));
        const Flow flow = ExecBody(node.body);
        if (flow == Flow::kBreak) break;
        if (flow == Flow::kReturn || flow == Flow::kStop) return flow;
      }
      return Flow::kNormal;
    }
  }
  Value iterable = Eval(*node.iterable);
  // A list no name holds (`range(n)`, a list display) is taken, not copied.
  auto* list = std::get_if<std::shared_ptr<ListData>>(&iterable.data);
  const std::vector<Value> items = list && list->use_count() == 1
                                       ? std::move((*list)->elements)
                                       : Iterate(iterable, node.iterable->span);
  for (const Value& item : items) {
    CountLoopIteration(span);
    if (node.targets.size() == 1) {
      Bind(node.targets[0].name, item);
    } else {
      std::vector<Value> parts = Iterate(item, node.iterable->span);
      if (parts.size() != node.targets.size()) {
        Fail(node.targets.front().span, "bad-unpack",
             "cannot unpack " + std::to_string(parts.size()) + " values into " +
                 std::to_string(node.targets.size()) + " names");
      }
      for (size_t i = 0; i < parts.size(); ++i) Bind(node.targets[i].name, parts[i]);
    }
    const Flow flow = ExecBody(node.body);
    if (flow == Flow::kBreak) break;
    if (flow == Flow::kReturn || flow == Flow::kStop) return flow;
  }
  return Flow::kNormal;
}

Flow Interpreter::ExecWhile(const WhileStmt& node, SourceSpan span) {
  while (Truthy(Eval(*node.condition), node.condition->span)) {
    CountLoopIteration(span);
    const Flow flow = ExecBody(node.body);
    if (flow == Flow::kBreak) break;
    if (flow == Flow::kReturn || flow == Flow::kStop) return flow;
  }
  return Flow::kNormal;
}

void Interpreter::CountLoopIteration(SourceSpan span) {
  if (++loop_iterations_ > options_.limits.max_loop_iterations) {
    Fail(span, "limit-exceeded",
         "loops ran more than " + std::to_string(options_.limits.max_loop_iterations) +
             " iterations in one scene; is this loop meant to end?");
  }
}

void Interpreter::ExecAssign(const AssignStmt& node, SourceSpan span) {
  const bool creates = std::holds_alternative<lang::CreateObject>(node.value->node) ||
                       std::holds_alternative<ClassRef>(node.value->node);
  if (!node.is_tuple_unpack && creates) pending_name_ = &node.targets[0].name;
  Value value = EvalStatementValue(*node.value);
  pending_name_ = nullptr;
  if (!node.is_tuple_unpack) {
    if (const auto* object = std::get_if<ObjectRef>(&value.data)) {
      auto& name = scene_.objects[object->index].name;
      if (!name) name = node.targets[0].name;
    }
    Bind(node.targets[0].name, std::move(value));
    return;
  }
  std::vector<Value> parts = Iterate(value, node.value->span);
  if (parts.size() != node.targets.size()) {
    Fail(span, "bad-unpack",
         "cannot unpack " + std::to_string(parts.size()) + " values into " +
             std::to_string(node.targets.size()) + " names");
  }
  for (size_t i = 0; i < parts.size(); ++i) Bind(node.targets[i].name, parts[i]);
}

Value Interpreter::EvalStatementValue(const Expr& expr) {
  if (const auto* ref = std::get_if<ClassRef>(&expr.node)) {
    const ClassInfo* cls = program_.class_scopes[current_module_].at(ref->name);
    return CreateObject(program_.default_plans.at(cls), expr.span);
  }
  return Eval(expr);
}

void Interpreter::ExecRequire(const RequireStmt& node, SourceSpan span) {
  if (!options_.check_requirements) return;
  if (node.probability) {
    const double p = EvalNumber(*node.probability, "the probability of 'require[p]'");
    if (!(p >= 0 && p <= 1)) {
      Fail(node.probability->span, "bad-value",
           "a requirement's probability must be between 0 and 1, got " + FormatNumber(p));
    }
    if (DrawUniform(0, 1, node.probability->span, "require[p]") >= p) return;  // not enforced in this scene
  }
  if (node.settled) {
    RecordSettledRequirement(node, span);
    return;
  }
  if (Truthy(Eval(*node.condition), node.condition->span)) return;
  const LineColumn where = program_.sources.CalcLineColumn(span.file, span.begin);
  // Naive mode counts requirements as the paper's Table II does (lang/requirement_form.h).
  Reject(options_.mode == SamplingMode::kNaive ? ClassifyRequirement(*node.condition)
                                               : RejectionKind::kRequirement,
         "require at " + program_.sources.path(span.file) + ":" + std::to_string(where.line), span);
}

void Interpreter::ExecParam(const ParamStmt& node) {
  for (const auto& [name, expr] : node.params) {
    Value value;
    auto it = program_.param_overrides.find(name.name);
    if (it != program_.param_overrides.end()) {
      char* end = nullptr;
      const double number = std::strtod(it->second.c_str(), &end);
      value = (!it->second.empty() && *end == '\0') ? Value(number) : MakeString(it->second);
    } else {
      value = Eval(*expr);
    }
    Bind(name.name, value);
    bool replaced = false;
    for (auto& [existing, v] : scene_.params) {
      if (existing == name.name) {
        v = value;
        replaced = true;
      }
    }
    if (!replaced) scene_.params.emplace_back(name.name, value);
  }
}

void Interpreter::Bind(const std::string& name, Value value) {
  Env& env = locals_ ? *locals_ : module_envs_[current_module_].own;
  env[name] = std::move(value);
}

Value Interpreter::Lookup(const std::string& name, SourceSpan span) {
  if (name == "self" && self_index_ >= 0) return ObjectRef{self_index_};
  if (locals_) {
    auto it = locals_->find(name);
    if (it != locals_->end()) return it->second;
  }
  if (const Value* global = module_envs_[current_module_].Find(name)) return *global;
  if (const BuiltinInfo* info = FindGlobalBuiltin(name)) return BuiltinRef{info->id};
  const auto& classes = program_.class_scopes[current_module_];
  if (auto cls = classes.find(name); cls != classes.end()) return cls->second;
  Fail(span, "unbound-name",
       "'" + name + "' is used before it is given a value; assign it earlier in the program");
}

std::vector<Value> Interpreter::Iterate(const Value& v, SourceSpan span) {
  if (const auto* list = std::get_if<std::shared_ptr<ListData>>(&v.data)) return (*list)->elements;
  if (const auto* tuple = std::get_if<std::shared_ptr<TupleData>>(&v.data)) {
    return (*tuple)->elements;
  }
  if (const auto* dict = std::get_if<std::shared_ptr<DictData>>(&v.data)) {
    std::vector<Value> keys;
    for (const auto& [key, value] : (*dict)->entries) keys.push_back(key);
    return keys;
  }
  if (const auto* s = std::get_if<StringPtr>(&v.data)) {
    std::vector<Value> chars;
    for (char c : **s) chars.push_back(MakeString(std::string(1, c)));
    return chars;
  }
  if (const auto* vec = std::get_if<Eigen::Vector3d>(&v.data)) {
    return {Value((*vec).x()), Value((*vec).y()), Value((*vec).z())};
  }
  Fail(span, "type-error", "cannot iterate over a " + TypeName(v) + "; expected a list, a tuple "
                           "or range(...)");
}

void Interpreter::Fail(SourceSpan span, const std::string& id, const std::string& message,
                       std::vector<DiagnosticNote> notes) const {
  Diagnostic d;
  d.id = id;
  d.span = span;
  d.message = message;
  d.notes = std::move(notes);
  throw ScenarioError(std::move(d));
}

[[noreturn]] void Interpreter::Reject(RejectionKind kind, std::string culprit, SourceSpan span,
                         std::string detail) {
  throw RejectSignal{Rejection{kind, std::move(culprit), span, std::move(detail)}};
}

}  // namespace internal
}  // namespace prs::lang
