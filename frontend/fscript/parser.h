#pragma once
// FScript parser: hand-written recursive descent with precedence climbing for binary operators.
// Recovers at ';', '}' and statement keywords, so one run reports every syntax error, once each.
#include "frontend/diagnostics.h"
#include "frontend/fscript/ast.h"

namespace fscript::frontend {

// Deeper nesting (parentheses, blocks, unary chains, right-associative chains) is refused with
// a diagnostic instead of risking the native stack. Left-associative chains have no limit.
constexpr int kMaxNesting = 2500;

// Parses a whole script. Always returns a Program (with Error nodes where input was bad).
std::unique_ptr<Program> parse(const SourceFile& file, DiagnosticSink& diag);

}  // namespace fscript::frontend
