// Value ranges under bounded parameters, from the interval rules of the op table (ir/interval_eval):
// one pass in reverse post-order; phis, memory and calls know nothing.
#include "ir/ranges.h"

#include <cmath>

#include "ir/analysis.h"
#include "ir/interval_eval.h"

namespace fscript::ir {

const ParamRange* row_param_range(const Function& fn, double param_bound, uint32_t param) {
  if (fn.row_param_ranges.empty() || !fn.row_params_from || param < fn.row_params_from || param >= fn.num_params)
    return nullptr;
  size_t k = fn.num_params - fn.row_params_from;
  for (size_t b = 0; b < kNumParamBounds; ++b)
    if (kParamBounds[b] == param_bound) return &fn.row_param_ranges[b * k + (param - fn.row_params_from)];
  return nullptr;
}

std::vector<Range> value_ranges(const Function& fn, double param_bound) {
  std::vector<math::Interval> v(fn.next_value, math::Interval::everything());
  std::vector<Range> r(fn.next_value, Range{-INFINITY, INFINITY, true});
  auto bound = static_cast<float>(param_bound);
  auto param = [&](const Inst* in) {
    if (const ParamRange* p = row_param_range(fn, param_bound, static_cast<uint32_t>(in->aux)))
      return math::Interval{p->lo, p->hi, p->nan};
    return math::Interval{-bound, bound, false};
  };
  for (const Block* blk : reverse_post_order(fn))
    for (const Inst* in : blk->insts) {
      if (!in->defines_value()) continue;
      v[in->id] = in->op == Op::Param ? param(in) : interval_of(*in, v);
      r[in->id] = {v[in->id].lo, v[in->id].hi, v[in->id].nan != 0};
    }
  return r;
}

bool may_be_nan(const Inst* v, const std::vector<Range>& ranges) {
  if (v->op == Op::Const) return v->imm != v->imm;
  return ranges.empty() || ranges[v->id].nan;
}

int nan_tests(const Function& fn, const std::vector<Range>& r) {
  int n = 0;
  for (const auto& blk : fn.blocks)
    for (const Inst* in : blk->insts) {
      switch (in->op) {
        case Op::Min:
        case Op::Max: n += may_be_nan(in->args[1], r); break;
        case Op::Clamp: n += may_be_nan(in->args[1], r) + may_be_nan(in->args[2], r); break;
        case Op::Not:
        case Op::Truth:
        case Op::Select:
        case Op::Branch: n += may_be_nan(in->args[0], r); break;
        default: break;
      }
    }
  return n;
}

double best_param_bound(const Function& fn) {
  int best_tests = nan_tests(fn, {});
  double best = 0;
  for (double bound : kParamBounds) {
    int tests = nan_tests(fn, value_ranges(fn, bound));
    if (tests < best_tests) best_tests = tests, best = bound;
  }
  return best;
}

}  // namespace fscript::ir
