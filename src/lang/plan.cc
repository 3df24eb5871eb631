// The creation planner: decides where each property of an object comes from (a class default,
// a `with`, the position specifiers together, the orientation) and orders them so that every
// property is computed after the ones it reads. Cycles and duplicate sources are errors.
#include <algorithm>
#include <map>
#include <set>

#include "lang/resolve_internal.h"

namespace prs::lang::internal {
namespace {

bool IsPositionSpecifier(const Specifier& s) {
  switch (s.kind) {
    case SpecifierKind::kWith:
      return s.property && s.property->name == "position";
    case SpecifierKind::kFacing:
    case SpecifierKind::kFacingToward:
      return false;
    default:
      return true;
  }
}

bool IsOrientationSpecifier(const Specifier& s) {
  return s.kind == SpecifierKind::kFacing || s.kind == SpecifierKind::kFacingToward ||
         (s.kind == SpecifierKind::kWith && s.property && s.property->name == "orientation");
}

// Properties of the object itself that a position specifier reads.
std::vector<std::string> PositionReads(const Specifier& s) {
  if (s.kind == SpecifierKind::kOn) return {"height"};
  if (s.kind == SpecifierKind::kCompletelyOn || IsSideSpecifier(s.kind) ||
      s.kind == SpecifierKind::kCompletelyInViewOf || s.kind == SpecifierKind::kCompletelyVisibleFrom) {
    return {"width", "length", "height", "orientation"};
  }
  return {};
}

struct Source {
  PlanStep step;
  std::vector<std::string> reads;
  SourceSpan span;
  bool has_span = false;
  std::string description;  // for cycle messages, e.g. "'completely on'"
};

class Planner {
 public:
  Planner(const CreateObject* create, const std::vector<Specifier>& specifiers,
          const ClassInfo& cls, DiagnosticEngine& diagnostics)
      : create_(create), specifiers_(specifiers), cls_(cls), diagnostics_(diagnostics) {}

  bool Build(ObjectPlan& plan) {
    plan.cls = &cls_;
    AddDefaults();
    if (!AddSpecifiers(plan)) return false;
    AddPositionAndOrientation(plan);
    // A mesh shape gives the object its size (spec §10): sizes are worked out after it.
    if (sources_.count("shape") && cls_.has_box) {
      for (const char* size : {"width", "length", "height"}) {
        if (sources_.count(size)) sources_[size].reads.push_back("shape");
      }
    }
    DropUnknownReads();
    BreakPositionOrientationCycle(plan);
    plan.fold_workspace = cls_.has_box && !DependsOn("orientation", "position");
    if (plan.fold_workspace && sources_.count("position")) {
      auto& reads = sources_["position"].reads;
      for (const char* p : {"width", "length", "height", "orientation"}) reads.push_back(p);
      DropUnknownReads();
    }
    return Order(plan);
  }

 private:
  void AddDefaults() {
    for (const PropertyDefault& d : cls_.defaults) {
      Source source{{PlanStepKind::kDefault, d.name, &d, nullptr}, d.self_reads, d.span,
                    d.expr != nullptr, "the default of '" + d.name + "'"};
      sources_[d.name] = std::move(source);
      order_.push_back(d.name);
    }
  }

  bool AddSpecifiers(ObjectPlan& plan) {
    std::map<std::string, const Specifier*> setters;
    bool ok = true;
    for (const Specifier& s : specifiers_) {
      if (IsPositionSpecifier(s)) {
        plan.position_specifiers.push_back(&s);
        continue;
      }
      const std::string property = IsOrientationSpecifier(s) ? "orientation" : s.property->name;
      if (property == "orientation" && !cls_.has_orientation) {
        diagnostics_.Error("bad-specifier", s.span,
                           "'" + cls_.name + "' has no orientation, so '" +
                               std::string(SpecifierName(s.kind)) + "' cannot apply to it");
        ok = false;
        continue;
      }
      auto [it, inserted] = setters.emplace(property, &s);
      if (!inserted) {
        Diagnostic d;
        d.id = "duplicate-specifier";
        d.span = s.span;
        d.message = "'" + property + "' is set twice for this " + cls_.name;
        d.notes.push_back({it->second->span, true, "it was first set here"});
        diagnostics_.Report(std::move(d));
        ok = false;
        continue;
      }
      if (property == "orientation") {
        orientation_specifier_ = &s;
      } else {
        Source source{{PlanStepKind::kWith, property, nullptr, &s}, {}, s.span, true,
                      "'with " + property + "'"};
        if (!sources_.count(property)) order_.push_back(property);
        sources_[property] = std::move(source);
      }
    }
    return ok;
  }

  void AddPositionAndOrientation(ObjectPlan& plan) {
    if (!plan.position_specifiers.empty()) {
      Source& position = sources_["position"];
      position.step = {PlanStepKind::kPosition, "position", position.step.default_value, nullptr};
      position.reads.clear();
      position.description = "the position specifiers";
      position.span = plan.position_specifiers.front()->span;
      position.has_span = true;
      for (const Specifier* s : plan.position_specifiers) {
        for (std::string& r : PositionReads(*s)) position.reads.push_back(std::move(r));
      }
    } else if (sources_.count("position")) {
      sources_["position"].step.kind = PlanStepKind::kPosition;
    }
    if (!cls_.has_orientation) return;
    Source& orientation = sources_["orientation"];
    orientation.step.kind = PlanStepKind::kOrientation;
    orientation.step.specifier = orientation_specifier_;
    if (orientation_specifier_) {
      orientation.reads.clear();
      orientation.span = orientation_specifier_->span;
      orientation.has_span = true;
      orientation.description = "'" + std::string(SpecifierName(orientation_specifier_->kind)) + "'";
      if (orientation_specifier_->kind == SpecifierKind::kFacingToward) {
        orientation.reads.push_back("position");
      }
    }
    for (const char* angle : {"yaw", "pitch", "roll"}) orientation.reads.push_back(angle);
  }

