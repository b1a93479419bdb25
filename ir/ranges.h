#pragma once
// Value ranges: an interval and a may-be-NaN bit for every value of a function, given that every
// parameter is finite with |p| <= bound, by the op table's interval rules (ir/interval_eval).
// Backends use it to drop NaN handling that cannot matter.
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

// Whether v may be NaN: a constant by its value, anything else by `ranges` (empty: unknown).
bool may_be_nan(const Inst* v, const std::vector<Range>& ranges);
// How many operations need a NaN test: min/max/clamp on a bound operand that may be NaN (the
// first operand's NaN comes out of minps/maxps by itself), truthiness of one that may be NaN.
int nan_tests(const Function& fn, const std::vector<Range>& ranges);
// The largest parameter bound (of kParamBounds) that leaves the fewest NaN tests; 0 when no
// bound removes any, so code need not assume one.
double best_param_bound(const Function& fn);
// What the bounded code for `param_bound` assumes of a row parameter (ir::Function::
// row_param_ranges); nullptr: |p| <= param_bound, as for any parameter.
const ParamRange* row_param_range(const Function& fn, double param_bound, uint32_t param);

}  // namespace fscript::ir
