// The lexer: turns a source file into tokens with Python's indentation rules (INDENT,
// DEDENT, NEWLINE), implicit line joining in brackets, and the trailing-comma rule.
#pragma once

#include <vector>

#include "lang/diagnostics.h"
#include "lang/source.h"
#include "lang/token.h"

namespace prs::lang {

/// Tokenises a whole file. Errors are reported to `diagnostics` and the lexer recovers,
/// so the result always ends with kEndOfFile (preceded by a NEWLINE and any DEDENTs
/// needed to close open blocks). A logical line whose last token is ',' outside brackets
/// continues on the next physical line (the specifier-list rule of the paper's Figure 1).
std::vector<Token> Lex(FileId file, const SourceManager& sources, DiagnosticEngine& diagnostics);

}  // namespace prs::lang
