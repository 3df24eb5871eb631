// The lexer: one pass over the text producing tokens, with Python's indentation and
// line-joining rules plus ProbRobScene's trailing-comma continuation.
#include "lang/lexer.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <unordered_map>

namespace prs::lang {
namespace {

const std::unordered_map<std::string_view, TokenKind>& Keywords() {
  static const std::unordered_map<std::string_view, TokenKind> kKeywords = {
      {"and", TokenKind::kAnd},       {"or", TokenKind::kOr},
      {"not", TokenKind::kNot},       {"if", TokenKind::kIf},
      {"elif", TokenKind::kElif},     {"else", TokenKind::kElse},
      {"for", TokenKind::kFor},       {"in", TokenKind::kIn},
      {"def", TokenKind::kDef},       {"return", TokenKind::kReturn},
      {"class", TokenKind::kClass},   {"from", TokenKind::kFrom},
      {"import", TokenKind::kImport}, {"True", TokenKind::kTrue},
      {"False", TokenKind::kFalse},   {"None", TokenKind::kNone},
      {"pass", TokenKind::kPass},     {"break", TokenKind::kBreak},
      {"continue", TokenKind::kContinue}, {"while", TokenKind::kWhile},
      {"is", TokenKind::kIs},         {"lambda", TokenKind::kLambda},
      {"with", TokenKind::kWith},     {"require", TokenKind::kRequire},
      {"param", TokenKind::kParam},   {"global", TokenKind::kGlobal},
      {"nonlocal", TokenKind::kNonlocal}, {"yield", TokenKind::kYield},
      {"try", TokenKind::kTry},       {"except", TokenKind::kExcept},
      {"finally", TokenKind::kFinally}, {"raise", TokenKind::kRaise},
      {"del", TokenKind::kDel},       {"assert", TokenKind::kAssert},
      {"async", TokenKind::kAsync},   {"await", TokenKind::kAwait},
      {"as", TokenKind::kAs},
  };
  return kKeywords;
}

bool IsNameStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' ||
         static_cast<unsigned char>(c) >= 0x80;  // UTF-8 identifiers, as in Python
}
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsNameChar(char c) { return IsNameStart(c) || IsDigit(c); }

char CloserOf(char opener) { return opener == '(' ? ')' : opener == '[' ? ']' : '}'; }
TokenKind CloserKind(char opener) {
  return opener == '(' ? TokenKind::kRParen
         : opener == '[' ? TokenKind::kRBracket : TokenKind::kRBrace;
}

// One indentation level, measured with tab stops of 8 and of 1 as Python does: when the two
// measures disagree about an indent or dedent, tabs and spaces are mixed ambiguously.
struct Indent {
  int col = 0;
  int alt_col = 0;
};

struct OpenBracket {
  char ch;
  SourceSpan span;
};

class Lexer {
 public:
  Lexer(FileId file, std::string_view text, DiagnosticEngine& diags)
      : file_(file), text_(text), diags_(diags) {}

  std::vector<Token> Run();

 private:
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Peek(size_t ahead = 0) const {
    return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0';
  }
  SourceSpan Span(size_t begin, size_t end) const {
    return SourceSpan{file_, static_cast<uint32_t>(begin), static_cast<uint32_t>(end)};
  }
  void Emit(TokenKind kind, size_t begin, size_t end);
  bool LastIs(TokenKind kind) const { return !tokens_.empty() && tokens_.back().kind == kind; }

  bool HandleLineStart();
  void HandleNewline();
  void LexToken();
  void LexName();
  void LexNumber();
  void LexString(size_t prefix_begin, bool raw);
  bool ReadEscape(std::string* out);
  bool ReadHexEscape(int digits, size_t backslash, std::string* out);
  void LexOperator();
  void OpenBracketAt(char c);
  void CloseBracketAt(char c);
  void Finish();

