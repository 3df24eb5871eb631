// Tokens produced by the lexer: Python's lexical structure plus ProbRobScene's hard keywords.
#pragma once

#include <string>
#include <string_view>

#include "lang/source.h"

namespace prs::lang {

enum class TokenKind {
  kName, kNumber, kString, kNewline, kIndent, kDedent, kEndOfFile,
  // Punctuation and operators.
  kLParen, kRParen, kLBracket, kRBracket, kLBrace, kRBrace,
  kComma, kColon, kDot, kSemicolon,
  kPlus, kMinus, kStar, kSlash, kDoubleSlash, kPercent, kDoubleStar,
  kAssign, kPlusAssign, kMinusAssign, kStarAssign, kSlashAssign,
  kEqEq, kNotEq, kLess, kLessEq, kGreater, kGreaterEq, kArrow,
  // Hard keywords. Specifier and side words (on, at, top, …) are plain kName.
  kAnd, kOr, kNot, kIf, kElif, kElse, kFor, kIn, kDef, kReturn, kClass, kFrom, kImport,
  kTrue, kFalse, kNone, kPass, kBreak, kContinue, kWhile, kIs, kLambda, kWith, kRequire,
  kParam,
  // Python keywords ProbRobScene reserves but does not support (reported by the parser).
  kGlobal, kNonlocal, kYield, kTry, kExcept, kFinally, kRaise, kDel, kAssert, kAsync, kAwait,
  kAs,
  kAt,  // '@' (decorators), unsupported
  kError,  // a character the lexer rejected (already reported)
};

struct Token {
  TokenKind kind = TokenKind::kEndOfFile;
  SourceSpan span;
  std::string_view lexeme;  // the source text of the token (empty for NEWLINE/INDENT/DEDENT)
  double number = 0;        // kNumber: the value
  std::string text;         // kString: the unescaped value
};

/// A short human-readable spelling of a token kind, e.g. "')'", "name", "end of line".
std::string_view TokenKindName(TokenKind kind);

/// Returns a description of a token for messages: "name 'foo'", "')'", "end of line".
std::string DescribeToken(const Token& token);

}  // namespace prs::lang
