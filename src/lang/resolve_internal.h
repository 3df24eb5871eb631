// Internals shared by the resolver's files: the name checker and the object-creation planner.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "lang/ast.h"
#include "lang/diagnostics.h"
#include "lang/program.h"

namespace prs::lang::internal {

/// Adds the names bound at the top level of `body` (descending into if/for/while blocks, not
/// into nested functions) to `names`; `from M import *` adds M's globals.
void CollectBoundNames(const CompiledProgram& program, const std::vector<StmtPtr>& body,
                       std::set<std::string>& names);

/// Checks names, `self`, and call arities in module `m`, and plans its object creations.
void CheckModule(CompiledProgram& program, int m, DiagnosticEngine& diagnostics);

/// Builds the plan for one creation site of class `cls`; reports duplicate and cyclic
/// property sources. Returns false on error.
bool BuildObjectPlan(const CreateObject& create, const ClassInfo& cls, ObjectPlan& plan,
                     DiagnosticEngine& diagnostics);

/// Marks the creation plans whose region or whole object is the same in every scene. Returns,
/// per module, the names whose value after the module has run is the same in every scene.
std::vector<std::set<std::string>> MarkFixedPlacements(CompiledProgram& program);

/// Marks the creation sites whose object is a function of its own draws (ObjectPlan::
/// own_draws_only; own_draws.cc), given MarkFixedPlacements' fixed names.
void MarkOwnDrawSites(CompiledProgram& program, const std::vector<std::set<std::string>>& fixed);

/// Builds the plan for a class created with no specifiers.
bool BuildDefaultPlan(const ClassInfo& cls, ObjectPlan& plan, DiagnosticEngine& diagnostics);

}  // namespace prs::lang::internal
