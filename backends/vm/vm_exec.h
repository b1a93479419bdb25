#pragma once
// The VM executor: runs a VmProgram's kernel over a chunk of lanes (SIMT over the CFG, masked
// writes), and user calls one lane at a time (recursion), under the budgets.
#include <cstddef>

#include "backends/backend.h"
#include "backends/vm/bytecode.h"
#include "runtime/math/isa.h"

namespace fscript::vm {

// Evaluates points [0, n) of `inputs` into `outputs`, chunk by chunk; one variant per ISA. A
// recursion that nears the end of this thread's stack stops the batch with `out_of_stack` set
// (the caller runs it again on a stack sized for the budget). A kernel with row parameters runs
// rows of `row_length` points: point i reads inputs[k][i % row_length] below them and
// inputs[k][i / row_length] from them on.
#define FS_VM_RUN_BATCH                                                                            \
  bool run_batch(const VmProgram& p, const backends::Budgets& budgets, const float* const* inputs, \
                 float* const* outputs, size_t n, size_t row_length, backends::RuntimeError& err, bool& out_of_stack)
FS_FOR_EACH_ISA_DECLARE(FS_VM_RUN_BATCH)
#undef FS_VM_RUN_BATCH

// The variant of the active ISA; a recursion deeper than the caller's stack allows runs again on a
// stack sized for the budget, so the call budget, not `ulimit -s`, decides how deep it goes.
bool run_batch(const VmProgram& p, const backends::Budgets& budgets, const float* const* inputs, float* const* outputs,
               size_t n, size_t row_length, backends::RuntimeError& err);

}  // namespace fscript::vm
