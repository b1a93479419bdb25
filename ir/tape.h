#pragma once
// Tape simplification: a straight-line kernel specialised to one region of its inputs. Every
// min / max / select whose interval evaluation decided the side becomes that side, and what only
// the other side needed disappears. The result gives the same bits as the original at every point
// of the region, so a region's pixels or cells can run the shorter kernel.
#include <memory>

#include "ir/interval_eval.h"
#include "ir/ir.h"

namespace fscript::ir {

struct SimplifiedTape {
  std::unique_ptr<Module> module;  // one function, the kernel (num_params and results as `fn`)
  size_t ops = 0;                  // value operations it keeps (params and constants included)
  size_t choices_collapsed = 0;
};

// `fn` must be interval_evaluable and `ev` its evaluation over the region. Recursion works: a
// sub-region's evaluation of the result simplifies it further.
SimplifiedTape simplify_tape(const Function& fn, const IntervalEval& ev);

// Value operations of a straight-line kernel (its tape length).
size_t tape_length(const Function& fn);

}  // namespace fscript::ir