  FileId file_;
  std::string_view text_;
  DiagnosticEngine& diags_;
  size_t pos_ = 0;
  bool at_line_start_ = true;
  std::vector<Token> tokens_;
  std::vector<Indent> indents_ = {Indent{}};
  std::vector<OpenBracket> brackets_;
};

void Lexer::Emit(TokenKind kind, size_t begin, size_t end) {
  Token t;
  t.kind = kind;
  t.span = Span(begin, end);
  t.lexeme = text_.substr(begin, end - begin);
  tokens_.push_back(std::move(t));
}

std::vector<Token> Lexer::Run() {
  while (true) {
    if (at_line_start_ && !HandleLineStart()) break;
    char c = Peek();
    if (AtEnd()) break;
    if (c == ' ' || c == '\t' || c == '\f') {
      ++pos_;
    } else if (c == '#') {
      while (!AtEnd() && Peek() != '\n' && Peek() != '\r') ++pos_;
    } else if (c == '\n' || c == '\r') {
      HandleNewline();
    } else if (c == '\\') {
      size_t begin = pos_++;
      if (Peek() == '\r') ++pos_;
      if (Peek() == '\n') {
        ++pos_;  // explicit line joining: the logical line goes on
      } else if (!AtEnd()) {
        diags_.Error("bad-line-continuation", Span(begin, begin + 1),
                     "unexpected character after line continuation character '\\'");
      }
    } else {
      LexToken();
    }
  }
  Finish();
  return std::move(tokens_);
}

// Measures the indentation of a new physical line and emits INDENT/DEDENT tokens. Skips
// blank and comment-only lines. Returns false at the end of the text.
bool Lexer::HandleLineStart() {
  while (true) {
    Indent ind;
    size_t line_begin = pos_;
    for (; !AtEnd(); ++pos_) {
      char c = Peek();
      if (c == ' ') {
        ++ind.col, ++ind.alt_col;
      } else if (c == '\t') {
        ind.col = (ind.col / 8 + 1) * 8, ++ind.alt_col;
      } else if (c == '\f') {
        ind = Indent{};
      } else {
        break;
      }
    }
    if (AtEnd()) return false;
    char c = Peek();
    if (c == '#') {
      while (!AtEnd() && Peek() != '\n' && Peek() != '\r') ++pos_;
      c = Peek();
    }
    if (c == '\n' || c == '\r') {
      pos_ += (c == '\r' && Peek(1) == '\n') ? 2 : 1;
      continue;  // blank or comment-only line
    }
    if (AtEnd()) return false;
    at_line_start_ = false;
    const Indent& top = indents_.back();
    SourceSpan where = Span(line_begin, pos_);
    if (ind.col == top.col) {
      if (ind.alt_col != top.alt_col) {
        diags_.Error("inconsistent-tabs", where, "inconsistent use of tabs and spaces in indentation");
      }
    } else if (ind.col > top.col) {
      if (ind.alt_col <= top.alt_col) {
        diags_.Error("inconsistent-tabs", where, "inconsistent use of tabs and spaces in indentation");
      }
      indents_.push_back(ind);
      Emit(TokenKind::kIndent, line_begin, pos_);
    } else {
      while (indents_.size() > 1 && ind.col < indents_.back().col) {
        indents_.pop_back();
        Emit(TokenKind::kDedent, pos_, pos_);
      }
      if (ind.col != indents_.back().col) {
        // Recover by treating the line as belonging to the enclosing level.
        diags_.Error("inconsistent-dedent", Span(pos_, pos_ + 1),
                     "unindent does not match any outer indentation level");
      }
    }
    return true;
  }
}

// A physical line ends: inside brackets or after a trailing ',' the logical line goes on.
void Lexer::HandleNewline() {
  size_t begin = pos_;
  pos_ += (Peek() == '\r' && Peek(1) == '\n') ? 2 : 1;
  if (!brackets_.empty() || LastIs(TokenKind::kComma)) return;
  if (!tokens_.empty() && !LastIs(TokenKind::kNewline) && !LastIs(TokenKind::kIndent) &&
      !LastIs(TokenKind::kDedent)) {
    Emit(TokenKind::kNewline, begin, begin);
  }
  at_line_start_ = true;
}

void Lexer::LexToken() {
  char c = Peek();
  size_t begin = pos_;
  if (IsNameStart(c)) {
    // A string prefix (r, u, f, b and combinations) directly before a quote.
    size_t n = 0;
    while (n < 2 && std::string_view("rRuUfFbB").find(Peek(n)) != std::string_view::npos) ++n;
    if (n > 0 && (Peek(n) == '\'' || Peek(n) == '"')) {
      std::string prefix(text_.substr(pos_, n));
      if (prefix.find_first_of("fFbB") != std::string::npos) {
        diags_.Error("unsupported-feature", Span(begin, begin + n),
                     fmt::format("'{}' string prefixes are not supported in ProbRobScene", prefix));
      }
      pos_ += n;
      LexString(begin, prefix.find_first_of("rR") != std::string::npos);
      return;
    }
    LexName();
  } else if (IsDigit(c) || (c == '.' && IsDigit(Peek(1)))) {
    LexNumber();
  } else if (c == '\'' || c == '"') {
    LexString(begin, false);
  } else {
    LexOperator();
  }
}

void Lexer::LexName() {
  size_t begin = pos_;
  while (!AtEnd() && IsNameChar(Peek())) ++pos_;
  std::string_view word = text_.substr(begin, pos_ - begin);
  auto it = Keywords().find(word);
  Emit(it == Keywords().end() ? TokenKind::kName : it->second, begin, pos_);
}

void Lexer::LexNumber() {
  size_t begin = pos_;
  bool bad = false, too_large = false;
  double value = 0;
  if (Peek() == '0' && std::string_view("xXoObB").find(Peek(1)) != std::string_view::npos &&
      Peek(1) != '\0') {
    int base = (Peek(1) == 'x' || Peek(1) == 'X') ? 16 : (Peek(1) == 'o' || Peek(1) == 'O') ? 8 : 2;
    pos_ += 2;
    size_t digits = pos_;
    while (!AtEnd() && std::isxdigit(static_cast<unsigned char>(Peek()))) ++pos_;
    long long v = 0;
    auto r = std::from_chars(text_.data() + digits, text_.data() + pos_, v, base);
    bad = digits == pos_ || r.ptr != text_.data() + pos_;
    value = static_cast<double>(v);
  } else {
    while (IsDigit(Peek())) ++pos_;
    if (Peek() == '.') {
      ++pos_;
      while (IsDigit(Peek())) ++pos_;
    }
    if (Peek() == 'e' || Peek() == 'E') {
      ++pos_;
      if (Peek() == '+' || Peek() == '-') ++pos_;
      if (!IsDigit(Peek())) bad = true;
      while (IsDigit(Peek())) ++pos_;
    }
    auto r = std::from_chars(text_.data() + begin, text_.data() + pos_, value);
    if (r.ec == std::errc::result_out_of_range) {
      // Too small underflows to 0 harmlessly; too large would be infinite.
      value = std::strtod(std::string(text_.substr(begin, pos_ - begin)).c_str(), nullptr);
      if (!std::isfinite(value)) too_large = true;
    } else if (r.ec != std::errc()) {
      bad = true;
    }
  }
  // A number running straight into letters or a second '.' ("1abc", "1.2.3") is malformed.
  while (!AtEnd() && (IsNameChar(Peek()) || (Peek() == '.' && IsDigit(Peek(1))))) {
    bad = true;
    ++pos_;
  }
  if (bad) {
    diags_.Error("invalid-number", Span(begin, pos_),
                 fmt::format("invalid number literal '{}'", text_.substr(begin, pos_ - begin)));
  } else if (too_large) {
    diags_.Error("invalid-number", Span(begin, pos_),
                 fmt::format("number literal '{}' is too large (the largest is about 1.8e308)",
                             text_.substr(begin, pos_ - begin)));
    value = 0;
  }
  Emit(TokenKind::kNumber, begin, pos_);
  tokens_.back().number = value;
}

// Reads the escape after a backslash (pos_ is on the character after '\'). Returns false for
// an escaped newline, which produces nothing. \xHH is one byte, \uXXXX a code point in UTF-8;
// a malformed one is an error. Unknown escapes keep their backslash, as in Python, with a
// warning, since `"\d"` is more often a mistake than a backslash.
bool Lexer::ReadEscape(std::string* out) {
  const size_t backslash = pos_ - 1;
  char c = Peek();
  ++pos_;
  switch (c) {
    case 'n': out->push_back('\n'); return true;
    case 't': out->push_back('\t'); return true;
    case 'r': out->push_back('\r'); return true;
    case '0': out->push_back('\0'); return true;
    case '\\': case '\'': case '"': out->push_back(c); return true;
    case 'x':
    case 'u':
      return ReadHexEscape(c == 'x' ? 2 : 4, backslash, out);
    case '\r':
      if (Peek() == '\n') ++pos_;
      return false;
    case '\n': return false;
    default: {
      Diagnostic d;
      d.severity = Severity::kWarning;
      d.id = "unknown-escape";
      d.span = Span(backslash, pos_);
      d.message = fmt::format("unknown escape sequence '\\{}' is kept as written", c);
      d.fix_it = fmt::format("\\\\{}", c);
      diags_.Report(std::move(d));
      out->push_back('\\');
      out->push_back(c);
      return true;
    }
  }
}

// \xHH (digits == 2) or \uXXXX (digits == 4), pos_ just past the 'x' or 'u'.
bool Lexer::ReadHexEscape(int digits, size_t backslash, std::string* out) {
  uint32_t code = 0;
  for (int i = 0; i < digits; ++i) {
    const char h = Peek();
    const int value = h >= '0' && h <= '9'   ? h - '0'
                      : h >= 'a' && h <= 'f' ? h - 'a' + 10
                      : h >= 'A' && h <= 'F' ? h - 'A' + 10
                                             : -1;
    if (value < 0) {
      diags_.Error(
          "bad-escape", Span(backslash, pos_),
          fmt::format("'\\{}' needs {} hexadecimal digits", digits == 2 ? 'x' : 'u', digits));
      return true;
    }
    code = code * 16 + value;
    ++pos_;
  }
  if (digits == 2 || code < 0x80) {
    out->push_back(static_cast<char>(code));
  } else if (code < 0x800) {
    out->push_back(static_cast<char>(0xC0 | (code >> 6)));
    out->push_back(static_cast<char>(0x80 | (code & 0x3F)));
  } else {
    out->push_back(static_cast<char>(0xE0 | (code >> 12)));
    out->push_back(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (code & 0x3F)));
  }
  return true;
}

