#pragma once
// Arrays of every backend: the per-lane array storage of one group of lanes (a VM chunk, 4 for sse,
// the vector width for llvm), one lane's operations (the VM calls them), and the helpers generated
// code calls for anew / aload / astore / alen under the block's lane mask. One implementation, so
// the budgets, the semantics and the messages are the same on every backend.
#include <cstdint>
#include <string>
#include <vector>

#include "backends/backend.h"

namespace fscript::backends {

struct LaneArrays {
  uint32_t lanes = 4;
  uint64_t max_elements = 0;        // per evaluation (one lane), all arrays together
  std::vector<std::string> names;   // by slot: the module's global arrays, then each function's own
  std::vector<std::vector<float>> heap;  // per lane
  std::vector<int64_t> off, len;    // [slot * lanes + lane] (-1: not created yet)
  std::string message;              // set when a helper returns 1

  // Storage for `slot_names` (display names made here) with the given budget.
  void init(uint32_t lane_count, uint64_t budget, const std::vector<std::string>& slot_names);
  // Every array of every lane gone (a new evaluation).
  void reset();

  // One lane's operations; each returns false (nullptr) with `message` set.
  bool create(uint32_t slot, uint32_t lane, float size);
  float* element(uint32_t slot, uint32_t lane, float index);
  bool length(uint32_t slot, uint32_t lane, float& out);
  // A function activation's own arrays, slots [first, first + count) of one lane: entering saves
  // them (2 * count int64) and marks them not created; leaving puts the caller's back.
  void enter(uint32_t first, uint32_t count, uint32_t lane, int64_t* save);
  void leave(uint32_t first, uint32_t count, uint32_t lane, const int64_t* save);

 private:
  bool created(uint32_t slot, uint32_t lane);
};

// Each returns 0, or 1 with `message` set. Masks are one 32-bit word per lane, nonzero where the
// lane runs; sizes, indices, values and results one float per lane.
extern "C" {
uint32_t fs_lanes_reset(LaneArrays* s);
uint32_t fs_lanes_anew(LaneArrays* s, uint32_t slot, const float* size, const uint32_t* mask);
uint32_t fs_lanes_aload(LaneArrays* s, uint32_t slot, const float* index, float* out, const uint32_t* mask);
uint32_t fs_lanes_astore(LaneArrays* s, uint32_t slot, const float* index, const float* value, const uint32_t* mask);
uint32_t fs_lanes_alen(LaneArrays* s, uint32_t slot, float* out, const uint32_t* mask);
// A recursive function's local arrays belong to its activation: entering saves the slots' state
// (2 * lanes int64 per slot) and marks them not created; leaving puts the caller's back.
uint32_t fs_lanes_enter(LaneArrays* s, uint32_t first, uint32_t count, int64_t* save);
uint32_t fs_lanes_leave(LaneArrays* s, uint32_t first, uint32_t count, const int64_t* save);
}

}  // namespace fscript::backends
