// Tests for diagnostics: the Clang-style renderer, "did you mean" suggestions, the catalogue,
// and the data-driven bad programs in tests/lang/bad/parse_*.prs with their .expected output.
#include "lang/diagnostics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "lang/parser.h"

namespace prs::lang {
namespace {

Diagnostic MakeError(FileId file, uint32_t begin, uint32_t end, std::string message) {
  Diagnostic d;
  d.id = "unknown-class";
  d.span = SourceSpan{file, begin, end};
  d.message = std::move(message);
  return d;
}

TEST(RenderDiagnosticTest, MatchesClangLayout) {
  SourceManager sm;
  FileId f = sm.AddFile("examples/bad.prs", "class Cube:\n    width: 1\nc = Cub on table\n");
  Diagnostic d = MakeError(f, 29, 32, "unknown class 'Cub'");
  d.fix_it = "Cube";
  d.notes.push_back({SourceSpan{f, 6, 10}, true, "'Cube' is defined here"});
  EXPECT_EQ(RenderDiagnostic(d, sm),
            "examples/bad.prs:3:5: error: unknown class 'Cub'\n"
            "    3 | c = Cub on table\n"
            "      |     ^~~\n"
            "      |     Cube\n"
            "examples/bad.prs:1:7: note: 'Cube' is defined here\n");
}

TEST(RenderDiagnosticTest, ExpandsTabsAndCutsSpansAtLineEnd) {
  SourceManager sm;
  FileId f = sm.AddFile("t.prs", "if x:\n\ty = (1,\n\t 2)\n");
  Diagnostic d = MakeError(f, 11, 20, "span running onto the next line");
  d.severity = Severity::kWarning;
  EXPECT_EQ(RenderDiagnostic(d, sm),
            "t.prs:2:6: warning: span running onto the next line\n"
            "    2 |         y = (1,\n"
            "      |             ^~~\n");
}

TEST(RenderDiagnosticTest, EmptySpanAtLineEndGetsOneCaret) {
  SourceManager sm;
  FileId f = sm.AddFile("t.prs", "x = 1 +");
  EXPECT_EQ(RenderDiagnostic(MakeError(f, 7, 7, "expected an expression"), sm),
            "t.prs:1:8: error: expected an expression\n"
            "    1 | x = 1 +\n"
            "      |        ^\n");
}

// A long line shows a window around the caret, marked with "..." where it was cut, and the
// caret still points at the same character.
TEST(RenderDiagnosticTest, LongLinesShowAWindowAroundTheCaret) {
  SourceManager sm;
  const std::string line = "x = " + std::string(300, 'a') + " + b" + std::string(300, 'c');
  FileId f = sm.AddFile("t.prs", line + "\n");
  const uint32_t b = uint32_t(line.find(" b")) + 1;
  const std::string rendered = RenderDiagnostic(MakeError(f, b, b + 1, "unknown name 'b'"), sm);
  const std::string shown = rendered.substr(rendered.find("| ") + 2);
  const std::string source_line = shown.substr(0, shown.find('\n'));
  const std::string caret_line = rendered.substr(rendered.rfind("| ") + 2);
  EXPECT_TRUE(source_line.starts_with("...")) << rendered;
  EXPECT_TRUE(source_line.ends_with("...")) << rendered;
  EXPECT_LE(source_line.size(), 126u);
  EXPECT_EQ(source_line[caret_line.find('^')], 'b') << rendered;
  // A caret just past the end of a long line (a missing token) and bytes that are not UTF-8:
  // one caret, no runaway underline.
  const std::string tail = std::string(400, '\xff') + " +";
  FileId g = sm.AddFile("u.prs", tail + "\n");
  const std::string at_end =
      RenderDiagnostic(MakeError(g, uint32_t(tail.size()), uint32_t(tail.size()), "expected"), sm);
  EXPECT_LT(at_end.size(), 400u) << at_end.size();
  EXPECT_TRUE(at_end.ends_with("^\n")) << at_end;
}

TEST(RenderDiagnosticTest, CaretColumnsCountCodePoints) {
  SourceManager sm;
  FileId f = sm.AddFile("t.prs", "s = 'é' + x\n");
  EXPECT_EQ(RenderDiagnostic(MakeError(f, 11, 12, "m"), sm),
            "t.prs:1:11: error: m\n"
            "    1 | s = 'é' + x\n"
            "      |           ^\n");
}

TEST(RenderDiagnosticTest, WithoutSpanAndInColor) {
  SourceManager sm;
  FileId f = sm.AddFile("t.prs", "x\n");
  Diagnostic d = MakeError(f, 0, 1, "no span");
  d.has_span = false;
  EXPECT_EQ(RenderDiagnostic(d, sm), "error: no span\n");
  d.has_span = true;
  std::string colored = RenderDiagnostic(d, sm, /*color=*/true);
  EXPECT_NE(colored.find("\033[1;31merror: "), std::string::npos);
  EXPECT_NE(colored.find("\033[1;32m^"), std::string::npos);
}

TEST(SourceManagerTest, LinesAndColumns) {
  SourceManager sm;
  FileId a = sm.AddFile("a.prs", "ab\r\ncd\n\nef");
  FileId b = sm.AddFile("b.prs", "");
  EXPECT_EQ(sm.CalcLineColumn(a, 0).line, 1u);
  EXPECT_EQ(sm.CalcLineColumn(a, 5).line, 2u);
  EXPECT_EQ(sm.CalcLineColumn(a, 5).column, 2u);
  EXPECT_EQ(sm.LineText(a, 1), "ab");
  EXPECT_EQ(sm.LineText(a, 3), "");
  EXPECT_EQ(sm.LineText(a, 4), "ef");
  EXPECT_EQ(sm.LineText(a, 9), "");
  EXPECT_EQ(sm.CalcLineColumn(b, 0).column, 1u);
  EXPECT_EQ(sm.path(b), "b.prs");
  std::string_view text = sm.text(a);
  for (int i = 0; i < 100; ++i) sm.AddFile("x", "y");  // views stay valid as files are added
  EXPECT_EQ(text, "ab\r\ncd\n\nef");
}

TEST(SuggestClosestTest, EditDistance) {
  EXPECT_EQ(CalcEditDistance("Cube", "Cube"), 0u);
  EXPECT_EQ(CalcEditDistance("Cub", "Cube"), 1u);
  EXPECT_EQ(CalcEditDistance("Cbue", "Cube"), 1u);  // a transposition counts once
  EXPECT_EQ(CalcEditDistance("", "abc"), 3u);
  EXPECT_EQ(CalcEditDistance("kitten", "sitting"), 3u);
}

TEST(SuggestClosestTest, SuggestsOnlyCloseNames) {
  std::vector<std::string> classes = {"Table", "Tray", "Cube", "Camera"};
  EXPECT_EQ(SuggestClosest("Cub", classes), "Cube");
  EXPECT_EQ(SuggestClosest("Tabel", classes), "Table");
  EXPECT_EQ(SuggestClosest("Try", classes), "Tray");
  EXPECT_EQ(SuggestClosest("Robot", classes), "");
  EXPECT_EQ(SuggestClosest("X", {"Y"}), "Y");  // distance 1 is always allowed
  EXPECT_EQ(SuggestClosest("Cube", classes), "");  // the name itself is no suggestion
}

TEST(DiagnosticEngineTest, CountsErrorsNotWarnings) {
  DiagnosticEngine engine;
  Diagnostic w;
  w.severity = Severity::kWarning;
  engine.Report(w);
  EXPECT_FALSE(engine.has_errors());
  engine.Error("unknown-class", SourceSpan{}, "m");
  EXPECT_TRUE(engine.has_errors());
  EXPECT_EQ(engine.diagnostics().size(), 2u);
}

// 40,000 stray brackets: 50 errors kept, one "too many errors" line, more than 50 counted, and
// the same error reported twice kept once.
TEST(DiagnosticEngineTest, StopsKeepingErrorsAfterTheLimit) {
  SourceManager sm;
  const std::string line = "x = " + std::string(40'000, ')');
  FileId f = sm.AddFile("t.prs", line + "\n");
  DiagnosticEngine engine;
  Parse(f, sm, engine);
  EXPECT_EQ(engine.diagnostics().size(), DiagnosticEngine::kMaxErrors + 1);
  EXPECT_EQ(engine.diagnostics().back().id, "too-many-errors");
  EXPECT_GT(engine.error_count(), DiagnosticEngine::kMaxErrors);
  DiagnosticEngine twice;
  twice.Error("unknown-name", SourceSpan{f, 0, 1}, "unknown name 'x'");
  twice.Error("unknown-name", SourceSpan{f, 0, 1}, "unknown name 'x'");
  EXPECT_EQ(twice.diagnostics().size(), 1u);
}

TEST(ScenarioErrorTest, CarriesTheDiagnostic) {
  Diagnostic d;
  d.id = "unknown-class";
  d.message = "boom";
  try {
    throw ScenarioError(d);
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "boom");
    EXPECT_EQ(dynamic_cast<const ScenarioError&>(e).diagnostic().id, "unknown-class");
  }
}

TEST(CatalogueTest, IdsAreUniqueKebabCase) {
  std::set<std::string> seen;
  for (const DiagnosticKind& k : DiagnosticCatalogue()) {
    EXPECT_TRUE(seen.insert(k.id).second) << "duplicate id " << k.id;
    std::string id = k.id;
    EXPECT_TRUE(std::all_of(id.begin(), id.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
    })) << id;
    EXPECT_STRNE(k.description, "");
  }
  EXPECT_TRUE(IsKnownDiagnosticId("unknown-class"));
  EXPECT_FALSE(IsKnownDiagnosticId("no-such-id"));
}

