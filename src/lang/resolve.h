// The resolver: static checks over parsed modules (unknown names with suggestions, `self`
// outside class defaults, call arity of built-ins and functions, class parents) and the
// per-creation-site plans that order an object's properties by their dependencies.
#pragma once

#include <map>
#include <string>

#include "lang/diagnostics.h"
#include "lang/program.h"

namespace prs::lang {

/// Fills in `program`'s class table, scopes and plans. `loaded` maps module names to indices.
/// Reports every problem found to `diagnostics`; returns false if any was an error.
bool ResolveProgram(CompiledProgram& program, const std::map<std::string, int>& loaded,
                    DiagnosticEngine& diagnostics);

}  // namespace prs::lang
