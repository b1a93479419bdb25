#pragma once
// The runtime errors of evaluation, worded once for every backend: the VM raises them, the JIT
// backends' array helpers (lane_arrays) and status codes (jit_support) report them, so a script
// fails with the same message and line whichever backend runs it.
#include <cstdint>
#include <string>

namespace fscript::backends::errors {

std::string loop_budget(uint64_t max_loop_iterations);
std::string call_depth(uint32_t max_call_depth);
// Only when even a stack sized for the budget (1 GiB) could not be had.
std::string recursion_stack(uint32_t max_call_depth);
// The run was cancelled from another thread (support/cancel.h): checked in loops and recursive calls.
std::string cancelled();
std::string array_size(const std::string& array, float size, uint64_t max_array_elements);
std::string array_index(const std::string& array, float index, int64_t length);
std::string array_unset(const std::string& array);

}  // namespace fscript::backends::errors