// ---- data-driven bad programs ----

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::filesystem::path RepoRoot() {
  const char* dir = std::getenv("PRS_SOURCE_DIR");
  return dir ? std::filesystem::path(dir) : std::filesystem::path(PRS_DEFAULT_SOURCE_DIR);
}

TEST(BadProgramsTest, ParserDiagnosticsMatchExpectedFiles) {
  std::filesystem::path dir = RepoRoot() / "tests/lang/bad";
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  std::vector<std::filesystem::path> programs;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (name.rfind("parse_", 0) == 0 && entry.path().extension() == ".prs") {
      programs.push_back(entry.path());
    }
  }
  std::sort(programs.begin(), programs.end());
  EXPECT_GE(programs.size(), 20u);
  for (const std::filesystem::path& program : programs) {
    SCOPED_TRACE(program.filename().string());
    SourceManager sources;
    DiagnosticEngine diags;
    std::string relative = "tests/lang/bad/" + program.filename().string();
    FileId file = sources.AddFile(relative, ReadFile(program));
    ParseOptions options;
    options.import_classes = [](const std::string&, SourceSpan) {
      return std::optional<std::vector<std::string>>(std::vector<std::string>{});
    };
    Parse(file, sources, diags, options);
    std::string rendered;
    for (const Diagnostic& d : diags.diagnostics()) {
      EXPECT_TRUE(IsKnownDiagnosticId(d.id)) << "id missing from the catalogue: " << d.id;
      rendered += RenderDiagnostic(d, sources);
    }
    EXPECT_TRUE(diags.has_errors());
    std::filesystem::path expected = program;
    expected.replace_extension(".expected");
    EXPECT_EQ(rendered, ReadFile(expected));
  }
}

}  // namespace
}  // namespace prs::lang
