// The runtime error messages every backend shares.
#include "backends/runtime_errors.h"

#include <cmath>
#include <cstdio>

#include "runtime/support/cancel.h"

namespace fscript::backends::errors {

namespace {
std::string number(float v) {  // as the user would write it back: the shortest round trip
  // NaN's sign is not the same on every backend (the language does not define it): "nan", never
  // "-nan", so that every backend gives the same message (a finding of the backend_diff target).
  if (std::isnan(v)) return "nan";
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", static_cast<double>(v));
  return b;
}
}  // namespace

std::string loop_budget(uint64_t max_loop_iterations) {
  return "loop iteration budget exceeded: more than " + std::to_string(max_loop_iterations) +
      " iterations in one evaluation";
}

std::string cancelled() { return support::kCancelledMessage; }

std::string call_depth(uint32_t max_call_depth) {
  return "call depth budget exceeded: more than " + std::to_string(max_call_depth) + " nested calls";
}

std::string recursion_stack(uint32_t max_call_depth) {
  return "recursion too deep for this thread's stack (the budget allows " + std::to_string(max_call_depth) +
      " nested calls); lower --max-call-depth";
}

std::string array_size(const std::string& array, float size, uint64_t max_array_elements) {
  return "array '" + array + "' of " + number(size) +
      " elements: sizes must be whole numbers from 0 to the budget of " + std::to_string(max_array_elements) +
      " elements per evaluation";
}

std::string array_index(const std::string& array, float index, int64_t length) {
  return "index " + number(index) + " is out of range for array '" + array + "' of " + std::to_string(length) +
      " elements";
}

std::string array_unset(const std::string& array) { return "array '" + array + "' is used before it is created"; }

}  // namespace fscript::backends::errors
