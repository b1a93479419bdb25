#pragma once
// What every fuzz target shares: how a finding is reported (the input and what broke, then abort,
// which libFuzzer records as a crash with the input saved), and bounded compile budgets.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "backends/backend.h"

namespace fscript::fuzz {

[[noreturn]] inline void finding(const std::string& what, const std::string& input) {
  std::fprintf(stderr, "==== fuzz finding: %s\n---- input ----\n%s\n---- end ----\n", what.c_str(), input.c_str());
  std::abort();
}

// Small enough that one execution stays in milliseconds, large enough to run every construct.
inline backends::Budgets small_budgets() {
  backends::Budgets b;
  b.max_loop_iterations = 20000;
  b.max_call_depth = 64;
  b.max_array_elements = 4096;
  return b;
}

}  // namespace fscript::fuzz
