// IntervalTape::eval_batch: kIntervalLanes regions in one pass over the tape, on the ISA variant
// of the lane loop this CPU runs best.
#include "ir/interval_eval.h"
#include "ir/interval_lanes.h"

namespace fscript::ir {

void IntervalTape::eval_batch(const std::vector<IntervalLanes>& inputs, IntervalBatchEval& out) const {
  out.values.resize(values_);
  out.choices.resize(size_t(values_) * kIntervalLanes);  // the choosing steps write theirs
  out.outputs = outputs_;
  out.masks = false;
  auto run = isa_base::eval_lanes;
  switch (math::active_isa()) {
    case math::Isa::Base: run = isa_base::eval_lanes; break;
    case math::Isa::Avx2: run = isa_avx2::eval_lanes; break;
    case math::Isa::Avx512: run = isa_avx512::eval_lanes; break;
  }
  run(steps_.data(), steps_.size(), inputs.data(), inputs.size(), out.values.data(), out.choices.data());
}

}  // namespace fscript::ir
