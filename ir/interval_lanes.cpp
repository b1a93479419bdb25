// The batched interval evaluator's loop, compiled once per ISA (FS_ISA): the rules the tapes run
// most, over kIntervalLanes regions at once, in branch-free lane loops the compiler vectorizes.
// In float, without widening: every backend computes + - * sqrt min max as correctly rounded float
// operations, which are monotone, so the rounded corner values already bound every point result.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ir/interval_lanes.h"

namespace fscript::ir::FS_ISA {

namespace {

constexpr size_t L = kIntervalLanes;
constexpr float kInf = std::numeric_limits<float>::infinity();

using Lanes = IntervalLanes;

// Lanes that hold no number (lo > hi) give "only NaN", as the scalar rules do.
inline void only_nan_where_empty(const Lanes& a, const Lanes& b, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    bool empty = a.lo[i] > a.hi[i] || b.lo[i] > b.hi[i];
    r.lo[i] = empty ? kInf : r.lo[i];
    r.hi[i] = empty ? -kInf : r.hi[i];
    r.nan[i] = empty ? 1u : r.nan[i];
  }
}

void add(const Lanes& a, const Lanes& b, bool negate_b, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    float blo = negate_b ? -b.hi[i] : b.lo[i], bhi = negate_b ? -b.lo[i] : b.hi[i];
    float lo = a.lo[i] + blo, hi = a.hi[i] + bhi;
    uint32_t nan = a.nan[i] | b.nan[i] | ((a.hi[i] == kInf) & (blo == -kInf)) | ((a.lo[i] == -kInf) & (bhi == kInf));
    r.lo[i] = lo != lo ? -kInf : lo;
    r.hi[i] = hi != hi ? kInf : hi;
    r.nan[i] = nan;
  }
  only_nan_where_empty(a, b, r);
}

void mul(const Lanes& a, const Lanes& b, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    float p0 = a.lo[i] * b.lo[i], p1 = a.lo[i] * b.hi[i], p2 = a.hi[i] * b.lo[i], p3 = a.hi[i] * b.hi[i];
    bool undefined = p0 != p0 || p1 != p1 || p2 != p2 || p3 != p3;  // 0 * inf at a corner
    bool a0 = a.lo[i] <= 0 && a.hi[i] >= 0, b0 = b.lo[i] <= 0 && b.hi[i] >= 0;
    bool ainf = a.lo[i] == -kInf || a.hi[i] == kInf, binf = b.lo[i] == -kInf || b.hi[i] == kInf;
    float lo = std::min(std::min(p0, p1), std::min(p2, p3)), hi = std::max(std::max(p0, p1), std::max(p2, p3));
    r.lo[i] = undefined ? -kInf : lo;
    r.hi[i] = undefined ? kInf : hi;
    r.nan[i] = a.nan[i] | b.nan[i] | static_cast<uint32_t>(undefined | (a0 & binf) | (b0 & ainf));
  }
  only_nan_where_empty(a, b, r);
}

void square(const Lanes& a, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    float x = a.lo[i] * a.lo[i], y = a.hi[i] * a.hi[i];
    bool zero = a.lo[i] <= 0 && a.hi[i] >= 0;
    r.lo[i] = zero ? 0.0f : std::min(x, y);
    r.hi[i] = std::max(x, y);
    r.nan[i] = a.nan[i];
  }
  only_nan_where_empty(a, a, r);
}

void neg(const Lanes& a, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    float lo = -a.hi[i], hi = -a.lo[i];  // an empty interval stays empty
    r.lo[i] = lo, r.hi[i] = hi, r.nan[i] = a.nan[i];
  }
}

