#pragma once
// Value ranges: an interval and a may-be-NaN bit for every value of a function, given that every
// parameter is finite with |p| <= bound. Backends use it to drop NaN handling that cannot matter.
#include <vector>

#include "ir/ir.h"

namespace fscript::ir {

struct Range {
  double lo, hi;  // every float the value can take lies in [lo, hi] (bounds may be infinite)
  bool nan;       // the value may be NaN
};

// Indexed by value id. Values the analysis knows nothing about (globals, arrays, calls, loop phis)
// get (-inf, inf, NaN possible).
std::vector<Range> value_ranges(const Function& fn, double param_bound);

}  // namespace fscript::ir
