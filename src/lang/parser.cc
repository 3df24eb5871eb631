// The recursive-descent parser, part 1: token access, error reporting and recovery, and
// statements. Expressions are in parser_expr.cc. Each routine opens with its grammar rule.
#include "lang/parser.h"

#include <fmt/format.h>

#include <algorithm>

#include "lang/lexer.h"
#include "lang/parser_internal.h"

namespace prs::lang {
namespace internal {
namespace {

// What an assignment target is, for "cannot assign to ..." messages.
std::string_view DescribeTarget(const Expr& e) {
  return std::visit(
      [](const auto& n) -> std::string_view {
        using T = std::decay_t<decltype(n)>;
        if constexpr (std::is_same_v<T, NumberLit> || std::is_same_v<T, StringLit> ||
                      std::is_same_v<T, BoolLit> || std::is_same_v<T, NoneLit>) {
          return "a literal";
        } else if constexpr (std::is_same_v<T, AttributeExpr>) {
          return "an attribute";
        } else if constexpr (std::is_same_v<T, IndexExpr>) {
          return "an indexed element";
        } else if constexpr (std::is_same_v<T, CallExpr>) {
          return "a function call";
        } else if constexpr (std::is_same_v<T, CreateObject>) {
          return "an object creation";
        } else if constexpr (std::is_same_v<T, ClassRef>) {
          return "a class";
        } else {
          return "an expression";
        }
      },
      e.node);
}

}  // namespace

Parser::Parser(FileId file, const SourceManager& sources, DiagnosticEngine& diags,
               const ParseOptions& options)
    : file_(file), sources_(sources), diags_(diags), options_(options) {
  tokens_ = Lex(file, sources, lexer_diags_);
  for (const Diagnostic& d : lexer_diags_.diagnostics()) {
    if (d.id != "unclosed-bracket") continue;
    // Past the line of an unclosed bracket every parse error is a consequence of it.
    LineColumn lc = sources.CalcLineColumn(file, d.span.begin);
    uint32_t next_line = sources.LineStart(file, lc.line + 1);
    suppress_from_ = std::min(suppress_from_, next_line);
  }
  for (const std::string& name : BuiltinClassNames()) AddClass(name, std::nullopt);
}

Module Parser::Run() {
  Module module{file_, {}};
  while (!Check(TK::kEndOfFile)) {
    if (Check(TK::kDedent)) {  // only after an inconsistent dedent, already reported
      Advance();
      continue;
    }
    ParseStatement(&module.body);
  }
  // Lexer and parser errors, in source order.
  std::vector<Diagnostic> all = lexer_diags_.diagnostics();
  all.insert(all.end(), parse_diags_.begin(), parse_diags_.end());
  std::stable_sort(all.begin(), all.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return a.span.begin < b.span.begin;
  });
  for (Diagnostic& d : all) diags_.Report(std::move(d));
  return module;
}

// ---------------------------------------------------------------------------
// Tokens and errors
// ---------------------------------------------------------------------------

const Token& Parser::Advance() {
  const Token& t = tokens_[pos_];
  if (pos_ + 1 < tokens_.size()) ++pos_;
  if (t.kind != TK::kNewline && t.kind != TK::kIndent && t.kind != TK::kDedent) {
    prev_end_ = t.span.end;
  }
  return t;
}

bool Parser::Match(TK kind) {
  if (!Check(kind)) return false;
  Advance();
  return true;
}

const Token& Parser::Expect(TK kind, std::string_view what) {
  if (!Check(kind)) {
    FailAtToken(fmt::format("expected {}{}, found {}", TokenKindName(kind), what,
                            DescribeToken(Peek())));
  }
  return Advance();
}

Identifier Parser::ExpectName(std::string_view what) {
  if (!Check(TK::kName)) FailAtToken(fmt::format("expected {}, found {}", what, DescribeToken(Peek())));
  const Token& t = Advance();
  return Identifier{std::string(t.lexeme), t.span};
}

void Parser::Report(Diagnostic d) {
  if (d.has_span && d.span.begin >= suppress_from_) return;
  // With an unclosed bracket the rest of the file is one logical line, so reaching its end
  // early is a consequence of that bracket.
  bool at_end = Check(TK::kNewline) || Check(TK::kEndOfFile) || Check(TK::kDedent);
  if (suppress_from_ != UINT32_MAX && at_end) return;
  parse_diags_.push_back(std::move(d));
}

void Parser::Fail(std::string id, SourceSpan span, std::string message, std::string fix_it) {
  Diagnostic d;
  d.id = std::move(id);
  d.span = span;
  d.message = std::move(message);
  d.fix_it = std::move(fix_it);
  Report(std::move(d));
  throw ParseAbort{};
}

void Parser::FailAtToken(std::string message) {
  const Token& t = Peek();
  if (t.kind == TK::kError) throw ParseAbort{};  // the lexer already reported it
  std::string id = message.rfind("expected an expression", 0) == 0 ? "expected-expression"
                                                                   : "expected-token";
  Fail(id, MissingSpan(), std::move(message));
}

// Where to point when something is missing: the next token, or just past the last token
// of the line when the line (or the file) has ended.
SourceSpan Parser::MissingSpan() const {
  const Token& t = Peek();
  if (t.kind == TK::kNewline || t.kind == TK::kEndOfFile) return {file_, prev_end_, prev_end_};
  return t.span;
}

// Skips to the start of the next statement: past the NEWLINE ending this logical line and,
// if an indented block follows (the body of a broken header), past that block too.
void Parser::Synchronize() {
  while (!Check(TK::kNewline) && !Check(TK::kEndOfFile) && !Check(TK::kDedent)) {
    if (Check(TK::kIndent)) {
      SkipBlock();
      continue;
    }
    Advance();
  }
  if (Match(TK::kNewline) && Check(TK::kIndent)) SkipBlock();
}

// Skips an INDENT ... DEDENT block including nested blocks.
void Parser::SkipBlock() {
  int depth = 0;
  do {
    if (Check(TK::kIndent)) ++depth;
    if (Check(TK::kDedent)) --depth;
    if (Check(TK::kEndOfFile)) return;
    Advance();
  } while (depth > 0);
}

// ---------------------------------------------------------------------------
// Statements
// ---------------------------------------------------------------------------

// statement := compound_stmt | simple_stmt {';' simple_stmt} [';'] NEWLINE
void Parser::ParseStatement(std::vector<StmtPtr>* out) {
  try {
    switch (Peek().kind) {
      case TK::kIndent:
        Advance();
        Fail("unexpected-indent", Peek().span, "unexpected indent");
      case TK::kClass: out->push_back(ParseClassDef()); return;
      case TK::kDef: out->push_back(ParseFunctionDef()); return;
      case TK::kIf: out->push_back(ParseIf()); return;
      case TK::kFor: out->push_back(ParseFor()); return;
      case TK::kWhile: out->push_back(ParseWhile()); return;
      default: ParseSimpleStatements(out); return;
    }
  } catch (const ParseAbort&) {
    if (pos_ > 0 && tokens_[pos_ - 1].kind == TK::kIndent) --pos_;  // let SkipBlock see it
    Synchronize();
  }
}

void Parser::ParseStatementsUntilDedent(std::vector<StmtPtr>* out) {
  while (!Check(TK::kDedent) && !Check(TK::kEndOfFile)) ParseStatement(out);
  Match(TK::kDedent);
}

void Parser::ParseSimpleStatements(std::vector<StmtPtr>* out) {
  // A docstring parses to null (it is dropped), wherever it stands on the line.
  auto add = [out](StmtPtr stmt) {
    if (stmt) out->push_back(std::move(stmt));
  };
  add(ParseSimpleStatement());
  while (Match(TK::kSemicolon)) {
    if (Check(TK::kNewline) || Check(TK::kEndOfFile)) break;
    add(ParseSimpleStatement());
  }
  ExpectStatementEnd();
}

void Parser::ExpectStatementEnd() {
  if (Match(TK::kNewline) || Check(TK::kEndOfFile)) return;
  if (Check(TK::kColon) && tokens_[pos_ - 1].kind == TK::kName) {
    Fail("unsupported-feature", Peek().span,
         "type annotations are not supported in ProbRobScene (class properties are written "
         "'name: value' inside a class)");
  }
  if (Check(TK::kError)) throw ParseAbort{};  // already reported by the lexer
  Fail("expected-statement-end", Peek().span,
       fmt::format("expected end of statement, found {}", DescribeToken(Peek())));
}

// simple_stmt := pass | break | continue | return_stmt | require_stmt | param_stmt
//              | import_stmt | from_import | assignment | expr_list
StmtPtr Parser::ParseSimpleStatement() {
  uint32_t begin = Here();
  switch (Peek().kind) {
    case TK::kPass: Advance(); return std::make_unique<Stmt>(Stmt{SpanFrom(begin), PassStmt{}});
    case TK::kBreak:
    case TK::kContinue: {
      const Token& t = Advance();
      if (loop_depth_ == 0) {
        Fail("outside-loop", t.span, fmt::format("'{}' outside a loop", t.lexeme));
      }
      if (t.kind == TK::kBreak) return std::make_unique<Stmt>(Stmt{SpanFrom(begin), BreakStmt{}});
      return std::make_unique<Stmt>(Stmt{SpanFrom(begin), ContinueStmt{}});
    }
    case TK::kReturn: return ParseReturn();
    case TK::kRequire: return ParseRequire();
    case TK::kParam: return ParseParamStmt();
    case TK::kImport: return ParseImport();
    case TK::kFrom: return ParseFromImport();
    case TK::kWith: case TK::kGlobal: case TK::kNonlocal: case TK::kTry: case TK::kExcept:
    case TK::kFinally: case TK::kRaise: case TK::kDel: case TK::kAssert: case TK::kAsync:
    case TK::kAt: case TK::kElif: case TK::kElse:
      FailUnsupportedStatement();
    default: return ParseExprOrAssign();
  }
}

void Parser::FailUnsupportedStatement() {
  const Token& t = Peek();
  if (t.kind == TK::kAt) {
    Fail("unsupported-feature", t.span, "decorators are not supported in ProbRobScene");
  }
  if (t.kind == TK::kElif || t.kind == TK::kElse) {
    Fail("expected-token", t.span, fmt::format("'{}' without a matching 'if'", t.lexeme));
  }
  Fail("unsupported-feature", t.span,
       fmt::format("'{}' statements are not supported in ProbRobScene", t.lexeme));
}

// block := ':' (simple_stmts | NEWLINE INDENT statement+ DEDENT)
std::vector<StmtPtr> Parser::ParseBlock(const Token& header) {
  Expect(TK::kColon, fmt::format(" after the '{}' header", header.lexeme));
  std::vector<StmtPtr> body;
  if (block_depth_ >= kMaxNesting) {
    Fail("too-deeply-nested", header.span, "blocks are nested too deeply");
  }
  ++block_depth_;
  if (!Match(TK::kNewline)) {
    ParseSimpleStatements(&body);
  } else if (!Match(TK::kIndent)) {
    --block_depth_;
    LineColumn lc = sources_.CalcLineColumn(file_, header.span.begin);
    Fail("expected-indented-block", MissingSpan(),
         fmt::format("expected an indented block after '{}' on line {}", header.lexeme, lc.line));
  } else {
    ParseStatementsUntilDedent(&body);
  }
  --block_depth_;
  return body;
}

// class_def := 'class' NAME ['(' NAME ')'] ':' NEWLINE INDENT {NAME ':' expr NEWLINE
//              | 'pass' NEWLINE | STRING NEWLINE} DEDENT
StmtPtr Parser::ParseClassDef() {
  const Token& header = Advance();
  uint32_t begin = header.span.begin;
  if (block_depth_ > 0) {
    Fail("nested-definition", header.span, "classes can only be defined at the top level");
  }
  ClassDef def;
  def.name = ExpectName("a class name after 'class'");
  if (Match(TK::kLParen)) {
    def.parent = ExpectName("the parent class name after '('");
    if (!IsClassName(def.parent->name) && !failed_import_) {
      --pos_;
      FailUnknownClass(Peek());
    }
    Expect(TK::kRParen, " after the parent class name");
  }
  AddClass(def.name.name, def.name.span);
  Expect(TK::kColon, " after the class header");
  ParseClassBody(&def, header);
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(def)});
}

