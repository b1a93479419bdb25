#pragma once
// The row split of a kernel for grid evaluation: along a row of a grid only the first input
// changes, so every value that does not depend on it is computed once per row (the prologue) and
// only the rest once per point (the body). One pass for every backend: they compile the two parts.
#include <cstddef>
#include <memory>

#include "ir/ir.h"

namespace fscript::ir {

struct RowSplit {
  // kernel(the original's inputs) -> the K row values the body needs (K >= 1).
  std::unique_ptr<Module> prologue;
  // kernel(first input, row value 0, ..., row value K-1) -> the original's outputs.
  std::unique_ptr<Module> body;
  size_t hoisted = 0;    // value operations that run once per row instead of once per point
  size_t per_point = 0;  // value operations left in the body (constants not counted)
  size_t row_values = 0; // K
};

// Splits a straight-line kernel (one block, no calls, no memory, no traps). Returns false, with
// `out` untouched, when the kernel has another shape or when the split would not pay: the work
// hoisted (a runtime call counted as kCallWeight operations) must exceed kRowValueCost operations
// per row value the body takes (a load or broadcast per group, and a register; measured,
// docs/performance.md, "Decisions": csg8's 25 operations for 12 values win, prospero's 734 for 571
// lose).
bool split_rows(const Module& m, RowSplit& out);
constexpr size_t kCallWeight = 8;
constexpr double kRowValueCost = 1.5;

}  // namespace fscript::ir
