#pragma once
// VRML97 lexer: identifiers (the standard's IdFirstChar/IdRestChars), numbers, strings with
// escapes and line breaks, brackets, '.', comments (#) and commas as white space; UTF-8 checked.
#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/source.h"

namespace fscript::vrml {

enum class VTok : uint8_t { Eof, Id, Number, String, LBracket, RBracket, LBrace, RBrace, Period, Error };

struct VToken {
  VTok kind = VTok::Eof;
  frontend::Span span;
  std::string text;  // Id: the name; String: the contents with escapes resolved; Number: as written
};

// Lexes a whole file (after its header line). Never fails; bad input becomes diagnostics.
std::vector<VToken> lex_vrml(const frontend::SourceFile& file, size_t start, frontend::DiagnosticSink& diag);

}  // namespace fscript::vrml
