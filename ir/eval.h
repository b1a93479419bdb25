#pragma once
// Evaluation of one pure op on constant operands through runtime/math: constant folding uses it,
// so a folded value is bit-for-bit what the VM computes at run time.
#include "ir/ir.h"

namespace fscript::ir {

// Sets `out` and returns true for ops that are pure functions of their operands.
bool eval_pure(Op op, const float* a, float& out);

}  // namespace fscript::ir