void Parser::ParseClassBody(ClassDef* def, const Token& header) {
  if (Match(TK::kPass)) return ExpectStatementEnd();
  Expect(TK::kNewline, " after ':'");
  if (!Match(TK::kIndent)) {
    LineColumn lc = sources_.CalcLineColumn(file_, header.span.begin);
    Fail("expected-indented-block", MissingSpan(),
         fmt::format("expected an indented block after 'class' on line {}", lc.line));
  }
  while (!Check(TK::kDedent) && !Check(TK::kEndOfFile)) {
    try {
      if (Match(TK::kPass) || (Check(TK::kString) && Check(TK::kNewline, 1) && Match(TK::kString))) {
        ExpectStatementEnd();
        continue;
      }
      Identifier name = ExpectName("a property line 'name: value' in the class body");
      if (Check(TK::kAssign)) {
        Fail("bad-class-body", Peek().span,
             "class properties are written 'name: value', not 'name = value'", ":");
      }
      Expect(TK::kColon, " after the property name");
      def->properties.push_back(PropertyDecl{std::move(name), ParseExpr()});
      ExpectStatementEnd();
    } catch (const ParseAbort&) {
      Synchronize();
    }
  }
  Match(TK::kDedent);
}

// function_def := 'def' NAME '(' [param {',' param} [',']] ')' block
StmtPtr Parser::ParseFunctionDef() {
  const Token& header = Advance();
  uint32_t begin = header.span.begin;
  FunctionDef def;
  def.name = ExpectName("a function name after 'def'");
  Expect(TK::kLParen, " after the function name");
  bool seen_default = false;
  while (!Check(TK::kRParen)) {
    Param p = ParseParam();
    for (const Param& q : def.params) {
      if (q.name.name == p.name.name) {
        Fail("duplicate-parameter", p.name.span,
             fmt::format("duplicate parameter '{}'", p.name.name));
      }
    }
    if (p.default_value) seen_default = true;
    else if (seen_default) {
      Fail("bad-default-order", p.name.span,
           "a parameter without a default cannot follow one with a default");
    }
    def.params.push_back(std::move(p));
    if (!Match(TK::kComma)) break;
  }
  Expect(TK::kRParen, " after the parameters");
  if (Check(TK::kArrow)) {
    Fail("unsupported-feature", Peek().span,
         "return type annotations are not supported in ProbRobScene");
  }
  ++function_depth_;
  int saved_loops = loop_depth_;
  loop_depth_ = 0;
  def.body = ParseBlock(header);
  loop_depth_ = saved_loops;
  --function_depth_;
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(def)});
}

