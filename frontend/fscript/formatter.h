#pragma once
// `fscript fmt`: the canonical layout of a script (2-space indent, one statement per line,
// spaces around binary operators, only the parentheses the precedence needs), comments kept.
#include <string>

#include "frontend/fscript/ast.h"

namespace fscript::frontend {

// Formats a program that parsed without errors. Formatting is idempotent.
std::string format_program(const Program& prog, const std::string& source);

// The shortest decimal text that reads back as the same float (e.g. 0.1, 1e-05, 2.5).
std::string shortest_float(float v);

}  // namespace fscript::frontend
