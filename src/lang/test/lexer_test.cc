// Tests for the lexer: indentation, line joining (brackets, backslash, trailing comma),
// strings, numbers and the positions of lexical errors.
#include "lang/lexer.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace prs::lang {
namespace {

struct LexResult {
  SourceManager sources;
  DiagnosticEngine diags;
  std::vector<Token> tokens;
};

std::unique_ptr<LexResult> LexText(const std::string& text) {
  auto r = std::make_unique<LexResult>();
  FileId f = r->sources.AddFile("test.prs", text);
  r->tokens = Lex(f, r->sources, r->diags);
  return r;
}

// A compact spelling of the token stream: names and numbers by lexeme, strings quoted,
// NEWLINE as ';', INDENT as '{', DEDENT as '}', operators by lexeme.
std::string Kinds(const std::vector<Token>& tokens) {
  std::string out;
  for (const Token& t : tokens) {
    if (!out.empty()) out += ' ';
    switch (t.kind) {
      case TokenKind::kNewline: out += ';'; break;
      case TokenKind::kIndent: out += '{'; break;
      case TokenKind::kDedent: out += '}'; break;
      case TokenKind::kEndOfFile: out += "EOF"; break;
      case TokenKind::kString: out += "'" + t.text + "'"; break;
      default: out += std::string(t.lexeme);
    }
  }
  return out;
}

TEST(LexerTest, IndentationProducesIndentAndDedent) {
  auto r = LexText("if a:\n    b = 1\n    if c:\n        d\ne\n");
  EXPECT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens), "if a : ; { b = 1 ; if c : ; { d ; } } e ; EOF");
}

TEST(LexerTest, DedentsAtEndOfFileWithoutTrailingNewline) {
  auto r = LexText("if a:\n  b");
  EXPECT_EQ(Kinds(r->tokens), "if a : ; { b ; } EOF");
}

TEST(LexerTest, BlankAndCommentLinesAreIgnored) {
  auto r = LexText("a\n\n   # comment\n\t\n  \nb  # trailing\n");
  EXPECT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens), "a ; b ; EOF");
}

TEST(LexerTest, TrailingCommaContinuesTheLogicalLine) {
  // The paper's Figure 1, including the trailing space after the first comma.
  auto r = LexText("tr_1 = Tray completely on t, \n            ahead of r1,\n            left of t\n"
                   "            \nx = 1\n");
  EXPECT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens),
            "tr_1 = Tray completely on t , ahead of r1 , left of t ; x = 1 ; EOF");
}

TEST(LexerTest, TrailingCommaContinuesPastCommentsAndBlankLines) {
  auto r = LexText("c = Cube on t,  # note\n\n    ahead of r\n");
  EXPECT_EQ(Kinds(r->tokens), "c = Cube on t , ahead of r ; EOF");
}

TEST(LexerTest, ImplicitJoiningInsideBrackets) {
  auto r = LexText("v = V3D((1,\n  2),\n [3,\n4], {5:\n 6})\ny\n");
  EXPECT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens), "v = V3D ( ( 1 , 2 ) , [ 3 , 4 ] , { 5 : 6 } ) ; y ; EOF");
}

TEST(LexerTest, BackslashContinuation) {
  auto r = LexText("x = 1 + \\\n    2\ny\n");
  EXPECT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens), "x = 1 + 2 ; y ; EOF");
}

// The position (line:column) and id of the first diagnostic.
std::string FirstError(const LexResult& r) {
  if (r.diags.diagnostics().empty()) return "none";
  const Diagnostic& d = r.diags.diagnostics()[0];
  LineColumn lc = r.sources.CalcLineColumn(d.span.file, d.span.begin);
  return d.id + "@" + std::to_string(lc.line) + ":" + std::to_string(lc.column);
}

TEST(LexerTest, StringsAndEscapes) {
  auto r = LexText(R"(a = 'x\ty' "q\"z\\" 'it\'s' "\n" '\d')" "\n");
  ASSERT_FALSE(r->diags.has_errors());
  ASSERT_EQ(r->tokens[2].kind, TokenKind::kString);
  EXPECT_EQ(r->tokens[2].text, "x\ty");
  EXPECT_EQ(r->tokens[3].text, "q\"z\\");
  EXPECT_EQ(r->tokens[4].text, "it's");
  EXPECT_EQ(r->tokens[5].text, "\n");
  EXPECT_EQ(r->tokens[6].text, "\\d");  // unknown escapes keep the backslash
  EXPECT_EQ(FirstError(*r), "unknown-escape@1:35");  // with a warning at the escape
  EXPECT_EQ(r->diags.diagnostics()[0].severity, Severity::kWarning);
}

TEST(LexerTest, HexAndUnicodeEscapes) {
  auto r = LexText(R"(a = '\x41\u00e9\u20ac')"
                   "\n");
  ASSERT_FALSE(r->diags.has_errors());
  EXPECT_TRUE(r->diags.diagnostics().empty());
  EXPECT_EQ(r->tokens[2].text, "A\xC3\xA9\xE2\x82\xAC");
  auto bad = LexText(R"(a = 'x\x4g')"
                     "\n");
  EXPECT_EQ(FirstError(*bad), "bad-escape@1:7");
  EXPECT_TRUE(bad->diags.has_errors());
}

TEST(LexerTest, TripleQuotedStringsSpanLines) {
  auto r = LexText("\"\"\"Models\nfor 'the' \"world\".\"\"\"\nx = '''a\nb'''\n");
  ASSERT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens), "'Models\nfor 'the' \"world\".' ; x = 'a\nb' ; EOF");
}

