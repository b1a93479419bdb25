#pragma once
// Liveness and live intervals over a linear block order, and a linear-scan assignment of values
// to registers. Shared by the VM (unbounded registers) and, later, the SSE backend (16 + spills).
#include <cstdint>
#include <vector>

#include "ir/ir.h"

namespace fscript::backends {

struct Interval {
  uint32_t start = 0;  // position of the definition
  uint32_t end = 0;    // last position where the value is live
};

struct LinearOrder {
  std::vector<ir::Block*> blocks;         // reverse post-order
  std::vector<uint32_t> block_start;      // position of each block's first instruction
  std::vector<uint32_t> block_end;        // position of each block's terminator
  std::vector<Interval> interval;         // by value id (start == end == 0 for non-values)
  std::vector<bool> has_value;            // by value id
};

// Numbers instructions in reverse post-order and computes a conservative single interval per
// value: from its definition to its last use, stretched over every block it is live through.
// A phi operand is used at the end of its predecessor; a phi is defined at its block's start.
LinearOrder compute_intervals(const ir::Function& fn);

// Assigns registers so that values with overlapping intervals never share one. `skip(value)`
// excludes values that get no register (e.g. constants the VM encodes as immediates).
// Returns the register per value id (UINT32_MAX when skipped) and sets `num_regs`.
template <typename Skip>
std::vector<uint32_t> linear_scan(const ir::Function& fn, const LinearOrder& lo, Skip skip, uint32_t& num_regs);

}  // namespace fscript::backends

#include "backends/regalloc_impl.h"
