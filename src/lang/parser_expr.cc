// The recursive-descent parser, part 2: expressions from the conditional down to atoms,
// side points (`top back of t`) and `distance from` (object creations: parser_creation.cc).
#include <fmt/format.h>

#include <algorithm>
#include <unordered_map>

#include "lang/parser_internal.h"

namespace prs::lang::internal {
namespace {

const std::unordered_map<std::string_view, Side>& SideWords() {
  static const std::unordered_map<std::string_view, Side> kSides = {
      {"front", Side::kFront}, {"back", Side::kBack},   {"left", Side::kLeft},
      {"right", Side::kRight}, {"top", Side::kTop},     {"bottom", Side::kBottom}};
  return kSides;
}

std::optional<Side> CompoundSide(Side first, std::string_view second) {
  if (first == Side::kFront && second == "left") return Side::kFrontLeft;
  if (first == Side::kFront && second == "right") return Side::kFrontRight;
  if (first == Side::kBack && second == "left") return Side::kBackLeft;
  if (first == Side::kBack && second == "right") return Side::kBackRight;
  if (first == Side::kTop && second == "front") return Side::kTopFront;
  if (first == Side::kTop && second == "back") return Side::kTopBack;
  return std::nullopt;
}

// Words that continue a specifier or operator and so can never be a side point's operand.
bool IsContinuationWord(std::string_view w) {
  return w == "by" || w == "to" || w == "on" || w == "along" || w == "of" ||
         w == "relative" || w == "offset";
}

std::optional<BinaryOp> ComparisonOp(TK kind) {
  switch (kind) {
    case TK::kLess: return BinaryOp::kLt;
    case TK::kLessEq: return BinaryOp::kLe;
    case TK::kGreater: return BinaryOp::kGt;
    case TK::kGreaterEq: return BinaryOp::kGe;
    case TK::kEqEq: return BinaryOp::kEq;
    case TK::kNotEq: return BinaryOp::kNe;
    default: return std::nullopt;
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// Expressions, lowest precedence first
// ---------------------------------------------------------------------------

// expr_list := expr {',' expr} [',']      (a TupleExpr when there is a comma)
ExprPtr Parser::ParseExprList() {
  uint32_t begin = Here();
  ExprPtr first = ParseExpr();
  if (!Check(TK::kComma)) return first;
  TupleExpr tuple;
  tuple.elements.push_back(std::move(first));
  while (Match(TK::kComma) && CanStartExpression(Peek())) tuple.elements.push_back(ParseExpr());
  return MakeExpr(begin, std::move(tuple));
}

// expr := or_expr ['if' or_expr 'else' expr]
ExprPtr Parser::ParseExpr() {
  if (Check(TK::kLambda)) {
    Fail("unsupported-feature", Peek().span,
         "lambda expressions are not supported in ProbRobScene; define a function with 'def'");
  }
  uint32_t begin = Here();
  NestingGuard guard(this);
  ExprPtr value = ParseOr();
  if (!Match(TK::kIf)) return value;
  ExprPtr cond = ParseOr();
  Expect(TK::kElse, " in the conditional expression 'a if condition else b'");
  ExprPtr other = ParseExpr();
  return MakeExpr(begin, ConditionalExpr{std::move(cond), std::move(value), std::move(other)});
}

// Guards the recursion so a pathological input reports an error instead of overflowing
// the stack.
Parser::NestingGuard::NestingGuard(Parser* parser) : parser_(parser) {
  if (++parser_->expr_depth_ > kMaxExprDepth) {
    --parser_->expr_depth_;  // no destructor runs when a constructor throws
    parser_->Fail("too-deeply-nested", parser_->Peek().span, "expression nested too deeply");
  }
}

ExprPtr Parser::MakeBinary(BinaryOp op, ExprPtr lhs, ExprPtr rhs, SourceSpan op_span) {
  SourceSpan span = Join(lhs->span, rhs->span);
  return WithHeight(
      std::make_unique<Expr>(Expr{span, BinaryExpr{op, std::move(lhs), std::move(rhs), op_span}}));
}

// Sets a new node's height and refuses a tree taller than kMaxExprHeight, pointing at the token
// that made it too tall. Refusing here, while the tree is still short, keeps every later walk
// over it (and its destruction) within the stack.
ExprPtr Parser::WithHeight(ExprPtr e) {
  e->height = CalcExprHeight(*e);
  if (e->height > kMaxExprHeight) {
    const SourceSpan last = tokens_[pos_ > 0 ? pos_ - 1 : 0].span;
    Fail("too-deeply-nested", last,
         fmt::format("expression nested too deeply: more than {} levels of operators, calls, "
                     "subscripts or brackets; split it into several statements",
                     kMaxExprHeight),
         "");
  }
  return e;
}

// or_expr := and_expr {'or' and_expr}
ExprPtr Parser::ParseOr() {
  ExprPtr lhs = ParseAnd();
  while (Check(TK::kOr)) {
    SourceSpan op = Advance().span;
    lhs = MakeBinary(BinaryOp::kOr, std::move(lhs), ParseAnd(), op);
  }
  return lhs;
}

// and_expr := not_expr {'and' not_expr}
ExprPtr Parser::ParseAnd() {
  ExprPtr lhs = ParseNot();
  while (Check(TK::kAnd)) {
    SourceSpan op = Advance().span;
    lhs = MakeBinary(BinaryOp::kAnd, std::move(lhs), ParseNot(), op);
  }
  return lhs;
}

// not_expr := 'not' not_expr | comparison
ExprPtr Parser::ParseNot() {
  if (!Check(TK::kNot)) return ParseComparison();
  uint32_t begin = Advance().span.begin;
  NestingGuard guard(this);
  ExprPtr operand = ParseNot();
  return MakeExpr(begin, UnaryExpr{UnaryOp::kNot, std::move(operand)});
}

// comparison := relative {comp_op relative}
// comp_op := '<' | '<=' | '>' | '>=' | '==' | '!=' | 'in' | 'not' 'in' | 'is' ['not']
ExprPtr Parser::ParseComparison() {
  uint32_t begin = Here();
  CompareChain chain;
  chain.operands.push_back(ParseRelative());
  while (true) {
    std::optional<BinaryOp> op = ComparisonOp(Peek().kind);
    uint32_t op_begin = Here();
    if (op) {
      Advance();
    } else if (Check(TK::kIn)) {
      Advance(), op = BinaryOp::kIn;
    } else if (Check(TK::kNot) && Check(TK::kIn, 1)) {
      Advance(), Advance(), op = BinaryOp::kNotIn;
    } else if (Check(TK::kIs)) {
      Advance();
      op = Match(TK::kNot) ? BinaryOp::kIsNot : BinaryOp::kIs;
    } else {
      break;
    }
    chain.ops.push_back(*op);
    chain.op_spans.push_back(SpanFrom(op_begin));
    chain.operands.push_back(ParseRelative());
  }
  if (chain.ops.empty()) return std::move(chain.operands[0]);
  if (chain.ops.size() == 1) {
    return MakeBinary(chain.ops[0], std::move(chain.operands[0]), std::move(chain.operands[1]),
                      chain.op_spans[0]);
  }
  return MakeExpr(begin, std::move(chain));
}

// relative := additive {('relative' 'to' | 'offset' 'by') additive}
ExprPtr Parser::ParseRelative() {
  uint32_t begin = Here();
  ExprPtr lhs = ParseAdditive();
  while (true) {
    if (CheckWord("relative") && CheckWord("to", 1)) {
      Advance(), Advance();
      ExprPtr rhs = ParseAdditive();
      lhs = MakeExpr(begin, RelativeToExpr{std::move(lhs), std::move(rhs)});
    } else if (CheckWord("offset") && CheckWord("by", 1)) {
      Advance(), Advance();
      ExprPtr rhs = ParseAdditive();
      lhs = MakeExpr(begin, OffsetByExpr{std::move(lhs), std::move(rhs)});
    } else {
      return lhs;
    }
  }
}

// additive := multiplicative {('+' | '-') multiplicative}
ExprPtr Parser::ParseAdditive() {
  ExprPtr lhs = ParseMultiplicative();
  while (Check(TK::kPlus) || Check(TK::kMinus)) {
    const Token& op = Advance();
    BinaryOp bop = op.kind == TK::kPlus ? BinaryOp::kAdd : BinaryOp::kSub;
    lhs = MakeBinary(bop, std::move(lhs), ParseMultiplicative(), op.span);
  }
  return lhs;
}

// multiplicative := unary {('*' | '/' | '//' | '%') unary}
ExprPtr Parser::ParseMultiplicative() {
  ExprPtr lhs = ParseUnary();
  while (true) {
    BinaryOp op;
    switch (Peek().kind) {
      case TK::kStar: op = BinaryOp::kMul; break;
      case TK::kSlash: op = BinaryOp::kDiv; break;
      case TK::kDoubleSlash: op = BinaryOp::kFloorDiv; break;
      case TK::kPercent: op = BinaryOp::kMod; break;
      default: return lhs;
    }
    SourceSpan op_span = Advance().span;
    lhs = MakeBinary(op, std::move(lhs), ParseUnary(), op_span);
  }
}

// unary := ('-' | '+') unary | power
ExprPtr Parser::ParseUnary() {
  if (!Check(TK::kMinus) && !Check(TK::kPlus)) return ParsePower();
  const Token& op = Advance();
  UnaryOp uop = op.kind == TK::kMinus ? UnaryOp::kNeg : UnaryOp::kPos;
  NestingGuard guard(this);
  ExprPtr operand = ParseUnary();
  return MakeExpr(op.span.begin, UnaryExpr{uop, std::move(operand)});
}

// power := postfix ['**' unary]          (right-associative; -2**2 == -(2**2))
ExprPtr Parser::ParsePower() {
  ExprPtr base = ParsePostfix();
  if (!Check(TK::kDoubleStar)) return base;
  SourceSpan op = Advance().span;
  NestingGuard guard(this);  // `a ** b ** c ...` recurses once per operator
  return MakeBinary(BinaryOp::kPow, std::move(base), ParseUnary(), op);
}

// postfix := atom {'(' args ')' | '.' NAME | '[' expr_list ']'}
ExprPtr Parser::ParsePostfix() {
  ExprPtr e = ParseAtom();
  while (true) {
    if (Check(TK::kLParen)) {
      e = ParseCall(std::move(e));
    } else if (Check(TK::kLBracket)) {
      e = ParseIndex(std::move(e));
    } else if (Match(TK::kDot)) {
      uint32_t begin = e->span.begin;
      Identifier attr = ExpectName("an attribute name after '.'");
      e = MakeExpr(begin, AttributeExpr{std::move(e), std::move(attr)});
    } else {
      return e;
    }
  }
}

// call := callee '(' [arg {',' arg} [',']] ')'      arg := [NAME '='] expr
ExprPtr Parser::ParseCall(ExprPtr callee) {
  uint32_t begin = callee->span.begin;
  uint32_t paren_begin = Advance().span.begin;
  Context saved_context = std::exchange(context_, Context{});
  CallExpr call{std::move(callee), {}, {}};
  while (!Check(TK::kRParen)) {
    if (Check(TK::kStar) || Check(TK::kDoubleStar)) {
      Fail("unsupported-feature", Peek().span,
           "argument unpacking with '*' or '**' is not supported in ProbRobScene");
    }
    CallArg arg;
    if (Check(TK::kName) && Check(TK::kAssign, 1)) {
      const Token& kw = Advance();
      Advance();
      for (const CallArg& a : call.args) {
        if (a.keyword && a.keyword->name == kw.lexeme) {
          Fail("duplicate-parameter", kw.span, fmt::format("keyword argument '{}' given twice", kw.lexeme));
        }
      }
      arg.keyword = Identifier{std::string(kw.lexeme), kw.span};
    } else if (!call.args.empty() && call.args.back().keyword) {
      Fail("bad-argument-order", Peek().span, "positional argument follows keyword argument");
    }
    arg.value = ParseExpr();
    if (Check(TK::kFor)) RejectComprehension("generator expressions");
    call.args.push_back(std::move(arg));
    if (!Match(TK::kComma)) break;
  }
  Expect(TK::kRParen, " to close the argument list");
  context_ = saved_context;
  call.paren_span = SpanFrom(paren_begin);
  return MakeExpr(begin, std::move(call));
}

// index := object '[' expr_list ']'
ExprPtr Parser::ParseIndex(ExprPtr object) {
  uint32_t begin = object->span.begin;
  Advance();
  Context saved_context = std::exchange(context_, Context{});
  if (Check(TK::kColon)) {
    Fail("unsupported-feature", Peek().span, "slicing is not supported in ProbRobScene");
  }
  ExprPtr index = ParseExprList();
  if (Check(TK::kColon)) {
    Fail("unsupported-feature", Peek().span, "slicing is not supported in ProbRobScene");
  }
  Expect(TK::kRBracket, " to close the index");
  context_ = saved_context;
  return MakeExpr(begin, IndexExpr{std::move(object), std::move(index)});
}

bool Parser::CanStartExpression(const Token& t) const {
  switch (t.kind) {
    case TK::kName: case TK::kNumber: case TK::kString: case TK::kLParen: case TK::kLBracket:
    case TK::kLBrace: case TK::kMinus: case TK::kPlus: case TK::kNot: case TK::kTrue:
    case TK::kFalse: case TK::kNone: case TK::kLambda:
      return true;
    default:
      return false;
  }
}

void Parser::RejectComprehension(std::string_view what) {
  Fail("unsupported-feature", Peek().span,
       fmt::format("{} are not supported in ProbRobScene; use a 'for' loop", what));
}

// atom := NUMBER | STRING+ | 'True' | 'False' | 'None' | name_atom | paren | list | dict
ExprPtr Parser::ParseAtom() {
  uint32_t begin = Here();
  NestingGuard guard(this);
  switch (Peek().kind) {
    case TK::kNumber: {
      double v = Advance().number;
      return MakeExpr(begin, NumberLit{v});
    }
    case TK::kString: return ParseString();
    case TK::kTrue: Advance(); return MakeExpr(begin, BoolLit{true});
    case TK::kFalse: Advance(); return MakeExpr(begin, BoolLit{false});
    case TK::kNone: Advance(); return MakeExpr(begin, NoneLit{});
    case TK::kName: return ParseName();
    case TK::kLParen: return ParseParenthesized();
    case TK::kLBracket: return ParseList();
    case TK::kLBrace: return ParseDict();
    case TK::kLambda: return ParseExpr();  // reports that lambda is unsupported
    case TK::kYield: case TK::kAwait:
      Fail("unsupported-feature", Peek().span,
           fmt::format("'{}' is not supported in ProbRobScene", Peek().lexeme));
    case TK::kStar:
      Fail("unsupported-feature", Peek().span, "unpacking with '*' is not supported in ProbRobScene");
    default:
      FailAtToken(fmt::format("expected an expression, found {}", DescribeToken(Peek())));
  }
}

// string := STRING {STRING}              (adjacent literals concatenate)
ExprPtr Parser::ParseString() {
  uint32_t begin = Here();
  std::string value;
  while (Check(TK::kString)) value += Advance().text;
  return MakeExpr(begin, StringLit{std::move(value)});
}

// name_atom := creation | distance | side_point | NAME
ExprPtr Parser::ParseName() {
  const Token& name = Peek();
  bool on_ends_operand = context_.stop_at_on && (CheckWord("on", 1) || CheckWord("along", 1));
  if (IsClassName(name.lexeme) && !on_ends_operand) return ParseCreation();
  if (name.lexeme == "distance" && Check(TK::kFrom, 1)) return ParseDistance();
  if (SideWords().count(name.lexeme)) {  // `top back of t`, or just a variable `top`
    if (std::optional<ExprPtr> side = TryParseSidePoint()) return std::move(*side);
  }
  bool is_side_word = SideWords().count(name.lexeme) > 0;
  if (IsSpecifierStart(1) && !Check(TK::kIn, 1) && !context_.in_specifier_arg && !is_side_word) {
    if (!failed_import_) FailUnknownClass(name);
    return ParseCreation();  // a class from a module that failed to load: no cascade
  }
  Advance();
  return MakeExpr(name.span.begin, NameRef{std::string(name.lexeme)});
}

// distance := 'distance' 'from' additive 'to' additive
ExprPtr Parser::ParseDistance() {
  uint32_t begin = Advance().span.begin;
  Advance();
  ExprPtr from = ParseAdditive();
  ExpectWord("to", "'distance from A'");
  ExprPtr to = ParseAdditive();
  return MakeExpr(begin, DistanceExpr{std::move(from), std::move(to)});
}

// Whether the token `ahead` positions on can start a side point's operand.
bool Parser::CanStartOperand(size_t ahead) const {
  const Token& t = Peek(ahead);
  if (t.kind == TK::kLParen) return true;
  return t.kind == TK::kName && !IsContinuationWord(t.lexeme) && !IsSpecifierStart(ahead);
}

// side_point := SIDE [SIDE2] ['of'] postfix     (SIDE2 forms a compound: `top back`)
// Returns nullopt (consuming nothing) when the side word is just a name, as in `x = top`.
std::optional<ExprPtr> Parser::TryParseSidePoint() {
  Side side = SideWords().at(Peek().lexeme);
  size_t words = 1;
  if (Peek(1).kind == TK::kName) {
    if (std::optional<Side> compound = CompoundSide(side, Peek(1).lexeme)) {
      if (CheckWord("of", 2) || CanStartOperand(2)) side = *compound, words = 2;
    } else if (CheckWord("of", 2) && !IsContinuationWord(Peek(1).lexeme)) {
      FailUnknownCompoundSide();  // `top frnt of t`
    }
  }
  bool has_of = CheckWord("of", words);
  if (!has_of && !CanStartOperand(words)) return std::nullopt;
  uint32_t begin = Here();
  for (size_t i = 0; i < words; ++i) Advance();
  SourceSpan keyword_span = SpanFrom(begin);
  if (has_of) Advance();
  ExprPtr object = ParsePostfix();
  return MakeExpr(begin, SidePointExpr{side, std::move(object), keyword_span});
}

// A side word, then a word that is not a side, then `of`: a misspelled compound side.
void Parser::FailUnknownCompoundSide() {
  const std::string first(Peek().lexeme);
  const Token& second = Peek(1);
  std::vector<std::string> valid;
  for (const auto& [word, side] : SideWords()) {
    if (CompoundSide(SideWords().at(first), word)) valid.push_back(first + " " + std::string(word));
  }
  std::sort(valid.begin(), valid.end());
  const std::string written = first + " " + std::string(second.lexeme);
  const std::string suggestion = SuggestClosest(written, valid);
  std::string message = fmt::format("unknown side '{}'", written);
  if (!suggestion.empty()) {
    message += fmt::format("; did you mean '{}'?", suggestion);
    Fail("unknown-side", second.span, message, suggestion.substr(first.size() + 1));
  }
  message += valid.empty() ? fmt::format("; '{}' takes no second word: write '{} of X'", first, first)
                           : fmt::format("; '{}' combines with {}", first, fmt::join(valid, ", "));
  Fail("unknown-side", second.span, message);
}

// paren := '(' ')' | '(' expr ')' | '(' expr ',' [expr {',' expr} [',']] ')'
ExprPtr Parser::ParseParenthesized() {
  const Token& open = Advance();
  Context saved_context = std::exchange(context_, Context{});
  ExprPtr result;
  if (Check(TK::kRParen)) {
    Advance();
    result = MakeExpr(open.span.begin, TupleExpr{});
  } else {
    ExprPtr first = ParseExpr();
    if (Check(TK::kFor)) RejectComprehension("generator expressions");
    if (Check(TK::kRParen)) {
      Advance();
      result = std::move(first);
    } else {
      TupleExpr tuple;
      tuple.elements.push_back(std::move(first));
      while (Match(TK::kComma) && !Check(TK::kRParen)) tuple.elements.push_back(ParseExpr());
      Expect(TK::kRParen, " to close the parenthesis");
      result = MakeExpr(open.span.begin, std::move(tuple));
    }
  }
  context_ = saved_context;
  return result;
}

// list := '[' [expr {',' expr} [',']] ']'
ExprPtr Parser::ParseList() {
  uint32_t begin = Advance().span.begin;
  Context saved_context = std::exchange(context_, Context{});
  ListExpr list;
  while (!Check(TK::kRBracket)) {
    list.elements.push_back(ParseExpr());
    if (Check(TK::kFor)) RejectComprehension("list comprehensions");
    if (!Match(TK::kComma)) break;
  }
  Expect(TK::kRBracket, " to close the list");
  context_ = saved_context;
  return MakeExpr(begin, std::move(list));
}

// dict := '{' [expr ':' expr {',' expr ':' expr} [',']] '}'
ExprPtr Parser::ParseDict() {
  uint32_t begin = Advance().span.begin;
  Context saved_context = std::exchange(context_, Context{});
  DictExpr dict;
  while (!Check(TK::kRBrace)) {
    ExprPtr key = ParseExpr();
    if (Check(TK::kComma) || Check(TK::kRBrace)) {
      Fail("unsupported-feature", key->span,
           "sets are not supported in ProbRobScene; a dict needs 'key: value' entries");
    }
    Expect(TK::kColon, " between a dict key and its value");
    ExprPtr value = ParseExpr();
    if (Check(TK::kFor)) RejectComprehension("dict comprehensions");
    dict.entries.emplace_back(std::move(key), std::move(value));
    if (!Match(TK::kComma)) break;
  }
  Expect(TK::kRBrace, " to close the dict");
  context_ = saved_context;
  return MakeExpr(begin, std::move(dict));
}

}  // namespace prs::lang::internal
