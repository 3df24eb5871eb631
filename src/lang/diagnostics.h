// Diagnostics shared by every stage (lexer, parser, resolver, interpreter, sampler):
// one data type, one engine that collects them, one Clang-style renderer.
#pragma once

#include <exception>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "lang/source.h"

namespace prs::lang {

enum class Severity { kError, kWarning, kNote };

struct DiagnosticNote {
  SourceSpan span;
  bool has_span = true;
  std::string message;
};

struct Diagnostic {
  std::string id;  // stable kebab-case id from DiagnosticCatalogue(), e.g. "unknown-name"
  Severity severity = Severity::kError;
  SourceSpan span;
  bool has_span = true;
  std::string message;
  std::vector<DiagnosticNote> notes;
  std::string fix_it;  // suggested replacement text for span, may be empty
};

/// Collects diagnostics in the order they are reported, each once. After kMaxErrors errors,
/// further errors are counted but not kept: one "too-many-errors" diagnostic stands for them.
class DiagnosticEngine {
 public:
  static constexpr size_t kMaxErrors = 50;
  void Report(Diagnostic diagnostic);
  /// Shorthand for an error with no notes or fix-it.
  void Error(std::string id, SourceSpan span, std::string message, std::string fix_it = "");
  bool has_errors() const { return error_count_ > 0; }
  size_t error_count() const { return error_count_; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
  // What identifies a diagnostic for Report()'s duplicate check: a hash set, so that a file
  // with tens of thousands of errors (a line of 40,000 brackets) is not checked in O(n²).
  std::unordered_set<std::string> seen_;
  size_t error_count_ = 0;
};

/// Renders one diagnostic (and its notes) Clang-style, ending with a newline:
///   file:line:col: error: message
///       3 | source line
///         |     ^~~
///         |     fix-it
/// With `color`, uses ANSI escapes for the severity, the message and the caret.
std::string RenderDiagnostic(const Diagnostic& diagnostic, const SourceManager& sources,
                             bool color = false);

/// Thrown by later stages (interpreter, sampler) to abort with a diagnostic.
class ScenarioError : public std::exception {
 public:
  explicit ScenarioError(Diagnostic diagnostic);
  const Diagnostic& diagnostic() const { return diagnostic_; }
  /// The diagnostic's message.
  const char* what() const noexcept override { return diagnostic_.message.c_str(); }

 private:
  Diagnostic diagnostic_;
};

/// Optimal-string-alignment (Damerau-Levenshtein) distance between a and b.
size_t CalcEditDistance(std::string_view a, std::string_view b);

/// Returns the candidate closest to `name` by edit distance, or "" when none is within
/// max(1, name.size() / 3). Ties go to the earliest candidate; `name` itself is skipped.
std::string SuggestClosest(std::string_view name, const std::vector<std::string>& candidates);

/// One entry of the catalogue of diagnostic ids.
struct DiagnosticKind {
  const char* id;
  const char* stage;  // "lexer", "parser", "interpreter", ...
  const char* description;
};

/// Every diagnostic id any stage may report, with a one-line description.
const std::vector<DiagnosticKind>& DiagnosticCatalogue();

/// True when `id` is in the catalogue.
bool IsKnownDiagnosticId(std::string_view id);

}  // namespace prs::lang
