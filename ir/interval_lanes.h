#pragma once
// The batched interval evaluator's per-ISA loop (ir/interval_lanes.cpp, compiled once per ISA);
// IntervalTape::eval_batch picks the variant for this CPU.
#include "ir/interval_eval.h"
#include "runtime/math/isa.h"

namespace fscript::ir {
FS_FOR_EACH_ISA_DECLARE(void eval_lanes(const IntervalTape::Step* steps, size_t n, const IntervalLanes* inputs,
                                        size_t num_inputs, IntervalLanes* values, Choice* choices))
}  // namespace fscript::ir
