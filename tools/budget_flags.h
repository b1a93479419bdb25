#pragma once
// The budget options every tool that runs scripts takes (fscript, fvrml-run): one wording, one range.
#include <CLI/CLI.hpp>

#include "backends/backend.h"

namespace fscript::tools {

// Ranges are said in words in the help; CLI11's own hint ("UINT:UINT in [1 - 4611686018427387904]")
// is for parsers, not people. The range is still checked, with CLI11's message.
inline void add_budget_flags(CLI::App& app, backends::Budgets& budgets, uint32_t& max_call_depth) {
  app.add_option("--max-loop-iterations", budgets.max_loop_iterations,
                 "loop iterations allowed per evaluation, at least 1 (default 10,000,000)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 62).description(""))
      ->type_name("N");
  app.add_option("--max-call-depth", max_call_depth,
                 std::string("nested calls allowed, 1 to ") + backends::kCallDepthCeilingText + " (default 1,000)")
      ->check(CLI::Range(1u, backends::kCallDepthCeiling).description(""))
      ->type_name("N");
  app.add_option("--max-array-elements", budgets.max_array_elements,
                 "array elements allowed per evaluation, up to 2^32 (default 1,000,000)")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 32).description(""))
      ->type_name("N");
}

}  // namespace fscript::tools