void Lexer::LexString(size_t prefix_begin, bool raw) {
  size_t quote_begin = pos_;
  char q = Peek();
  bool triple = Peek(1) == q && Peek(2) == q;
  size_t quote_len = triple ? 3 : 1;
  pos_ += quote_len;
  std::string value;
  while (true) {
    if (AtEnd() || (!triple && (Peek() == '\n' || Peek() == '\r'))) {
      diags_.Error("unterminated-string", Span(quote_begin, quote_begin + quote_len),
                   triple ? "unterminated triple-quoted string literal"
                          : "unterminated string literal");
      break;
    }
    char c = Peek();
    if (c == q && (!triple || (Peek(1) == q && Peek(2) == q))) {
      pos_ += quote_len;
      break;
    }
    if (c == '\\' && pos_ + 1 < text_.size()) {
      ++pos_;
      if (raw) {
        value.push_back('\\');
        value.push_back(Peek());
        ++pos_;
      } else {
        ReadEscape(&value);
      }
      continue;
    }
    value.push_back(c);
    ++pos_;
  }
  Emit(TokenKind::kString, prefix_begin, pos_);
  tokens_.back().text = std::move(value);
}

void Lexer::OpenBracketAt(char c) {
  brackets_.push_back(OpenBracket{c, Span(pos_, pos_ + 1)});
  Emit(c == '(' ? TokenKind::kLParen : c == '[' ? TokenKind::kLBracket : TokenKind::kLBrace,
       pos_, pos_ + 1);
  ++pos_;
}

