#pragma once
// Grid rows with the row split (ir/passes/row_split.h): a kernel whose eval_rows runs the split's
// prologue once per row and its body once per point, both compiled by the kernel's own backend.
#include <memory>
#include <string>

#include "backends/backend.h"

namespace fscript::backends {

// `full` (module `m` compiled by backend `backend`) with eval_rows through the row split, when the
// kernel has one that pays; else `full` unchanged. The split's two kernels are compiled on the
// first eval_rows (a job that never asks for rows never pays for them).
std::unique_ptr<Kernel> with_row_split(std::unique_ptr<Kernel> full, const std::string& backend, const ir::Module& m,
                                       const Budgets& budgets);

// What the row split did in this process (fscript bench --grid, fvrml-run --stats).
struct RowStats {
  uint64_t kernels = 0;     // kernels that have a row split
  uint64_t rows = 0;        // rows evaluated through one
  uint64_t points = 0;      // and their points
  uint64_t hoisted = 0;     // of the last split made: operations once per row,
  uint64_t per_point = 0;   // operations per point,
  uint64_t row_values = 0;  // values handed from the prologue to the body
};
RowStats row_stats();

// A row job's points expanded into batches of `k` (the default Kernel::eval_rows).
bool expand_rows(const Kernel& k, const float* first, size_t count, const float* const* rest, size_t rows,
                 float* const* outputs, RuntimeError& err);

// FSCRIPT_ROW_SPLIT=0 turns the split off (measurements, and a check that both paths agree).
bool row_split_enabled();

}  // namespace fscript::backends
