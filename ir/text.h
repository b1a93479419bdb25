#pragma once
// Text form of the IR: the printer (golden tests, `fscript emit-ir`) and the reader that parses it
// back. print(read(print(m))) == print(m) for every module.
#include <memory>
#include <string>

#include "ir/ir.h"

namespace fscript::ir {

std::string print(const Module& m);
std::string print(const Module& m, const Function& fn);
// The canonical spelling of a float constant: %.9g, nan, inf, -inf.
std::string format_float(float v);

// Parses the text form; on error returns nullptr and sets `error` to "line N: message".
std::unique_ptr<Module> read(const std::string& text, std::string& error);

}  // namespace fscript::ir