// A closing bracket: matched, mismatched (reported with a note at the opener, then treated
// as the opener's closer so the parser sees balanced brackets), or stray (reported, and
// passed on as an error token).
void Lexer::CloseBracketAt(char c) {
  size_t begin = pos_++;
  if (brackets_.empty()) {
    diags_.Error("unmatched-bracket", Span(begin, begin + 1), fmt::format("unmatched '{}'", c));
    Emit(TokenKind::kError, begin, pos_);  // the parser stays quiet about error tokens
    return;
  }
  OpenBracket open = brackets_.back();
  if (CloserOf(open.ch) != c) {
    Diagnostic d;
    d.id = "mismatched-bracket";
    d.span = Span(begin, begin + 1);
    d.message = fmt::format("closing '{}' does not match opening '{}'", c, open.ch);
    d.notes.push_back({open.span, true, fmt::format("'{}' opened here", open.ch)});
    d.fix_it = std::string(1, CloserOf(open.ch));
    diags_.Report(std::move(d));
  }
  brackets_.pop_back();
  Emit(CloserKind(open.ch), begin, begin + 1);
}

void Lexer::LexOperator() {
  struct Op {
    std::string_view text;
    TokenKind kind;
  };
  // Longest first, so "**" wins over "*" and "//=" is not needed.
  static const Op kOps[] = {
      {"**", TokenKind::kDoubleStar}, {"//", TokenKind::kDoubleSlash},
      {"+=", TokenKind::kPlusAssign}, {"-=", TokenKind::kMinusAssign},
      {"*=", TokenKind::kStarAssign}, {"/=", TokenKind::kSlashAssign},
      {"==", TokenKind::kEqEq},       {"!=", TokenKind::kNotEq},
      {"<=", TokenKind::kLessEq},     {">=", TokenKind::kGreaterEq},
      {"->", TokenKind::kArrow},      {",", TokenKind::kComma},
      {":", TokenKind::kColon},       {".", TokenKind::kDot},
      {";", TokenKind::kSemicolon},   {"+", TokenKind::kPlus},
      {"-", TokenKind::kMinus},       {"*", TokenKind::kStar},
      {"/", TokenKind::kSlash},       {"%", TokenKind::kPercent},
      {"=", TokenKind::kAssign},      {"<", TokenKind::kLess},
      {">", TokenKind::kGreater},     {"@", TokenKind::kAt},
  };
  char c = Peek();
  if (c == '(' || c == '[' || c == '{') return OpenBracketAt(c);
  if (c == ')' || c == ']' || c == '}') return CloseBracketAt(c);
  std::string_view rest = text_.substr(pos_);
  for (const Op& op : kOps) {
    if (rest.substr(0, op.text.size()) == op.text) {
      Emit(op.kind, pos_, pos_ + op.text.size());
      pos_ += op.text.size();
      return;
    }
  }
  size_t begin = pos_;
  if (std::string_view("&|^~").find(c) != std::string_view::npos ||
      rest.substr(0, 2) == "<<" || rest.substr(0, 2) == ">>") {
    diags_.Error("unsupported-feature", Span(begin, begin + 1),
                 fmt::format("bitwise operator '{}' is not supported in ProbRobScene", c));
    ++pos_;
  } else {
    // Consume a whole UTF-8 sequence so the message shows the character.
    ++pos_;
    while (!AtEnd() && (static_cast<unsigned char>(Peek()) & 0xC0) == 0x80) ++pos_;
    diags_.Error("invalid-character", Span(begin, pos_),
                 fmt::format("invalid character '{}' in source", text_.substr(begin, pos_ - begin)));
  }
  Emit(TokenKind::kError, begin, pos_);
}