// param := NAME ['=' expr]
Param Parser::ParseParam() {
  if (Check(TK::kStar) || Check(TK::kDoubleStar)) {
    Fail("unsupported-feature", Peek().span,
         "'*args' and '**kwargs' parameters are not supported in ProbRobScene");
  }
  Param p;
  p.name = ExpectName("a parameter name");
  if (Check(TK::kColon)) {
    Fail("unsupported-feature", Peek().span,
         "parameter annotations are not supported in ProbRobScene");
  }
  if (Match(TK::kAssign)) p.default_value = ParseExpr();
  return p;
}

// if_stmt := 'if' expr block {'elif' expr block} ['else' block]
StmtPtr Parser::ParseIf() {
  uint32_t begin = Here();
  IfStmt stmt;
  do {
    const Token& header = Advance();
    ExprPtr cond = ParseExpr();
    stmt.branches.emplace_back(std::move(cond), ParseBlock(header));
  } while (Check(TK::kElif));
  if (Check(TK::kElse)) {
    const Token& header = Advance();
    stmt.else_body = ParseBlock(header);
  }
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// for_stmt := 'for' NAME {',' NAME} 'in' expr_list block
StmtPtr Parser::ParseFor() {
  const Token& header = Advance();
  uint32_t begin = header.span.begin;
  ForStmt stmt;
  do {
    stmt.targets.push_back(ExpectName("a loop variable name"));
  } while (Match(TK::kComma) && !Check(TK::kIn));
  Expect(TK::kIn, " after the loop variable");
  stmt.iterable = ParseExprList();
  ++loop_depth_;
  stmt.body = ParseBlock(header);
  --loop_depth_;
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// while_stmt := 'while' expr block
StmtPtr Parser::ParseWhile() {
  const Token& header = Advance();
  uint32_t begin = header.span.begin;
  WhileStmt stmt;
  stmt.condition = ParseExpr();
  ++loop_depth_;
  stmt.body = ParseBlock(header);
  --loop_depth_;
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// return_stmt := 'return' [expr_list]
StmtPtr Parser::ParseReturn() {
  const Token& t = Advance();
  if (function_depth_ == 0) Fail("outside-function", t.span, "'return' outside a function");
  ReturnStmt stmt;
  if (!Check(TK::kNewline) && !Check(TK::kSemicolon) && !Check(TK::kEndOfFile)) {
    stmt.value = ParseExprList();
  }
  return std::make_unique<Stmt>(Stmt{SpanFrom(t.span.begin), std::move(stmt)});
}

// require_stmt := 'require' ['[' expr ']'] ['settled'] expr
// (`settled` followed by an expression is the keyword; `require settled` alone reads a name.)
StmtPtr Parser::ParseRequire() {
  uint32_t begin = Advance().span.begin;
  RequireStmt stmt;
  if (Match(TK::kLBracket)) {
    stmt.probability = ParseExpr();
    Expect(TK::kRBracket, " after the requirement's probability");
  }
  if (CheckWord("settled") && CanStartExpression(Peek(1))) {
    Advance();
    stmt.settled = true;
  }
  if (!CanStartExpression(Peek())) {
    FailAtToken(fmt::format("expected an expression after 'require', found {}",
                            DescribeToken(Peek())));
  }
  stmt.condition = ParseExpr();
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// param_stmt := 'param' NAME '=' expr {',' NAME '=' expr}
StmtPtr Parser::ParseParamStmt() {
  uint32_t begin = Advance().span.begin;
  ParamStmt stmt;
  do {
    Identifier name = ExpectName("a parameter name after 'param'");
    Expect(TK::kAssign, fmt::format(" after the parameter name '{}'", name.name));
    stmt.params.emplace_back(std::move(name), ParseExpr());
  } while (Match(TK::kComma));
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// import_stmt := 'import' NAME
StmtPtr Parser::ParseImport() {
  uint32_t begin = Advance().span.begin;
  ImportStmt stmt{ExpectName("a module name after 'import'")};
  if (Check(TK::kDot) || Check(TK::kAs) || Check(TK::kComma)) {
    Fail("unsupported-feature", Peek().span,
         "only 'import NAME' and 'from NAME import *' are supported in ProbRobScene");
  }
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

// from_import := 'from' NAME 'import' '*'
StmtPtr Parser::ParseFromImport() {
  uint32_t begin = Advance().span.begin;
  FromImportStmt stmt{ExpectName("a module name after 'from'")};
  if (Check(TK::kDot)) {
    Fail("unsupported-feature", Peek().span,
         "dotted module names are not supported in ProbRobScene; modules are plain file names");
  }
  Expect(TK::kImport, " after the module name");
  if (!Check(TK::kStar)) {
    Fail("unsupported-feature", Peek().span,
         "only 'from NAME import *' is supported in ProbRobScene", "*");
  }
  Advance();
  SourceSpan span = SpanFrom(begin);
  if (options_.import_classes) {
    std::optional<std::vector<std::string>> classes = options_.import_classes(stmt.module.name, span);
    if (!classes) failed_import_ = true;
    else for (const std::string& c : *classes) AddClass(c, std::nullopt);
  }
  return std::make_unique<Stmt>(Stmt{span, std::move(stmt)});
}

// assignment := target_list '=' expr_list | NAME ('+='|'-='|'*='|'/=') expr
// expr_stmt := expr_list            (a string on its own is a docstring and is dropped)
StmtPtr Parser::ParseExprOrAssign() {
  uint32_t begin = Here();
  ExprPtr lhs = ParseExprList();
  if (Check(TK::kAssign)) {
    Advance();
    ExprPtr value = ParseExprList();
    if (Check(TK::kAssign)) {
      Fail("unsupported-feature", Peek().span,
           "chained assignment 'a = b = value' is not supported in ProbRobScene");
    }
    return MakeAssign(begin, std::move(lhs), std::move(value));
  }
  static const std::pair<TK, BinaryOp> kAugmented[] = {{TK::kPlusAssign, BinaryOp::kAdd},
                                                       {TK::kMinusAssign, BinaryOp::kSub},
                                                       {TK::kStarAssign, BinaryOp::kMul},
                                                       {TK::kSlashAssign, BinaryOp::kDiv}};
  for (auto [kind, op] : kAugmented) {
    if (!Check(kind)) continue;
    auto* name = std::get_if<NameRef>(&lhs->node);
    if (!name) {
      Fail("invalid-assignment-target", lhs->span,
           fmt::format("cannot assign to {}; only a name can be the target of '{}'",
                       DescribeTarget(*lhs), Peek().lexeme));
    }
    Advance();
    AugAssignStmt stmt{Identifier{name->name, lhs->span}, op, ParseExpr()};
    return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
  }
  if (std::holds_alternative<StringLit>(lhs->node)) return nullptr;  // docstring
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), ExprStmt{std::move(lhs)}});
}

StmtPtr Parser::MakeAssign(uint32_t begin, ExprPtr target, ExprPtr value) {
  AssignStmt stmt;
  stmt.is_tuple_unpack = false;
  const std::vector<ExprPtr>* elements = nullptr;
  if (auto* t = std::get_if<TupleExpr>(&target->node)) elements = &t->elements;
  if (auto* l = std::get_if<ListExpr>(&target->node)) elements = &l->elements;
  if (elements) {
    stmt.is_tuple_unpack = true;
    for (const ExprPtr& e : *elements) {
      auto* name = std::get_if<NameRef>(&e->node);
      if (!name) {
        Fail("invalid-assignment-target", e->span,
             fmt::format("cannot assign to {}; only names can be unpacked into",
                         DescribeTarget(*e)));
      }
      stmt.targets.push_back(Identifier{name->name, e->span});
    }
  } else if (auto* name = std::get_if<NameRef>(&target->node)) {
    stmt.targets.push_back(Identifier{name->name, target->span});
  } else {
    Fail("invalid-assignment-target", target->span,
         fmt::format("cannot assign to {}; only a name or a tuple of names can be assigned to",
                     DescribeTarget(*target)));
  }
  stmt.value = std::move(value);
  return std::make_unique<Stmt>(Stmt{SpanFrom(begin), std::move(stmt)});
}

}  // namespace internal

const std::vector<std::string>& BuiltinClassNames() {
  static const std::vector<std::string> kNames = {"Point3D", "OrientedPoint3D", "Object"};
  return kNames;
}

Module Parse(FileId file, const SourceManager& sources, DiagnosticEngine& diagnostics,
             const ParseOptions& options) {
  return internal::Parser(file, sources, diagnostics, options).Run();
}

}  // namespace prs::lang
