#pragma once
// Straight-line flat tapes run directly at up to kPointLanes points, with no compile: for the
// quadtree's last level, where a region's tape is short and its points few, compiling it costs
// more than running it. The same per-lane math as the VM (ir/math_ops.def), so the same bits.
#include <cstddef>

#include "ir/interval_eval.h"
#include "runtime/math/isa.h"

namespace fscript::vm {

constexpr size_t kPointLanes = 256;

// Output 0 of `t` at n <= kPointLanes points, parameter p at inputs[p][i] (parameters past
// num_inputs are 0); out[i] for i < n.
void eval_tape_points(const ir::IntervalTape& t, const float* const* inputs, size_t num_inputs, size_t n, float* out);
// Outputs 0 .. count - 1 of `t` the same way (out[k][i]).
void eval_tape_points(const ir::IntervalTape& t, const float* const* inputs, size_t num_inputs, size_t n,
                      float* const* out, size_t count);

// The per-ISA loop: `values` holds kPointLanes floats per value id, parameters already in place;
// the first `lanes` of each are computed (a multiple of 16, at most kPointLanes).
FS_FOR_EACH_ISA_DECLARE(void run_tape_points(const ir::IntervalTape::Step* steps, size_t count, float* values,
                                             size_t lanes))

}  // namespace fscript::vm