// End of text: close the last line and all blocks; report the innermost unclosed bracket.
void Lexer::Finish() {
  size_t end = text_.size();
  if (!brackets_.empty()) {
    const OpenBracket& open = brackets_.back();
    diags_.Error("unclosed-bracket", open.span, fmt::format("'{}' was never closed", open.ch));
  }
  if (!tokens_.empty() && !LastIs(TokenKind::kNewline) && !LastIs(TokenKind::kDedent) &&
      !LastIs(TokenKind::kIndent)) {
    Emit(TokenKind::kNewline, end, end);
  }
  while (indents_.size() > 1) {
    indents_.pop_back();
    Emit(TokenKind::kDedent, end, end);
  }
  Emit(TokenKind::kEndOfFile, end, end);
}

}  // namespace

std::vector<Token> Lex(FileId file, const SourceManager& sources, DiagnosticEngine& diagnostics) {
  return Lexer(file, sources.text(file), diagnostics).Run();
}

std::string_view TokenKindName(TokenKind kind) {
  switch (kind) {
    case TokenKind::kName: return "name";
    case TokenKind::kNumber: return "number";
    case TokenKind::kString: return "string";
    case TokenKind::kNewline: return "end of line";
    case TokenKind::kIndent: return "indent";
    case TokenKind::kDedent: return "unindent";
    case TokenKind::kEndOfFile: return "end of file";
    case TokenKind::kLParen: return "'('";
    case TokenKind::kRParen: return "')'";
    case TokenKind::kLBracket: return "'['";
    case TokenKind::kRBracket: return "']'";
    case TokenKind::kLBrace: return "'{'";
    case TokenKind::kRBrace: return "'}'";
    case TokenKind::kComma: return "','";
    case TokenKind::kColon: return "':'";
    case TokenKind::kDot: return "'.'";
    case TokenKind::kSemicolon: return "';'";
    case TokenKind::kPlus: return "'+'";
    case TokenKind::kMinus: return "'-'";
    case TokenKind::kStar: return "'*'";
    case TokenKind::kSlash: return "'/'";
    case TokenKind::kDoubleSlash: return "'//'";
    case TokenKind::kPercent: return "'%'";
    case TokenKind::kDoubleStar: return "'**'";
    case TokenKind::kAssign: return "'='";
    case TokenKind::kPlusAssign: return "'+='";
    case TokenKind::kMinusAssign: return "'-='";
    case TokenKind::kStarAssign: return "'*='";
    case TokenKind::kSlashAssign: return "'/='";
    case TokenKind::kEqEq: return "'=='";
    case TokenKind::kNotEq: return "'!='";
    case TokenKind::kLess: return "'<'";
    case TokenKind::kLessEq: return "'<='";
    case TokenKind::kGreater: return "'>'";
    case TokenKind::kGreaterEq: return "'>='";
    case TokenKind::kArrow: return "'->'";
    case TokenKind::kAt: return "'@'";
    case TokenKind::kError: return "invalid token";
    default: break;
  }
  // A keyword: its spelling in quotes.
  static const std::unordered_map<TokenKind, std::string> kQuoted = [] {
    std::unordered_map<TokenKind, std::string> quoted;
    for (const auto& [word, k] : Keywords()) quoted[k] = fmt::format("'{}'", word);
    return quoted;
  }();
  auto it = kQuoted.find(kind);
  return it == kQuoted.end() ? "token" : std::string_view(it->second);
}

std::string DescribeToken(const Token& token) {
  switch (token.kind) {
    case TokenKind::kName: return fmt::format("name '{}'", token.lexeme);
    case TokenKind::kNumber: return fmt::format("number {}", token.lexeme);
    case TokenKind::kString: return "string literal";
    default:
      return std::string(TokenKindName(token.kind));
  }
}

}  // namespace prs::lang
