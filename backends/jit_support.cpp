// Runtime errors, the stack limit and the input guard of the JIT backends.
#include "backends/jit_support.h"

#include <pthread.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

namespace fscript::backend {

namespace {
constexpr uintptr_t kStackMargin = 256 * 1024;
}

bool jit_status(uint64_t code, const LaneArrays& arrays, const Budgets& budgets, RuntimeError& err) {
  if (code == 0) return true;
  err.line = static_cast<uint32_t>(code);
  switch (code >> 32) {
    case 1:
      err.message = "loop iteration budget exceeded: more than " + std::to_string(budgets.max_loop_iterations) +
                    " iterations in one evaluation";
      break;
    case 2: err.message = arrays.message; break;
    case 3:
      err.message = "call depth budget exceeded: more than " + std::to_string(budgets.max_call_depth) + " nested calls";
      break;
    default:
      err.message = "recursion too deep for this thread's stack (the budget allows " +
                    std::to_string(budgets.max_call_depth) + " nested calls); lower --max-call-depth or use --backend vm";
      break;
  }
  return false;
}

uintptr_t stack_limit() {
  thread_local uintptr_t limit = [] {
    pthread_attr_t attr;
    void* addr = nullptr;
    size_t size = 0;
    if (pthread_getattr_np(pthread_self(), &attr) != 0)  // then assume the smallest usual stack
      return reinterpret_cast<uintptr_t>(__builtin_frame_address(0)) - (size_t{1} << 20) + kStackMargin;
    pthread_attr_getstack(&attr, &addr, &size);
    pthread_attr_destroy(&attr);
    return reinterpret_cast<uintptr_t>(addr) + kStackMargin;
  }();
  return limit;
}

extern "C" uint32_t fs_ticks_carry(int32_t* counters, uint64_t budget) {
  // Invariant: a lane's ticks so far = totals + counters. The counter restarts so that it passes
  // the generated code's int32 threshold exactly when the lane passes the budget (or, when that
  // is further than int32 reaches, at the next carry).
  constexpr int64_t kThreshold = INT32_MAX - 1;
  auto* totals = reinterpret_cast<int64_t*>(reinterpret_cast<char*>(counters) + 16);
  uint32_t over = 0;
  for (int i = 0; i < 4; ++i) {
    int64_t ticks = totals[i] + counters[i];
    if (static_cast<uint64_t>(ticks) > budget) {
      over = 1;
      continue;
    }
    int64_t start = kThreshold - std::min<int64_t>(kThreshold, static_cast<int64_t>(budget - static_cast<uint64_t>(ticks)));
    counters[i] = static_cast<int32_t>(start);
    totals[i] = ticks - start;
  }
  return over;
}

// No early exit, so the loop vectorises.
bool inputs_in_range(const float* const* inputs, size_t num_inputs, size_t n, double bound) {
  float b = static_cast<float>(bound);
  bool ok = true;
  for (size_t k = 0; k < num_inputs; ++k)
    for (size_t i = 0; i < n; ++i) ok &= std::fabs(inputs[k][i]) <= b;
  return ok;
}

}  // namespace fscript::backend
