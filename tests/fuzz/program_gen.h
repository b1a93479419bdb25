#pragma once
// Turns a fuzzer's bytes into a well-formed FScript program (backend_diff, interval_sound): globals,
// helper functions, bounded recursion and loops, arrays, every built-in. Every byte string maps to
// a program that compiles, so the fuzzer spends its time in the backends, not in the parser.
#include <string>

#include <fuzzer/FuzzedDataProvider.h>

namespace fscript::fuzz {

struct GeneratedProgram {
  std::string text;          // defines FRep(x, y, z, t)
  bool transcendental = false;  // calls a built-in the optimiser folds within 4 ulp (not exactly)
};

struct GenOptions {
  bool straight_line = false;  // no loops, recursion, arrays or early returns (interval_sound)
};

GeneratedProgram generate_program(FuzzedDataProvider& in, const GenOptions& options = {});

}  // namespace fscript::fuzz
