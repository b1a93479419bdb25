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
  // The same program as JavaScript (the node oracle, tests/oracle): the body of a function of
  // (x, y, z, t) that runs the top level and returns FRep's value, every operation rounded to
  // float32 with Math.fround, with the helpers of tests/oracle/prelude.js. Empty when the program
  // calls a built-in JavaScript has no counterpart of (noise).
  std::string js;
};

struct GenOptions {
  bool straight_line = false;  // no loops, recursion, arrays or early returns (interval_sound)
  bool exact_only = false;     // only what the language defines exactly: no transcendental built-ins, ^ or **
};

GeneratedProgram generate_program(FuzzedDataProvider& in, const GenOptions& options = {});

}  // namespace fscript::fuzz
