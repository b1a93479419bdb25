#pragma once
// FScript lexer: text -> tokens, with comments kept aside (the formatter re-emits them) and
// the "a line break precedes this token" bit that automatic semicolon insertion needs.
#include <string>
#include <string_view>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/source.h"

namespace fscript::frontend {

enum class Tok : uint8_t {
#define FS_TOKEN(N, S) N,
#define FS_KEYWORD(N, S, D) N,
#include "frontend/fscript/tokens.def"
};

// Human spelling of a token kind, for diagnostics ("expected ')'").
const char* token_spelling(Tok t);
bool is_keyword(Tok t);

struct Token {
  Tok kind = Tok::Eof;
  Span span;
  bool newline_before = false;  // a line break lies between this token and the previous one
  double number = 0;            // Number: the value (rounded to float by the parser)
};

struct Comment {
  Span span;
  bool own_line = false;  // nothing but white space before it on its line
};

struct LexResult {
  std::vector<Token> tokens;  // always ends with Eof
  std::vector<Comment> comments;
};

// Lexes the whole file; errors (bad characters, unterminated comments) go to `diag`.
LexResult lex(const SourceFile& file, DiagnosticSink& diag);

}  // namespace fscript::frontend