  // `completely on X, facing toward Y`: the position needs the orientation for the box's
  // footprint, and the orientation needs the position. When nothing else closes the loop,
  // the position reads only what a yaw-independent superset needs (ObjectPlan::open_turn).
  void BreakPositionOrientationCycle(ObjectPlan& plan) {
    auto position = sources_.find("position");
    if (position == sources_.end() || !sources_.count("orientation")) return;
    std::vector<std::string>& reads = position->second.reads;
    const auto reads_orientation = std::remove(reads.begin(), reads.end(), "orientation");
    if (reads_orientation == reads.end()) return;
    reads.erase(reads_orientation, reads.end());
    if (!DependsOn("orientation", "position")) {
      reads.push_back("orientation");
      return;
    }
    const PropertyDefault* base = cls_.FindDefault("orientation");
    const bool turns_about_z = orientation_specifier_
                                   ? orientation_specifier_->kind == SpecifierKind::kFacingToward
                                   : !(base && base->expr);
    const bool tilt_known = (!sources_.count("pitch") || !DependsOn("pitch", "position")) &&
                            (!sources_.count("roll") || !DependsOn("roll", "position"));
    if (turns_about_z && tilt_known) {
      plan.open_turn = ObjectPlan::OpenTurn::kYaw;
      for (const char* angle : {"pitch", "roll"}) {
        if (sources_.count(angle)) reads.push_back(angle);
      }
    } else {
      plan.open_turn = ObjectPlan::OpenTurn::kAny;
    }
  }

  // A point has no width; reads of properties the class lacks are not dependencies.
  void DropUnknownReads() {
    for (auto& [name, source] : sources_) {
      std::vector<std::string> kept;
      for (const std::string& r : source.reads) {
        if (sources_.count(r) && r != name) kept.push_back(r);
      }
      source.reads = std::move(kept);
    }
  }

  bool DependsOn(const std::string& from, const std::string& target) const {
    std::set<std::string> seen;
    std::vector<std::string> stack{from};
    while (!stack.empty()) {
      const std::string current = stack.back();
      stack.pop_back();
      if (!seen.insert(current).second) continue;
      auto it = sources_.find(current);
      if (it == sources_.end()) continue;
      for (const std::string& r : it->second.reads) {
        if (r == target) return true;
        stack.push_back(r);
      }
    }
    return false;
  }

  // Depth-first topological order; a back edge is a cycle, reported with its path.
  bool Order(ObjectPlan& plan) {
    std::map<std::string, int> state;  // 0 new, 1 on the stack, 2 done
    std::vector<std::string> stack;
    for (const std::string& name : order_) {
      if (!Visit(name, state, stack, plan)) return false;
    }
    return true;
  }

  bool Visit(const std::string& name, std::map<std::string, int>& state,
             std::vector<std::string>& stack, ObjectPlan& plan) {
    if (state[name] == 2) return true;
    if (state[name] == 1) {
      ReportCycle(name, stack);
      return false;
    }
    state[name] = 1;
    stack.push_back(name);
    for (const std::string& r : sources_.at(name).reads) {
      if (!Visit(r, state, stack, plan)) return false;
    }
    stack.pop_back();
    state[name] = 2;
    plan.steps.push_back(sources_.at(name).step);
    return true;
  }

  void ReportCycle(const std::string& name, const std::vector<std::string>& stack) {
    auto start = std::find(stack.begin(), stack.end(), name);
    std::string chain;
    for (auto it = start; it != stack.end(); ++it) chain += *it + " -> ";
    chain += name;
    Diagnostic d;
    d.id = "dependency-cycle";
    const Source& first = sources_.at(name);
    d.span = first.has_span ? first.span : (create_ ? create_->class_name.span : SourceSpan{});
    d.has_span = first.has_span || create_ != nullptr;
    d.message = "the properties of this " + cls_.name + " depend on each other in a cycle: " + chain;
    bool all_defaults = true;
    for (auto it = start; it != stack.end(); ++it) {
      const Source& s = sources_.at(*it);
      d.notes.push_back({s.span, s.has_span, *it + " comes from " + s.description});
      all_defaults = all_defaults && s.step.kind == PlanStepKind::kDefault;
    }
    d.notes.push_back({{}, false, all_defaults
        ? "give one of these defaults a value that does not read the others"
        : "set one of these properties directly, e.g. with 'facing V' instead of 'facing toward', "
          "or drop one specifier"});
    diagnostics_.Report(std::move(d));
  }

  const CreateObject* create_;
  const std::vector<Specifier>& specifiers_;
  const ClassInfo& cls_;
  DiagnosticEngine& diagnostics_;
  std::map<std::string, Source> sources_;
  std::vector<std::string> order_;  // properties in declaration order, for a stable plan
  const Specifier* orientation_specifier_ = nullptr;
};

}  // namespace

bool BuildObjectPlan(const CreateObject& create, const ClassInfo& cls, ObjectPlan& plan,
                     DiagnosticEngine& diagnostics) {
  return Planner(&create, create.specifiers, cls, diagnostics).Build(plan);
}

bool BuildDefaultPlan(const ClassInfo& cls, ObjectPlan& plan, DiagnosticEngine& diagnostics) {
  static const std::vector<Specifier> kNone;
  return Planner(nullptr, kNone, cls, diagnostics).Build(plan);
}

}  // namespace prs::lang::internal
