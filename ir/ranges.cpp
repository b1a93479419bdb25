// Interval analysis over one pass in reverse post-order. Bounds are computed in double and widened
// outward so float rounding of the real operation always stays inside them.
#include "ir/ranges.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "ir/analysis.h"

namespace fscript::ir {
namespace {

constexpr double kInf = INFINITY;
const Range kTop{-kInf, kInf, true};

bool finite(const Range& r) { return r.lo > -kInf && r.hi < kInf; }

// Outward by far more than a float rounding (2^-24 relative); zero stays zero, so a sum of squares
// keeps its non-negative lower bound. Beyond the float range a bound becomes infinite.
Range widen(double lo, double hi, bool nan) {
  lo -= std::fabs(lo) * 1e-5;
  hi += std::fabs(hi) * 1e-5;
  if (lo < -FLT_MAX) lo = -kInf;
  if (hi > FLT_MAX) hi = kInf;
  return {lo, hi, nan};
}

Range join(const Range& a, const Range& b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.nan || b.nan}; }

// Infinite operands can meet as inf - inf or 0 * inf: NaN.
Range arith(const Range& a, const Range& b, double lo, double hi) {
  if (!finite(a) || !finite(b)) return kTop;
  return widen(lo, hi, a.nan || b.nan);
}

Range mul(const Range& a, const Range& b, bool square) {
  if (square) {
    double lo = (a.lo <= 0 && a.hi >= 0) ? 0 : std::min(a.lo * a.lo, a.hi * a.hi);
    return arith(a, a, lo, std::max(a.lo * a.lo, a.hi * a.hi));
  }
  double p[] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return arith(a, b, *std::min_element(p, p + 4), *std::max_element(p, p + 4));
}

Range range_of(const Inst& in, const std::vector<Range>& r, double bound) {
  auto arg = [&](size_t i) { return r[in.args[i]->id]; };
  switch (in.op) {
    case Op::Const: return {in.imm, in.imm, in.imm != in.imm};
    case Op::Param: return {-bound, bound, false};
    case Op::Add: return arith(arg(0), arg(1), arg(0).lo + arg(1).lo, arg(0).hi + arg(1).hi);
    case Op::Sub: return arith(arg(0), arg(1), arg(0).lo - arg(1).hi, arg(0).hi - arg(1).lo);
    case Op::Mul: return mul(arg(0), arg(1), in.args[0] == in.args[1]);
    case Op::Neg: return {-arg(0).hi, -arg(0).lo, arg(0).nan};
    case Op::Abs: {
      Range a = arg(0);
      double lo = (a.lo <= 0 && a.hi >= 0) ? 0 : std::min(std::fabs(a.lo), std::fabs(a.hi));
      return {lo, std::max(std::fabs(a.lo), std::fabs(a.hi)), a.nan};
    }
    case Op::Min: return {std::min(arg(0).lo, arg(1).lo), std::min(arg(0).hi, arg(1).hi), arg(0).nan || arg(1).nan};
    case Op::Max: return {std::max(arg(0).lo, arg(1).lo), std::max(arg(0).hi, arg(1).hi), arg(0).nan || arg(1).nan};
    case Op::Clamp: {
      Range lo{std::max(arg(0).lo, arg(1).lo), std::max(arg(0).hi, arg(1).hi), arg(0).nan || arg(1).nan};
      return {std::min(lo.lo, arg(2).lo), std::min(lo.hi, arg(2).hi), lo.nan || arg(2).nan};
    }
    case Op::Sqrt: {
      Range a = arg(0);
      return widen(std::sqrt(std::max(a.lo, 0.0)), std::sqrt(a.hi), a.nan || a.lo < 0);
    }
    case Op::Floor: case Op::Ceil: case Op::Round:
      return {std::floor(arg(0).lo), std::ceil(arg(0).hi), arg(0).nan};
    case Op::Sign: return {-1, 1, arg(0).nan};
    case Op::Sin: case Op::Cos: return {-1, 1, arg(0).nan || !finite(arg(0))};
    case Op::Hypot: {  // between the larger magnitude and the length of the largest corner
      auto least = [](const Range& r) { return r.lo <= 0 && r.hi >= 0 ? 0.0 : std::min(std::fabs(r.lo), std::fabs(r.hi)); };
      auto most = [](const Range& r) { return std::max(std::fabs(r.lo), std::fabs(r.hi)); };
      double hi = std::sqrt(most(arg(0)) * most(arg(0)) + most(arg(1)) * most(arg(1)));
      return widen(std::max(least(arg(0)), least(arg(1))), hi, arg(0).nan || arg(1).nan);
    }
    case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::Not: case Op::Truth:
      return {0, 1, false};
    case Op::Select: return join(arg(1), arg(2));
    case Op::Div: case Op::Mod: case Op::Pow: case Op::Exp: case Op::Log: case Op::Log10: case Op::Tan:
    case Op::Asin: case Op::Acos: case Op::Atan: case Op::Atan2: case Op::Sinh: case Op::Cosh: case Op::Tanh:
    case Op::Noise: case Op::Phi: case Op::GLoad: case Op::GStore: case Op::ANew: case Op::ALoad:
    case Op::AStore: case Op::ALen: case Op::Call: case Op::Tick: case Op::Jump: case Op::Branch: case Op::Ret:
      return kTop;
  }
  return kTop;
}

}  // namespace

std::vector<Range> value_ranges(const Function& fn, double param_bound) {
  std::vector<Range> r(fn.next_value, kTop);
  for (const Block* blk : reverse_post_order(fn))
    for (const Inst* in : blk->insts)
      if (in->defines_value()) r[in->id] = range_of(*in, r, param_bound);
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
        case Op::Min: case Op::Max: n += may_be_nan(in->args[1], r); break;
        case Op::Clamp: n += may_be_nan(in->args[1], r) + may_be_nan(in->args[2], r); break;
        case Op::Not: case Op::Truth: case Op::Select: case Op::Branch: n += may_be_nan(in->args[0], r); break;
        default: break;
      }
    }
  return n;
}

double best_param_bound(const Function& fn) {
  int best_tests = nan_tests(fn, {});
  double best = 0;
  for (double bound : {65536.0, 1024.0, 16.0}) {
    int tests = nan_tests(fn, value_ranges(fn, bound));
    if (tests < best_tests) best_tests = tests, best = bound;
  }
  return best;
}

}  // namespace fscript::ir