TEST(LexerTest, NumbersWithExponents) {
  auto r = LexText("1 2.5 .5 3. 1e3 2.5E-2 7e+1 0x1F");
  ASSERT_FALSE(r->diags.has_errors());
  std::vector<double> values;
  for (const Token& t : r->tokens) {
    if (t.kind == TokenKind::kNumber) values.push_back(t.number);
  }
  EXPECT_EQ(values, (std::vector<double>{1, 2.5, 0.5, 3, 1000, 0.025, 70, 31}));
}

TEST(LexerTest, OperatorsUseLongestMatch) {
  auto r = LexText("a ** b // c <= d >= e == f != g -> h += i -= j *= k /= l % m");
  ASSERT_FALSE(r->diags.has_errors());
  EXPECT_EQ(Kinds(r->tokens),
            "a ** b // c <= d >= e == f != g -> h += i -= j *= k /= l % m ; EOF");
}

TEST(LexerTest, SpecifierWordsAreNamesButHardKeywordsAreNot) {
  auto r = LexText("on top with in require param lambda");
  EXPECT_EQ(r->tokens[0].kind, TokenKind::kName);
  EXPECT_EQ(r->tokens[1].kind, TokenKind::kName);
  EXPECT_EQ(r->tokens[2].kind, TokenKind::kWith);
  EXPECT_EQ(r->tokens[3].kind, TokenKind::kIn);
  EXPECT_EQ(r->tokens[4].kind, TokenKind::kRequire);
  EXPECT_EQ(r->tokens[5].kind, TokenKind::kParam);
  EXPECT_EQ(r->tokens[6].kind, TokenKind::kLambda);
}

TEST(LexerTest, TokenSpansAreByteOffsets) {
  auto r = LexText("ab = 'cd'\n");
  EXPECT_EQ(r->tokens[0].span.begin, 0u);
  EXPECT_EQ(r->tokens[0].span.end, 2u);
  EXPECT_EQ(r->tokens[2].span.begin, 5u);
  EXPECT_EQ(r->tokens[2].span.end, 9u);
}

TEST(LexerTest, UnterminatedStringIsReportedAtItsStart) {
  auto r = LexText("x = 1\ny = 'abc\nz = 2\n");
  EXPECT_EQ(FirstError(*r), "unterminated-string@2:5");
  EXPECT_EQ(Kinds(r->tokens), "x = 1 ; y = 'abc' ; z = 2 ; EOF");  // lexing recovered
}

TEST(LexerTest, UnclosedBracketPointsAtTheOpener) {
  auto r = LexText("a = f(1,\n  [2, 3]\nb = 4\n");
  EXPECT_EQ(FirstError(*r), "unclosed-bracket@1:6");
  EXPECT_EQ(r->diags.diagnostics()[0].message, "'(' was never closed");
}

TEST(LexerTest, MismatchedCloserHasANoteAtTheOpener) {
  auto r = LexText("a = (1,\n 2]\n");
  ASSERT_EQ(r->diags.diagnostics().size(), 1u);
  EXPECT_EQ(FirstError(*r), "mismatched-bracket@2:3");
  const Diagnostic& d = r->diags.diagnostics()[0];
  ASSERT_EQ(d.notes.size(), 1u);
  EXPECT_EQ(d.notes[0].span.begin, 4u);
  ASSERT_EQ(Kinds(r->tokens), "a = ( 1 , 2 ] ; EOF");
  EXPECT_EQ(r->tokens[6].kind, TokenKind::kRParen);  // treated as the matching closer
}

TEST(LexerTest, StrayCloserIsReportedAndBecomesAnErrorToken) {
  auto r = LexText("a = 1)\nb\n");
  EXPECT_EQ(FirstError(*r), "unmatched-bracket@1:6");
  EXPECT_EQ(Kinds(r->tokens), "a = 1 ) ; b ; EOF");
  EXPECT_EQ(r->tokens[3].kind, TokenKind::kError);
}

TEST(LexerTest, DedentToUnknownLevel) {
  auto r = LexText("if a:\n    b\n  c\n");
  EXPECT_EQ(FirstError(*r), "inconsistent-dedent@3:3");
  EXPECT_EQ(r->diags.diagnostics()[0].message,
            "unindent does not match any outer indentation level");
}

TEST(LexerTest, InconsistentTabsAndSpaces) {
  auto r = LexText("if a:\n\tb\n        c\n");
  EXPECT_EQ(FirstError(*r), "inconsistent-tabs@3:1");
  auto ok = LexText("if a:\n\tb\n\tc\n");
  EXPECT_FALSE(ok->diags.has_errors());
}

TEST(LexerTest, InvalidCharactersAndNumbers) {
  EXPECT_EQ(FirstError(*LexText("x = 3 $ 4")), "invalid-character@1:7");
  EXPECT_EQ(FirstError(*LexText("x = 1e")), "invalid-number@1:5");
  EXPECT_EQ(FirstError(*LexText("x = 12abc")), "invalid-number@1:5");
  EXPECT_EQ(FirstError(*LexText("x = a | b")), "unsupported-feature@1:7");
}

TEST(LexerTest, ColumnsCountCodePoints) {
  auto r = LexText("s = 'é' $");
  EXPECT_EQ(FirstError(*r), "invalid-character@1:9");
}

}  // namespace
}  // namespace prs::lang
