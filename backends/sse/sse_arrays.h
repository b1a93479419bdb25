#pragma once
// Arrays for SSE kernels: the per-lane array storage of one group of four points, and the helpers
// the generated code calls for anew / aload / astore / alen (four lanes at once, under the block's
// lane mask). Semantics, budgets and messages are the VM's (backends/vm/vm_exec.cpp).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "backends/backend.h"

namespace fscript::sse {

struct ArrayState {
  uint64_t max_elements = 0;        // per evaluation (one lane), all arrays together
  std::vector<std::string> names;   // by slot: the module's global arrays, then the kernel's own
  std::array<std::vector<float>, 4> heap;
  std::vector<std::array<int64_t, 4>> off, len;  // by slot, per lane (-1: not created yet)
  std::string message;              // set when a helper returns 1
};

// Each returns 0, or 1 with `message` set. Masks are four floats, all-ones bits where a lane runs.
extern "C" {
uint32_t fs_sse_arrays_reset(ArrayState* s);
uint32_t fs_sse_anew(ArrayState* s, uint32_t slot, const float* size, const float* mask);
uint32_t fs_sse_aload(ArrayState* s, uint32_t slot, const float* index, float* out, const float* mask);
uint32_t fs_sse_astore(ArrayState* s, uint32_t slot, const float* index, const float* value, const float* mask);
uint32_t fs_sse_alen(ArrayState* s, uint32_t slot, float* out, const float* mask);
// A recursive function's local arrays belong to its activation: entering saves the slots' state
// (eight int64 per slot) and marks them not created; leaving puts the caller's back.
uint32_t fs_sse_arrays_enter(ArrayState* s, uint32_t first, uint32_t count, int64_t* save);
uint32_t fs_sse_arrays_leave(ArrayState* s, uint32_t first, uint32_t count, const int64_t* save);
}

}  // namespace fscript::sse
