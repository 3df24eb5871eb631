// Internal to the parser: the Parser class shared by parser.cc (tokens, errors, statements)
// and parser_expr.cc (expressions, side points, object creations and specifiers).
#pragma once

#include <fmt/format.h>

#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "lang/ast.h"
#include "lang/diagnostics.h"
#include "lang/parser.h"
#include "lang/token.h"

namespace prs::lang::internal {

using TK = TokenKind;

// Thrown after an error has been reported, to unwind to the statement loop.
struct ParseAbort {};

class Parser {
 public:
  Parser(FileId file, const SourceManager& sources, DiagnosticEngine& diags,
         const ParseOptions& options);
  Module Run();

 private:
  // ---- token access ----
  const Token& Peek(size_t ahead = 0) const {
    return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)];
  }
  bool Check(TK kind, size_t ahead = 0) const { return Peek(ahead).kind == kind; }
  bool CheckWord(std::string_view word, size_t ahead = 0) const {
    return Peek(ahead).kind == TK::kName && Peek(ahead).lexeme == word;
  }
  const Token& Advance();
  bool Match(TK kind);
  const Token& Expect(TK kind, std::string_view what);
  Identifier ExpectName(std::string_view what);
  SourceSpan SpanFrom(uint32_t begin) const { return SourceSpan{file_, begin, prev_end_}; }
  uint32_t Here() const { return Peek().span.begin; }

  // ---- errors ----
  [[noreturn]] void Fail(std::string id, SourceSpan span, std::string message,
                         std::string fix_it = "");
  [[noreturn]] void FailAtToken(std::string message);
  SourceSpan MissingSpan() const;
  struct NestingGuard {  // counts expression depth; the destructor also runs on errors
    explicit NestingGuard(Parser* parser);
    ~NestingGuard() { --parser_->expr_depth_; }
    Parser* parser_;
  };
  void Report(Diagnostic d);
  void Synchronize();
  void SkipBlock();

  // ---- statements ----
  void ParseStatementsUntilDedent(std::vector<StmtPtr>* out);
  void ParseStatement(std::vector<StmtPtr>* out);
  void ParseSimpleStatements(std::vector<StmtPtr>* out);
  StmtPtr ParseSimpleStatement();
  std::vector<StmtPtr> ParseBlock(const Token& header);
  StmtPtr ParseClassDef();
  void ParseClassBody(ClassDef* def, const Token& header);
  StmtPtr ParseFunctionDef();
  Param ParseParam();
  StmtPtr ParseIf();
  StmtPtr ParseFor();
  StmtPtr ParseWhile();
  StmtPtr ParseReturn();
  StmtPtr ParseRequire();
  StmtPtr ParseParamStmt();
  StmtPtr ParseImport();
  StmtPtr ParseFromImport();
  StmtPtr ParseExprOrAssign();
  StmtPtr MakeAssign(uint32_t begin, ExprPtr target, ExprPtr value);
  void ExpectStatementEnd();
  [[noreturn]] void FailUnsupportedStatement();

  // ---- expressions ----
  ExprPtr ParseExprList();
  ExprPtr ParseExpr();
  ExprPtr ParseOr();
  ExprPtr ParseAnd();
  ExprPtr ParseNot();
  ExprPtr ParseComparison();
  ExprPtr ParseRelative();
  ExprPtr ParseAdditive();
  ExprPtr ParseMultiplicative();
  ExprPtr ParseUnary();
  ExprPtr ParsePower();
  ExprPtr ParsePostfix();
  ExprPtr ParseCall(ExprPtr callee);
  ExprPtr ParseIndex(ExprPtr object);
  ExprPtr ParseAtom();
  ExprPtr ParseName();
  ExprPtr ParseString();
  ExprPtr ParseParenthesized();
  ExprPtr ParseList();
  ExprPtr ParseDict();
  ExprPtr ParseDistance();
  std::optional<ExprPtr> TryParseSidePoint();
  bool CanStartExpression(const Token& t) const;
  bool CanStartOperand(size_t ahead) const;
  void RejectComprehension(std::string_view what);
  ExprPtr MakeExpr(uint32_t begin, auto node) {
    return WithHeight(std::make_unique<Expr>(Expr{SpanFrom(begin), std::move(node)}));
  }
  ExprPtr WithHeight(ExprPtr e);
  ExprPtr MakeBinary(BinaryOp op, ExprPtr lhs, ExprPtr rhs, SourceSpan op_span);

  // ---- object creation ----
  bool IsClassName(std::string_view name) const;
  bool IsSpecifierStart(size_t ahead) const;
  ExprPtr ParseCreation();
  Specifier ParseSpecifier();
  void ParseSpecifierTail(Specifier* s, const Token& keyword);
  void ParseVisibilitySpecifier(Specifier* s, const Token& keyword);
  void ParseReachableOptions(Specifier* s);
  void ParseAlignedAxis(Specifier* s);
  ExprPtr ParseSpecifierArg(std::string_view after);
  std::optional<ExprPtr> ParseOptionalBy();
  void ExpectWord(std::string_view word, std::string_view after);
  [[noreturn]] void FailUnknownClass(const Token& name);
  [[noreturn]] void FailUnknownCompoundSide();
  void CheckMisspelledSpecifier(const Token& class_name, bool after_comma);
  void AddClass(const std::string& name, std::optional<SourceSpan> where);

  FileId file_;
  const SourceManager& sources_;
  DiagnosticEngine& diags_;
  DiagnosticEngine lexer_diags_;
  std::vector<Diagnostic> parse_diags_;
  const ParseOptions& options_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  uint32_t prev_end_ = 0;
  uint32_t suppress_from_ = UINT32_MAX;  // errors at or past an unclosed bracket are noise
  std::vector<std::string> class_names_;
  std::unordered_map<std::string, std::optional<SourceSpan>> class_defs_;
  bool failed_import_ = false;
  static constexpr int kMaxNesting = 100;     // nested blocks
  static constexpr int kMaxExprDepth = 400;  // nested expression routines (not tokens)
  // The tallest expression tree (Expr::height) a program may build: long flat chains
  // (`1 + 1 + ...`, `f()()...`, `a[0][0]...`) build trees as deep as nested brackets do, and
  // the resolver, interpreter and destructors walk trees recursively.
  static constexpr uint32_t kMaxExprHeight = 400;
  int expr_depth_ = 0;
  int block_depth_ = 0;
  int function_depth_ = 0;
  int loop_depth_ = 0;
  // Where the expression being parsed sits; reset inside brackets.
  struct Context {
    bool in_specifier_arg = false;  // a name followed by `ahead` is a missing ',', not a class
    bool stop_at_on = false;        // inside `aligned with X on AXIS`: `on` ends X
  };
  Context context_;
};

}  // namespace prs::lang::internal
