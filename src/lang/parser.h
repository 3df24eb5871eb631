// The parser: hand-written recursive descent from tokens to the AST (lang/ast.h), with
// Clang-style diagnostics and recovery at the next statement.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lang/ast.h"
#include "lang/diagnostics.h"
#include "lang/source.h"

namespace prs::lang {

struct ParseOptions {
  /// Called when the parser meets `from MODULE import *`: returns the class names the module
  /// defines (directly or through its own imports), or nullopt when the driver could not
  /// load it and has already reported why. May be empty (no imports resolved).
  std::function<std::optional<std::vector<std::string>>(const std::string& module,
                                                        SourceSpan where)>
      import_classes;
};

/// Lexes and parses one file. Syntax errors go to `diagnostics` (the parser recovers at the
/// next statement, so one mistake gives one error); the returned module holds every
/// statement that parsed. The parser knows which names are classes (built-ins Point3D,
/// OrientedPoint3D, Object; classes defined earlier in the file; imported ones) so it can
/// tell `Cube in r` (an object creation) from `x in r` (a membership test).
Module Parse(FileId file, const SourceManager& sources, DiagnosticEngine& diagnostics,
             const ParseOptions& options = {});

/// The names the parser treats as classes before any are defined or imported.
const std::vector<std::string>& BuiltinClassNames();

}  // namespace prs::lang
