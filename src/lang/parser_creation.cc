// The recursive-descent parser, part 3: object creations and their specifiers, the grammar
// of spec §5 and §10 (`Cube completely on t, reachable by arm, visible from camera`).
#include <fmt/format.h>

#include <algorithm>

#include "lang/parser_internal.h"

namespace prs::lang::internal {
namespace {

const std::vector<std::string>& SpecifierSpellings() {
  static const std::vector<std::string> kSpellings = {
      "with", "at", "in", "on", "completely on", "left of", "right of", "ahead of", "behind",
      "above", "below", "aligned with", "beyond", "facing", "facing toward", "completely",
      "aligned", "ahead", "reachable by", "reachable", "in view of", "visible from", "visible",
      "completely in view of", "completely visible from", "not visible from", "not in view of"};
  return kSpellings;
}

}  // namespace

// ---------------------------------------------------------------------------
// Object creation and specifiers
// ---------------------------------------------------------------------------

bool Parser::IsClassName(std::string_view name) const {
  return class_defs_.count(std::string(name)) > 0;
}

void Parser::AddClass(const std::string& name, std::optional<SourceSpan> where) {
  if (class_defs_.count(name)) {
    if (where) class_defs_[name] = where;
    return;
  }
  class_names_.push_back(name);
  class_defs_[name] = where;
}

bool Parser::IsSpecifierStart(size_t ahead) const {
  static const std::string_view kWords[] = {"at", "on", "completely", "left", "right", "ahead",
                                            "behind", "above", "below", "aligned", "beyond",
                                            "facing", "reachable", "visible"};
  const Token& t = Peek(ahead);
  if (t.kind == TK::kWith || t.kind == TK::kIn) return true;
  if (t.kind == TK::kNot) {  // `not visible from`, `not in view of` (not the operator `not in`)
    return CheckWord("visible", ahead + 1) ||
           (Check(TK::kIn, ahead + 1) && CheckWord("view", ahead + 2) && CheckWord("of", ahead + 3));
  }
  if (t.kind != TK::kName) return false;
  return std::find(std::begin(kWords), std::end(kWords), t.lexeme) != std::end(kWords);
}

void Parser::FailUnknownClass(const Token& name) {
  Diagnostic d;
  d.id = "unknown-class";
  d.span = name.span;
  d.message = fmt::format("unknown class '{}'", name.lexeme);
  std::string suggestion = SuggestClosest(name.lexeme, class_names_);
  if (!suggestion.empty()) {
    d.message += fmt::format("; did you mean '{}'?", suggestion);
    d.fix_it = suggestion;
    if (const std::optional<SourceSpan>& def = class_defs_.at(suggestion)) {
      d.notes.push_back({*def, true, fmt::format("'{}' is defined here", suggestion)});
    }
  }
  Report(std::move(d));
  throw ParseAbort{};
}

// After a class name (or a specifier list's comma): a word that is not a specifier. Reports
// a misspelled specifier (`compltely on`, `aheadof`) or, right after the class name, that a
// specifier was expected. After a comma, an unrelated word just ends the list.
void Parser::CheckMisspelledSpecifier(const Token& class_name, bool after_comma) {
  const Token& word = Peek();
  bool word_like = word.kind == TK::kName || word.kind == TK::kNumber || word.kind == TK::kString;
  if (!word_like) return;
  std::string suggestion;
  if (word.kind == TK::kName) suggestion = SuggestClosest(word.lexeme, SpecifierSpellings());
  const Token& next = Peek(1);
  bool operand_follows = next.kind == TK::kName || next.kind == TK::kNumber ||
                         next.kind == TK::kString || next.kind == TK::kLParen;
  if (!suggestion.empty() && (operand_follows || !after_comma)) {
    Fail("unknown-specifier", word.span,
         fmt::format("unknown specifier '{}'; did you mean '{}'?", word.lexeme, suggestion),
         suggestion);
  }
  if (!after_comma) {
    Fail("expected-specifier", word.span,
         fmt::format("expected a specifier ('with', 'at', 'on', 'in', 'left of', ...) after '{}'",
                     class_name.lexeme));
  }
}

// creation := CLASS [specifier {',' specifier}]     (no specifier: a ClassRef)
// A ',' not followed by a specifier ends the list and belongs to the enclosing construct.
ExprPtr Parser::ParseCreation() {
  const Token& name = Advance();
  uint32_t begin = name.span.begin;
  if (!IsSpecifierStart(0)) {
    CheckMisspelledSpecifier(name, false);
    return MakeExpr(begin, ClassRef{std::string(name.lexeme)});
  }
  CreateObject create{Identifier{std::string(name.lexeme), name.span}, {}};
  create.specifiers.push_back(ParseSpecifier());
  while (true) {
    if (IsSpecifierStart(0)) {
      Fail("expected-token", Peek().span,
           fmt::format("expected ',' before the specifier '{}'", Peek().lexeme));
    }
    if (!Check(TK::kComma)) break;
    if (!IsSpecifierStart(1)) {
      ++pos_;  // peek past the comma for a misspelled specifier (an error throws)
      CheckMisspelledSpecifier(name, true);
      --pos_;
      break;
    }
    Advance();
    create.specifiers.push_back(ParseSpecifier());
  }
  return MakeExpr(begin, std::move(create));
}

// specifier := 'with' NAME arg | 'at' arg | 'in' arg | ['completely'] 'on' arg
//            | ('left' | 'right' | 'ahead') 'of' arg ['by' arg]
//            | ('behind' | 'above' | 'below') arg ['by' arg]
//            | 'aligned' 'with' arg (('on' | 'along') AXIS | 'by' STRING)
//            | 'beyond' arg 'by' arg 'from' arg | 'facing' ['toward' | 'towards'] arg
//            | 'reachable' 'by' arg {'with' ('margin' | 'approach' | 'grasp') arg}
//            | ['completely' | 'not'] ('in' 'view' 'of' | 'visible' 'from') arg
// arg := or_expr
Specifier Parser::ParseSpecifier() {
  const Token& keyword = Advance();
  Specifier s;
  uint32_t begin = keyword.span.begin;
  std::string_view w = keyword.lexeme;
  if (keyword.kind == TK::kWith) {
    s.kind = SpecifierKind::kWith;
    if (!Check(TK::kName)) {
      FailAtToken(fmt::format("expected a property name after 'with', found {}",
                              DescribeToken(Peek())));
    }
    const Token& prop = Advance();
    s.property = Identifier{std::string(prop.lexeme), prop.span};
    s.target = ParseSpecifierArg(fmt::format("'with {}'", prop.lexeme));
  } else if (keyword.kind == TK::kIn && CheckWord("view") && CheckWord("of", 1)) {
    Advance(), Advance();
    s.kind = SpecifierKind::kInViewOf;
    s.target = ParseSpecifierArg("'in view of'");
  } else if (keyword.kind == TK::kIn || w == "at" || w == "on") {
    s.kind = keyword.kind == TK::kIn ? SpecifierKind::kIn
             : w == "at"             ? SpecifierKind::kAt : SpecifierKind::kOn;
    s.target = ParseSpecifierArg(fmt::format("'{}'", w));
  } else if (w == "completely" || keyword.kind == TK::kNot || w == "visible") {
    ParseVisibilitySpecifier(&s, keyword);
  } else if (w == "reachable") {
    ExpectWord("by", "'reachable'");
    s.kind = SpecifierKind::kReachableBy;
    s.target = ParseSpecifierArg("'reachable by'");
    ParseReachableOptions(&s);
  } else {
    ParseSpecifierTail(&s, keyword);
  }
  s.span = SpanFrom(begin);
  return s;
}

// completely on | completely in view of | completely visible from | visible from
// | not visible from | not in view of
void Parser::ParseVisibilitySpecifier(Specifier* s, const Token& keyword) {
  const bool completely = keyword.lexeme == "completely", negated = keyword.kind == TK::kNot;
  if (completely && CheckWord("on")) {
    Advance();
    s->kind = SpecifierKind::kCompletelyOn;
    s->target = ParseSpecifierArg("'completely on'");
    return;
  }
  const bool in_view = (completely || negated) && Check(TK::kIn) && CheckWord("view", 1) &&
                       CheckWord("of", 2);
  if (in_view) {
    Advance(), Advance(), Advance();
    s->kind = completely ? SpecifierKind::kCompletelyInViewOf : SpecifierKind::kNotInViewOf;
  } else {
    if (keyword.lexeme != "visible" && !CheckWord("visible")) {
      FailAtToken(fmt::format("expected 'on', 'in view of' or 'visible from' after 'completely', "
                              "found {}", DescribeToken(Peek())));
    }
    if (keyword.lexeme != "visible") Advance();
    if (!Match(TK::kFrom)) {
      FailAtToken(fmt::format("expected 'from' after 'visible', found {}", DescribeToken(Peek())));
    }
    s->kind = completely ? SpecifierKind::kCompletelyVisibleFrom
              : negated  ? SpecifierKind::kNotVisibleFrom : SpecifierKind::kVisibleFrom;
  }
  s->target = ParseSpecifierArg(fmt::format("'{}'", SpecifierName(s->kind)));
}

// reachable_options := {'with' ('margin' | 'approach' | 'grasp') arg}   (no commas between)
// A `with` followed by another name is left for the specifier list (a `with PROP` needs a comma).
void Parser::ParseReachableOptions(Specifier* s) {
  static const std::string_view kOptions[] = {"margin", "approach", "grasp"};
  while (Check(TK::kWith) && Check(TK::kName, 1) &&
         std::find(std::begin(kOptions), std::end(kOptions), Peek(1).lexeme) != std::end(kOptions)) {
    Advance();
    const Token& name = Advance();
    for (const SpecifierOption& seen : s->options) {
      if (seen.name.name == name.lexeme) {
        Fail("duplicate-option", name.span,
             fmt::format("'{}' is given twice for this 'reachable by'", name.lexeme));
      }
    }
    SpecifierOption option{Identifier{std::string(name.lexeme), name.span}, nullptr};
    option.value = ParseSpecifierArg(fmt::format("'with {}'", name.lexeme));
    s->options.push_back(std::move(option));
  }
}

// The relational specifiers: left of, behind, aligned with, beyond, facing, ...
void Parser::ParseSpecifierTail(Specifier* s, const Token& keyword) {
  std::string_view w = keyword.lexeme;
  if (w == "left" || w == "right" || w == "ahead") {
    s->kind = w == "left" ? SpecifierKind::kLeftOf
              : w == "right" ? SpecifierKind::kRightOf : SpecifierKind::kAheadOf;
    if (!CheckWord("of")) {
      Fail("missing-of", Peek().span.begin > keyword.span.end ? keyword.span : Peek().span,
           fmt::format("expected 'of' after '{}'", w), fmt::format("{} of", w));
    }
    Advance();
    s->target = ParseSpecifierArg(fmt::format("'{} of'", w));
    if (std::optional<ExprPtr> by = ParseOptionalBy()) s->distance = std::move(*by);
  } else if (w == "behind" || w == "above" || w == "below") {
    s->kind = w == "behind" ? SpecifierKind::kBehind
              : w == "above" ? SpecifierKind::kAbove : SpecifierKind::kBelow;
    s->target = ParseSpecifierArg(fmt::format("'{}'", w));
    if (std::optional<ExprPtr> by = ParseOptionalBy()) s->distance = std::move(*by);
  } else if (w == "aligned") {
    if (!Match(TK::kWith)) FailAtToken(fmt::format("expected 'with' after 'aligned', found {}", DescribeToken(Peek())));
    s->kind = SpecifierKind::kAlignedWith;
    bool saved = std::exchange(context_.stop_at_on, true);
    s->target = ParseSpecifierArg("'aligned with'");
    context_.stop_at_on = saved;
    ParseAlignedAxis(s);
  } else if (w == "beyond") {
    s->kind = SpecifierKind::kBeyond;
    s->target = ParseSpecifierArg("'beyond'");
    ExpectWord("by", "'beyond X'");
    s->distance = ParseSpecifierArg("'by'");
    if (!Match(TK::kFrom)) {
      FailAtToken(fmt::format("expected 'from' after 'beyond X by D', found {}",
                              DescribeToken(Peek())));
    }
    s->from = ParseSpecifierArg("'from'");
  } else {  // facing
    bool toward = CheckWord("toward") || CheckWord("towards");
    if (toward) Advance();
    s->kind = toward ? SpecifierKind::kFacingToward : SpecifierKind::kFacing;
    s->target = ParseSpecifierArg(toward ? "'facing toward'" : "'facing'");
  }
}

// aligned_axis := ('on' | 'along') ('x' | 'y' | 'z') | 'by' ('"x"' | '"y"' | '"z"')
void Parser::ParseAlignedAxis(Specifier* s) {
  auto is_axis = [](std::string_view a) { return a == "x" || a == "y" || a == "z"; };
  if (CheckWord("on") || CheckWord("along")) {
    std::string_view how = Advance().lexeme;
    if (!Check(TK::kName) || !is_axis(Peek().lexeme)) {
      Fail("bad-axis", Peek().kind == TK::kNewline ? SourceSpan{file_, prev_end_, prev_end_} : Peek().span,
           fmt::format("expected an axis 'x', 'y' or 'z' after '{}', found {}", how,
                       DescribeToken(Peek())));
    }
    const Token& axis = Advance();
    s->axis = Identifier{std::string(axis.lexeme), axis.span};
  } else if (CheckWord("by")) {
    Advance();
    if (!Check(TK::kString) || !is_axis(Peek().text)) {
      Fail("bad-axis", Peek().span,
           fmt::format("expected an axis \"x\", \"y\" or \"z\" after 'by', found {}",
                       DescribeToken(Peek())));
    }
    const Token& axis = Advance();
    s->axis = Identifier{axis.text, axis.span};
  } else {
    FailAtToken(fmt::format("expected 'on', 'along' or 'by' and an axis after 'aligned with X', "
                            "found {}", DescribeToken(Peek())));
  }
}

ExprPtr Parser::ParseSpecifierArg(std::string_view after) {
  if (!CanStartExpression(Peek())) {
    FailAtToken(fmt::format("expected an expression after {}, found {}", after,
                            DescribeToken(Peek())));
  }
  bool saved = std::exchange(context_.in_specifier_arg, true);
  ExprPtr arg = ParseOr();
  context_.in_specifier_arg = saved;
  return arg;
}

std::optional<ExprPtr> Parser::ParseOptionalBy() {
  if (!CheckWord("by")) return std::nullopt;
  Advance();
  return ParseSpecifierArg("'by'");
}

void Parser::ExpectWord(std::string_view word, std::string_view after) {
  if (!CheckWord(word)) {
    FailAtToken(fmt::format("expected '{}' after {}, found {}", word, after, DescribeToken(Peek())));
  }
  Advance();
}

}  // namespace prs::lang::internal