void min_max(bool is_min, const Lanes& a, const Lanes& b, Lanes& r, Choice* choice) {
  for (size_t i = 0; i < L; ++i) {
    r.lo[i] = is_min ? std::min(a.lo[i], b.lo[i]) : std::max(a.lo[i], b.lo[i]);
    r.hi[i] = is_min ? std::min(a.hi[i], b.hi[i]) : std::max(a.hi[i], b.hi[i]);
    r.nan[i] = a.nan[i] | b.nan[i];
    // The side taken, when the sides do not touch and the other is never NaN (as choice_of).
    bool empty = a.lo[i] > a.hi[i] || b.lo[i] > b.hi[i];
    bool a_below = a.hi[i] < b.lo[i], b_below = b.hi[i] < a.lo[i];
    bool left = !empty && (is_min ? a_below : b_below) && !b.nan[i];
    bool right = !empty && (is_min ? b_below : a_below) && !a.nan[i];
    choice[i] = left ? Choice::Left : right ? Choice::Right : Choice::Both;
  }
  only_nan_where_empty(a, b, r);
}

void sqrt(const Lanes& a, Lanes& r) {
  for (size_t i = 0; i < L; ++i) {
    bool none = a.lo[i] > a.hi[i] || a.hi[i] < 0;
    float lo = std::sqrt(std::max(a.lo[i], 0.0f)), hi = std::sqrt(std::max(a.hi[i], 0.0f));
    r.lo[i] = none ? kInf : lo;
    r.hi[i] = none ? -kInf : hi;
    r.nan[i] = none ? 1u : a.nan[i] | static_cast<uint32_t>(a.lo[i] < 0);
  }
}

void constant(float v, Lanes& r) {
  bool nan = v != v;
  for (size_t i = 0; i < L; ++i) {
    r.lo[i] = nan ? kInf : v;
    r.hi[i] = nan ? -kInf : v;
    r.nan[i] = nan;
  }
}

// Any other op: its scalar rule, lane by lane (interval_rule's switch lists every op).
void scalar(const IntervalTape::Step& s, const Lanes* v, Lanes& r, Choice* choice) {
  static const Lanes everything = [] {
    Lanes e;
    for (size_t i = 0; i < L; ++i) e.set(i, math::Interval::everything());
    return e;
  }();
  const Lanes& a = s.arity > 0 ? v[s.a] : everything;
  const Lanes& b = s.arity > 1 ? v[s.b] : everything;
  const Lanes& c = s.arity > 2 ? v[s.c] : everything;
  bool chooses = s.op == Op::Select;
  for (size_t i = 0; i < L; ++i) {
    math::Interval x = a.lane(i), y = b.lane(i), z = c.lane(i);
    r.set(i, interval_rule(s.op, s.square, s.imm, x, y, z));
    if (chooses) choice[i] = choice_of(s.op, x, y, z);
  }
}

}  // namespace

void eval_lanes(const IntervalTape::Step* steps, size_t n, const IntervalLanes* inputs, size_t num_inputs,
                IntervalLanes* v, Choice* choices) {
  static const IntervalLanes everything = [] {
    IntervalLanes e;
    for (size_t i = 0; i < L; ++i) e.set(i, math::Interval::everything());
    return e;
  }();
  for (size_t k = 0; k < n; ++k) {
    const IntervalTape::Step& s = steps[k];
    Lanes& r = v[s.dst];
    switch (s.op) {
      case Op::Param: r = s.a < num_inputs ? inputs[s.a] : everything; break;
      case Op::Const: constant(s.imm, r); break;
      case Op::Add: add(v[s.a], v[s.b], false, r); break;
      case Op::Sub: add(v[s.a], v[s.b], true, r); break;
      case Op::Mul: s.square ? square(v[s.a], r) : mul(v[s.a], v[s.b], r); break;
      case Op::Neg: neg(v[s.a], r); break;
      case Op::Min: min_max(true, v[s.a], v[s.b], r, choices + size_t(s.dst) * L); break;
      case Op::Max: min_max(false, v[s.a], v[s.b], r, choices + size_t(s.dst) * L); break;
      case Op::Sqrt: sqrt(v[s.a], r); break;
      default: scalar(s, v, r, choices + size_t(s.dst) * L); break;  // the rest: see scalar()
    }
  }
}

}  // namespace fscript::ir::FS_ISA
