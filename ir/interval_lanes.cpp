// The batched interval evaluator's loop, compiled once per ISA (FS_ISA): the rules the tapes run
// most, over kIntervalLanes regions at once, in branch-free lane loops the compiler vectorizes.
// In float, without widening: every backend computes + - * sqrt min max as correctly rounded float
// operations, which are monotone, so the rounded corner values already bound every point result.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "ir/interval_lanes.h"
#include "runtime/math/batch_isa.h"

namespace fscript::ir::FS_ISA {

namespace {

constexpr size_t L = kIntervalLanes;
constexpr float kInf = std::numeric_limits<float>::infinity();

using Lanes = IntervalLanes;
// GCC vector extensions: one vector of all the lanes, split into what the ISA has (4 SSE registers,
// 2 AVX2, 1 AVX-512), so every rule below is straight-line SIMD whatever the target.
typedef float F __attribute__((vector_size(L * sizeof(float))));
typedef int32_t I __attribute__((vector_size(L * sizeof(float))));
typedef uint32_t U __attribute__((vector_size(L * sizeof(float))));
static_assert(sizeof(F) == sizeof(Lanes::lo), "one vector per field");

struct V {
  F lo, hi;
  U nan;
};

inline V load(const Lanes& a) {
  V v;
  std::memcpy(&v.lo, a.lo, sizeof v.lo);
  std::memcpy(&v.hi, a.hi, sizeof v.hi);
  std::memcpy(&v.nan, a.nan, sizeof v.nan);
  return v;
}

// Lanes that hold no number (lo > hi) give "only NaN", as the scalar rules do.
inline void store(V r, I empty, Lanes& out) {
  F inf = F{} + kInf;
  r.lo = empty ? inf : r.lo;
  r.hi = empty ? -inf : r.hi;
  r.nan = empty ? U{} + 1u : r.nan;
  std::memcpy(out.lo, &r.lo, sizeof r.lo);
  std::memcpy(out.hi, &r.hi, sizeof r.hi);
  std::memcpy(out.nan, &r.nan, sizeof r.nan);
}

inline U bit(I mask) { return reinterpret_cast<U&>(mask) & 1u; }

void add(const Lanes& la, const Lanes& lb, bool negate_b, Lanes& out) {
  V a = load(la), b = load(lb);
  if (negate_b) {
    F t = -b.hi;
    b.hi = -b.lo, b.lo = t;
  }
  F inf = F{} + kInf;
  V r;
  r.lo = a.lo + b.lo;
  r.hi = a.hi + b.hi;
  r.lo = r.lo != r.lo ? -inf : r.lo;
  r.hi = r.hi != r.hi ? inf : r.hi;
  r.nan = a.nan | b.nan | bit(((a.hi == inf) & (b.lo == -inf)) | ((a.lo == -inf) & (b.hi == inf)));
  store(r, (a.lo > a.hi) | (b.lo > b.hi), out);
}

void mul(const Lanes& la, const Lanes& lb, Lanes& out) {
  V a = load(la), b = load(lb);
  F inf = F{} + kInf;
  F p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  I undefined = (p0 != p0) | (p1 != p1) | (p2 != p2) | (p3 != p3);  // 0 * inf at a corner
  I a0 = (a.lo <= 0) & (a.hi >= 0), b0 = (b.lo <= 0) & (b.hi >= 0);
  I ainf = (a.lo == -inf) | (a.hi == inf), binf = (b.lo == -inf) | (b.hi == inf);
  F lo01 = p0 < p1 ? p0 : p1, lo23 = p2 < p3 ? p2 : p3, hi01 = p0 > p1 ? p0 : p1, hi23 = p2 > p3 ? p2 : p3;
  V r;
  r.lo = undefined ? -inf : (lo01 < lo23 ? lo01 : lo23);
  r.hi = undefined ? inf : (hi01 > hi23 ? hi01 : hi23);
  r.nan = a.nan | b.nan | bit(undefined | (a0 & binf) | (b0 & ainf));
  store(r, (a.lo > a.hi) | (b.lo > b.hi), out);
}

void square(const Lanes& la, Lanes& out) {
  V a = load(la);
  F x = a.lo * a.lo, y = a.hi * a.hi;
  V r;
  r.lo = ((a.lo <= 0) & (a.hi >= 0)) ? F{} : (x < y ? x : y);
  r.hi = x > y ? x : y;
  r.nan = a.nan;
  store(r, a.lo > a.hi, out);
}

void neg(const Lanes& la, Lanes& out) {
  V a = load(la), r{-a.hi, -a.lo, a.nan};  // an empty interval stays empty
  store(r, I{}, out);
}

void min_max(bool is_min, const Lanes& la, const Lanes& lb, Lanes& out, Choice* choice) {
  V a = load(la), b = load(lb);
  V r;
  r.lo = is_min ? (b.lo < a.lo ? b.lo : a.lo) : (b.lo > a.lo ? b.lo : a.lo);
  r.hi = is_min ? (b.hi < a.hi ? b.hi : a.hi) : (b.hi > a.hi ? b.hi : a.hi);
  r.nan = a.nan | b.nan;
  I empty = (a.lo > a.hi) | (b.lo > b.hi);
  // The side taken, when the sides do not touch and the other is never NaN (as choice_of).
  I a_below = a.hi < b.lo, b_below = b.hi < a.lo;
  I left = ~empty & (is_min ? a_below : b_below) & (b.nan == 0);
  I right = ~empty & (is_min ? b_below : a_below) & (a.nan == 0);
  for (size_t i = 0; i < L; ++i) choice[i] = left[i] ? Choice::Left : right[i] ? Choice::Right : Choice::Both;
  store(r, empty, out);
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

// sin or cos over each lane (interval.cpp's periodic, lane by lane in its decisions): the ends by
// the batch twin the backends call (sincos_batch: their very bits, within 3 ulps of the truth, one
// range reduction for both ends' sin and cos), widened by kTrigUlps so that every backend's value at
// every point of the interval, itself within 3 ulps of the truth, lies inside; -1 and 1 (widened as
// the scalar rule widens them) where the interval reaches a trough or a crest.
constexpr int kTrigUlps = 6;

// floor without a library call (exact: every double past 2^52 is an integer).
inline double floor_of(double x) {
  if (!(std::fabs(x) < 4503599627370496.0)) return x;
  double t = static_cast<double>(static_cast<int64_t>(x));
  return t > x ? t - 1 : t;
}

// Whether lo <= c + k * 2 pi <= hi for some integer k, a little generous (as interval.cpp's hits).
inline bool reaches(double lo, double hi, double c) {
  constexpr double kInvTwoPi = 0.15915494309189533577;
  double slack = 1e-9 * (1 + std::fabs(lo) + std::fabs(hi));
  return floor_of((hi - c + slack) * kInvTwoPi) >= -floor_of(-((lo - c - slack) * kInvTwoPi));
}

void trig(const Lanes& a, bool cos, Lanes& r) {
  constexpr double kPi = 3.14159265358979323846;
  float s_lo[L], c_lo[L], s_hi[L], c_hi[L];
  math::FS_ISA::sincos_batch(a.lo, s_lo, c_lo, L);
  math::FS_ISA::sincos_batch(a.hi, s_hi, c_hi, L);
  const double crest = cos ? 0 : kPi / 2, trough = cos ? kPi : -kPi / 2;
  for (size_t i = 0; i < L; ++i) {
    const float lo = a.lo[i], hi = a.hi[i];
    if (lo > hi) {  // no number: only NaN
      r.lo[i] = kInf, r.hi[i] = -kInf, r.nan[i] = 1u;
      continue;
    }
    const bool inf = lo == -kInf || hi == kInf;
    r.nan[i] = a.nan[i] | static_cast<uint32_t>(inf);
    if (inf || static_cast<double>(hi) - lo >= 2 * kPi) {
      r.lo[i] = math::detail::down(-1, 4), r.hi[i] = math::detail::up(1, 4);  // the scalar rule's
      continue;
    }
    const float x = cos ? c_lo[i] : s_lo[i], y = cos ? c_hi[i] : s_hi[i];
    r.lo[i] = reaches(lo, hi, trough) ? math::detail::down(-1, 4) : math::detail::down(std::min(x, y), kTrigUlps);
    r.hi[i] = reaches(lo, hi, crest) ? math::detail::up(1, 4) : math::detail::up(std::max(x, y), kTrigUlps);
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

// Every lane the whole real line, maybe NaN: a missing operand or parameter.
const Lanes& everything() {
  static const Lanes e = [] {
    Lanes x;
    for (size_t i = 0; i < L; ++i) x.set(i, math::Interval::everything());
    return x;
  }();
  return e;
}

// Any other op: its scalar rule, lane by lane (interval_rule's switch lists every op).
void scalar(const IntervalTape::Step& s, const Lanes* v, Lanes& r, Choice* choice) {
  const Lanes& a = s.arity > 0 ? v[s.a] : everything();
  const Lanes& b = s.arity > 1 ? v[s.b] : everything();
  const Lanes& c = s.arity > 2 ? v[s.c] : everything();
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
  for (size_t k = 0; k < n; ++k) {
    const IntervalTape::Step& s = steps[k];
    Lanes& r = v[s.dst];
    switch (s.op) {
      case Op::Param: r = s.a < num_inputs ? inputs[s.a] : everything(); break;
      case Op::Const: constant(s.imm, r); break;
      case Op::Add: add(v[s.a], v[s.b], false, r); break;
      case Op::Sub: add(v[s.a], v[s.b], true, r); break;
      case Op::Mul: s.square ? square(v[s.a], r) : mul(v[s.a], v[s.b], r); break;
      case Op::Neg: neg(v[s.a], r); break;
      case Op::Min: min_max(true, v[s.a], v[s.b], r, choices + size_t(s.dst) * L); break;
      case Op::Max: min_max(false, v[s.a], v[s.b], r, choices + size_t(s.dst) * L); break;
      case Op::Sqrt: sqrt(v[s.a], r); break;
      case Op::Sin: trig(v[s.a], false, r); break;
      case Op::Cos: trig(v[s.a], true, r); break;
      default: scalar(s, v, r, choices + size_t(s.dst) * L); break;  // the rest: see scalar(), simd_interval_op
    }
  }
}

}  // namespace fscript::ir::FS_ISA
