// The diagnostic engine, the Clang-style renderer, "did you mean" suggestions and the
// catalogue of diagnostic ids (documented in docs/diagnostics.md).
#include "lang/diagnostics.h"

#include <fmt/format.h>

#include <algorithm>

namespace prs::lang {
namespace {

constexpr int kTabStop = 8;
constexpr const char* kReset = "\033[0m";
constexpr const char* kBold = "\033[1m";
constexpr const char* kGreen = "\033[1;32m";

const char* SeverityName(Severity s) {
  switch (s) {
    case Severity::kError: return "error";
    case Severity::kWarning: return "warning";
    case Severity::kNote: return "note";
  }
  return "error";
}

const char* SeverityColor(Severity s) {
  switch (s) {
    case Severity::kError: return "\033[1;31m";
    case Severity::kWarning: return "\033[1;35m";
    case Severity::kNote: return "\033[1;30m";
  }
  return "";
}

bool IsContinuationByte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

// Expands tabs in `line` and returns it with, for each byte offset (0..size), the display
// column (0-based) where that byte starts.
std::string ExpandTabs(std::string_view line, std::vector<uint32_t>* columns) {
  std::string out;
  uint32_t col = 0;
  columns->assign(line.size() + 1, 0);
  for (size_t i = 0; i < line.size(); ++i) {
    (*columns)[i] = col;
    if (line[i] == '\t') {
      uint32_t next = (col / kTabStop + 1) * kTabStop;
      out.append(next - col, ' ');
      col = next;
    } else {
      out.push_back(line[i]);
      if (!IsContinuationByte(line[i])) ++col;
    }
  }
  (*columns)[line.size()] = col;
  // Continuation bytes share the column of their lead byte.
  for (size_t i = 1; i < line.size(); ++i) {
    if (IsContinuationByte(line[i])) (*columns)[i] = (*columns)[i - 1];
  }
  return out;
}

// Appends "file:line:col: severity: message\n" (or "severity: message" with no span).
void RenderHeader(std::string* out, Severity severity, SourceSpan span, bool has_span,
                  const std::string& message, const SourceManager& sources, bool color) {
  if (color) out->append(kBold);
  if (has_span) {
    LineColumn lc = sources.CalcLineColumn(span.file, span.begin);
    out->append(fmt::format("{}:{}:{}: ", sources.path(span.file), lc.line, lc.column));
  }
  if (color) out->append(SeverityColor(severity));
  out->append(fmt::format("{}: ", SeverityName(severity)));
  if (color) out->append(std::string(kReset) + kBold);
  out->append(message);
  if (color) out->append(kReset);
  out->push_back('\n');
}

// The columns [first, first + count) of a long line that show the caret: Clang's habit of
// printing a window of a long line rather than the whole of it.
struct LineWindow {
  uint32_t first = 0;
  uint32_t count = 0;
};

// Picks the window of a `total`-column line that shows the caret at `caret_col` with some
// context before it (and as much of the span after it as fits).
LineWindow ChooseWindow(uint32_t total, uint32_t caret_col) {
  constexpr uint32_t kMaxColumns = 120;
  if (total <= kMaxColumns) return {0, total};
  uint32_t first = caret_col > kMaxColumns / 3 ? caret_col - kMaxColumns / 3 : 0;
  first = std::min(first, total - kMaxColumns);
  return {first, kMaxColumns};
}

// Cuts the display columns of `window` out of `expanded` (a line with its tabs expanded),
// marking each cut end with "...". Adds the width of the leading mark to *shift.
std::string CutWindow(const std::string& expanded, LineWindow window, uint32_t total,
                      uint32_t* shift) {
  if (window.first == 0 && window.count == total) return expanded;
  std::vector<uint32_t> columns;
  ExpandTabs(expanded, &columns);  // no tabs left: just the column of each byte
  size_t lo = 0, hi = expanded.size();
  while (lo < expanded.size() && (columns[lo] < window.first || IsContinuationByte(expanded[lo])))
    ++lo;
  for (size_t i = lo; i < expanded.size(); ++i) {
    if (columns[i] >= window.first + window.count && !IsContinuationByte(expanded[i])) {
      hi = i;
      break;
    }
  }
  std::string cut = expanded.substr(lo, hi - lo);
  if (window.first > 0) cut = "..." + cut, *shift += 3;
  if (hi < expanded.size()) cut += "...";
  return cut;
}

// Appends the source line of span.begin (a window of it when it is long), a caret line and,
// if any, the fix-it line.
void RenderSnippet(std::string* out, SourceSpan span, const std::string& fix_it,
                   const SourceManager& sources, bool color) {
  LineColumn lc = sources.CalcLineColumn(span.file, span.begin);
  std::string_view line = sources.LineText(span.file, lc.line);
  uint32_t line_start = sources.LineStart(span.file, lc.line);
  std::vector<uint32_t> columns;
  std::string expanded = ExpandTabs(line, &columns);
  uint32_t begin = std::min<uint32_t>(span.begin - line_start, line.size());
  uint32_t end = span.end > span.begin ? span.end - line_start : begin;
  end = std::min<uint32_t>(end, line.size());  // a span past the line end is cut there
  uint32_t caret_col = columns[begin];
  uint32_t width = end > begin ? columns[end] - caret_col : 1;
  if (width == 0) width = 1;

  const uint32_t total = columns[line.size()];
  const LineWindow window = ChooseWindow(total, caret_col);
  uint32_t shift = 0;
  const std::string shown = CutWindow(expanded, window, total, &shift);
  caret_col = caret_col - window.first + shift;
  if (window.count < total) {
    // The caret may sit just past the window's last column (a span at the end of the line).
    const uint32_t room = window.count + shift > caret_col ? window.count + shift - caret_col : 1;
    width = std::min(width, room);
  }

  std::string gutter = fmt::format("{:>5} | ", lc.line);
  std::string blank(gutter.size() - 2, ' ');
  blank += "| ";
  out->append(gutter).append(shown).push_back('\n');
  out->append(blank).append(caret_col, ' ');
  if (color) out->append(kGreen);
  out->push_back('^');
  out->append(width - 1, '~');
  if (color) out->append(kReset);
  out->push_back('\n');
  if (!fix_it.empty()) {
    out->append(blank).append(caret_col, ' ');
    if (color) out->append(kGreen);
    out->append(fix_it);
    if (color) out->append(kReset);
    out->push_back('\n');
  }
}

}  // namespace

void DiagnosticEngine::Report(Diagnostic diagnostic) {
  // Stages may meet the same fault twice (a class's cycle in each plan that uses it): keep one.
  const SourceSpan& s = diagnostic.span;
  std::string key = fmt::format("{}\n{}\n{}:{}:{}:{}", diagnostic.id, diagnostic.message,
                                diagnostic.has_span, s.file, s.begin, s.end);
  if (!seen_.insert(std::move(key)).second) return;
  if (diagnostic.severity == Severity::kError && error_count_ >= kMaxErrors) {
    // As Clang's -ferror-limit: past this, more errors only bury the first ones (and a line
    // of 40,000 stray brackets would take minutes to print).
    if (error_count_++ == kMaxErrors) {
      Diagnostic stop;
      stop.id = "too-many-errors";
      stop.has_span = false;
      stop.message = fmt::format("too many errors ({} shown); stopping here: fix these first",
                                 kMaxErrors);
      diagnostics_.push_back(std::move(stop));
    }
    return;
  }
  if (diagnostic.severity == Severity::kError) ++error_count_;
  diagnostics_.push_back(std::move(diagnostic));
}

void DiagnosticEngine::Error(std::string id, SourceSpan span, std::string message,
                             std::string fix_it) {
  Diagnostic d;
  d.id = std::move(id);
  d.span = span;
  d.message = std::move(message);
  d.fix_it = std::move(fix_it);
  Report(std::move(d));
}

std::string RenderDiagnostic(const Diagnostic& d, const SourceManager& sources, bool color) {
  std::string out;
  RenderHeader(&out, d.severity, d.span, d.has_span, d.message, sources, color);
  if (d.has_span) RenderSnippet(&out, d.span, d.fix_it, sources, color);
  // Notes are one line each, pointing at the related location (see docs/diagnostics.md).
  for (const DiagnosticNote& note : d.notes) {
    RenderHeader(&out, Severity::kNote, note.span, note.has_span, note.message, sources, color);
  }
  return out;
}

ScenarioError::ScenarioError(Diagnostic diagnostic) : diagnostic_(std::move(diagnostic)) {}

size_t CalcEditDistance(std::string_view a, std::string_view b) {
  // Optimal string alignment: insertions, deletions, substitutions, adjacent transpositions.
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i) {
    for (size_t j = 1; j <= m; ++j) {
      size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

std::string SuggestClosest(std::string_view name, const std::vector<std::string>& candidates) {
  const size_t limit = std::max<size_t>(1, name.size() / 3);
  std::string best;
  size_t best_distance = limit + 1;
  for (const std::string& c : candidates) {
    if (c == name) continue;
    size_t dist = CalcEditDistance(name, c);
    if (dist < best_distance) {
      best_distance = dist;
      best = c;
    }
  }
  return best;
}

const std::vector<DiagnosticKind>& DiagnosticCatalogue() {
  static const std::vector<DiagnosticKind> kCatalogue = {
      // ---- lexer -----------------------------------------------------------
      {"invalid-character", "lexer", "a character that cannot start any token"},
      {"invalid-number", "lexer", "a malformed number literal such as `1e` or `1.2.3`"},
      {"too-many-errors", "engine", "more than 50 errors: the rest are not reported"},
      {"unterminated-string", "lexer", "a string literal with no closing quote"},
      {"bad-escape", "lexer", "a `\\x` or `\\u` escape without its 2 or 4 hexadecimal digits"},
      {"unknown-escape", "lexer", "(warning) an escape such as `\\d` that Python keeps as written"},
      {"unclosed-bracket", "lexer", "an opening bracket never closed before the end of file"},
      {"mismatched-bracket", "lexer", "a closing bracket that does not match the open one"},
      {"unmatched-bracket", "lexer", "a closing bracket with no opening bracket"},
      {"unexpected-indent", "parser", "a line indented more than the block it belongs to"},
      {"inconsistent-dedent", "lexer", "an unindent that does not match any outer level"},
      {"inconsistent-tabs", "lexer", "indentation mixing tabs and spaces ambiguously"},
      {"bad-line-continuation", "lexer", "a backslash not at the end of a line"},
      // ---- parser ----------------------------------------------------------
      {"expected-token", "parser", "a specific token (`:`, `)`, `import`, …) is missing"},
      {"expected-expression", "parser", "an expression was expected"},
      {"expected-indented-block", "parser", "a `:` line not followed by an indented block"},
      {"expected-statement-end", "parser", "extra tokens after a complete statement"},
      {"unknown-class", "parser", "a name used with specifiers is not a known class"},
      {"expected-specifier", "parser", "a class name followed by something not a specifier"},
      {"unknown-specifier", "parser", "a misspelled specifier keyword"},
      {"missing-of", "parser", "`left`, `ahead`, … without `of`"},
      {"unknown-side", "parser", "a misspelled compound side such as `top frnt of t`"},
      {"bad-axis", "parser", "`aligned with X on` an axis other than x, y, z"},
      {"duplicate-option", "parser", "an option of `reachable by` (margin, approach, grasp) given twice"},
      {"invalid-assignment-target", "parser", "assigning to something that is not a name"},
      {"unsupported-feature", "lexer, parser", "a Python feature ProbRobScene does not support"},
      {"bad-class-body", "parser", "a class body line that is not `name: expr` or `pass`"},
      {"bad-argument-order", "parser", "a positional argument after a keyword argument"},
      {"duplicate-parameter", "parser", "a function parameter or keyword given twice"},
      {"bad-default-order", "parser", "a parameter without a default after one with"},
      {"outside-function", "parser", "`return` outside a function"},
      {"outside-loop", "parser", "`break` or `continue` outside a loop"},
      {"nested-definition", "parser", "`class` inside a block (classes are top-level only)"},
      {"too-deeply-nested", "parser", "blocks or expressions nested beyond the parser's limit"},
      // ---- resolver / interpreter (appended by those stages) ------------------
      {"file-not-found", "compiler", "the main file, or a URDF file an `arm` names, cannot be read"},
      {"module-not-found", "compiler", "`from NAME import *` finds no NAME.prs on the search path"},
      {"unknown-param", "compiler", "`-p NAME=VALUE` for a NAME no `param` statement declares"},
      {"import-cycle", "compiler", "modules that import each other, directly or not"},
      {"unknown-name", "resolver", "a name that is never bound (with the closest bound name)"},
      {"unknown-module", "resolver", "`import NAME` of a module other than `math`"},
      {"unknown-attribute", "resolver, interpreter", "`math.NAME` that `math` does not have"},
      {"misplaced-self", "resolver", "`self` outside a class's property defaults"},
      {"misplaced-statement", "resolver", "`return`, `param`, ... where they cannot appear"},
      {"misplaced-definition", "resolver", "`class` or `def` inside a block"},
      {"wrong-argument-count", "resolver, interpreter",
       "a call with too many or too few arguments"},
      {"bad-argument", "resolver", "an unknown or repeated keyword argument"},
      {"duplicate-specifier", "planner", "one property set by two specifiers of an object"},
      {"dependency-cycle", "planner",
       "an object's properties that depend on each other in a cycle"},
      {"bad-specifier", "planner, interpreter", "a specifier applied to a value it cannot use"},
      {"type-error", "interpreter", "a value of the wrong type (`on 3`, `\"a\" + 1`)"},
      {"bad-value", "interpreter", "a value of the right type out of range (negative size, 1/0)"},
      {"bad-unpack", "interpreter", "`a, b = e` where e has a different number of parts"},
      {"bad-index", "interpreter", "an index out of range, or a missing dict key"},
      {"bad-resample", "interpreter", "`resample` of a value no distribution drew"},
      {"bad-region", "interpreter", "a region constructor given degenerate arguments"},
      {"unbound-name", "interpreter", "a variable read before any assignment ran"},
      {"unknown-property", "interpreter", "an object property that is not defined (typo hint)"},
      {"unbounded-region", "interpreter", "an object's position region is unbounded"},
      {"empty-region", "interpreter", "no position satisfies an object's specifiers"},
      {"limit-exceeded", "interpreter", "a run exceeded a loop, recursion or object limit"},
      {"naive-needs-workspace", "interpreter", "naive sampling with no bounded workspace"},
      {"not-an-arm", "interpreter", "`reachable by` an object whose class has no `arm` property"},
      {"bad-arm", "interpreter",
       "an arm that cannot be used: unknown model, bad URDF, missing link, bad options"},
      {"arm-reaches-nothing", "interpreter",
       "`reachable by` an arm whose reachable set is empty (a URDF with too few joints)"},
      {"bad-camera", "interpreter", "a camera whose intrinsics are out of range (fov, aspect, near/far)"},
      {"bad-mesh", "interpreter",
       "a mesh shape that cannot be used: unknown format, unreadable or empty file, a path that "
       "is not a string literal, or an orientation that depends on its position where no "
       "footprint is common to every turn"},
      {"conflicting-size", "interpreter", "width, length or height given for a mesh-shaped object "
                                          "and different from its mesh's size"},
      {"mesh-warning", "resolver", "(warning) a mesh that is not closed, has zero-area triangles "
                                   "or looks like it is in the wrong units"},
      {"sampling-failed", "sampler", "no valid scene within the attempt limit, or none possible"},
      {"physics-without-contacts", "physics",
       "--stable or --settle with an object that has a mass and allowCollisions: True (no "
       "contacts: it falls through its support)"},
  };
  return kCatalogue;
}

bool IsKnownDiagnosticId(std::string_view id) {
  const auto& catalogue = DiagnosticCatalogue();
  return std::any_of(catalogue.begin(), catalogue.end(),
                     [&](const DiagnosticKind& k) { return id == k.id; });
}

}  // namespace prs::lang
