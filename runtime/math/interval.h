#pragma once
// Interval arithmetic for every built-in: iv::FN bounds what math::FN (and its batch twin, as every
// backend computes it, rounding included) can return for any inputs in the given intervals.
// ir/math_ops.def names each op's FN; the interval evaluator calls iv::FN for that row.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace fscript::math {

// Every non-NaN value lies in [lo, hi] (bounds may be infinite; lo > hi: no number, only NaN);
// `nan`: NaN may come out. Signs of zero are not tracked (-0 lies in [0, 0]).
struct Interval {
  float lo = -std::numeric_limits<float>::infinity();
  float hi = std::numeric_limits<float>::infinity();
  uint32_t nan = 1;  // a word, not a bool: a byte store read back as a word stalls the interval loops

  static Interval point(float v) { return v != v ? nan_only() : Interval{v, v, false}; }
  static Interval nan_only() {
    return {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(), true};
  }
  static Interval everything() { return {}; }
  bool empty() const { return lo > hi; }
  // Whether v (a point result) is allowed.
  bool contains(float v) const { return v != v ? nan : (lo <= v && v <= hi); }
};

// Truthiness of every value in an interval: always (nonzero, never NaN), never (only 0 or NaN), or
// either (comparisons and select use it).
enum class Truth { Always, Never, Either };
Truth truth_of(const Interval& a);

namespace iv {

inline Interval add(Interval a, Interval b);
inline Interval sub(Interval a, Interval b);
inline Interval mul(Interval a, Interval b);
inline Interval square(Interval a);  // a * a for one value (never negative)
Interval div(Interval a, Interval b);
Interval mod(Interval a, Interval b);
inline Interval neg(Interval a);
inline Interval min(Interval a, Interval b);
inline Interval max(Interval a, Interval b);
Interval abs(Interval a);
Interval sqrt(Interval a);
Interval floor(Interval a);
Interval ceil(Interval a);
Interval round(Interval a);
Interval sign(Interval a);
Interval clamp(Interval a, Interval lo, Interval hi);
Interval pow(Interval a, Interval b);
Interval exp(Interval a);
Interval log(Interval a);
Interval log10(Interval a);
Interval sin(Interval a);
Interval cos(Interval a);
Interval tan(Interval a);
Interval asin(Interval a);
Interval acos(Interval a);
Interval atan(Interval a);
Interval atan2(Interval y, Interval x);
Interval hypot(Interval x, Interval y);
Interval sinh(Interval a);
Interval cosh(Interval a);
Interval tanh(Interval a);
Interval noise(Interval x, Interval y, Interval z);
Interval eq(Interval a, Interval b);
Interval ne(Interval a, Interval b);
Interval lt(Interval a, Interval b);
Interval le(Interval a, Interval b);
Interval gt(Interval a, Interval b);
Interval ge(Interval a, Interval b);
Interval not_(Interval a);
Interval truth(Interval a);
Interval select(Interval c, Interval a, Interval b);
// The smallest interval holding both.
inline Interval hull(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi), a.nan || b.nan}; }

}  // namespace iv

// Outward rounding, and the rules the tapes run most (+ - * min max neg), inline: an interval
// returned from a call is packed through memory (two floats into one register), and that store
// forwarding stall cost more than the arithmetic.
namespace detail {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr float kInfF = std::numeric_limits<float>::infinity();

// The next float toward -inf (toward +inf for next_up), by its bits. -inf and +inf stay put.
[[gnu::always_inline]] inline float next_down(float f) {
  if (f == -kInfF || f != f) return f;
  if (f == 0) return -std::numeric_limits<float>::denorm_min();
  uint32_t b = std::bit_cast<uint32_t>(f);
  return std::bit_cast<float>(f > 0 ? b - 1 : b + 1);
}

[[gnu::always_inline]] inline float next_up(float f) { return -next_down(-f); }

// `ulps` times next_down: by the bits in one step where no step meets 0 or -inf (the loop's
// answer exactly), else step by step.
[[gnu::always_inline]] inline float steps_down(float f, int ulps) {
  const uint32_t b = std::bit_cast<uint32_t>(f), u = static_cast<uint32_t>(ulps);
  if (f > 0 && b > u) return std::bit_cast<float>(b - u);
  if (f < 0 && (b & 0x7fffffffu) + u <= 0x7f800000u) return std::bit_cast<float>(b + u);
  for (int k = 0; k < ulps; ++k) f = next_down(f);
  return f;
}

// The largest float <= x, `ulps` further down (NaN: -inf); up() likewise.
[[gnu::always_inline]] inline float down(double x, int ulps) {
  if (x != x) return -kInfF;
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = next_down(f);
  return steps_down(f, ulps);
}

[[gnu::always_inline]] inline float up(double x, int ulps) {
  if (x != x) return kInfF;
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = next_up(f);
  return -steps_down(-f, ulps);
}

[[gnu::always_inline]] inline Interval make(double lo, double hi, bool nan, int ulps) {
  return {down(lo, ulps), up(hi, ulps), nan};
}
inline bool has_zero(const Interval& a) { return a.lo <= 0 && a.hi >= 0; }
inline bool has_inf(const Interval& a) { return a.lo == -kInfF || a.hi == kInfF; }

}  // namespace detail

namespace iv {

// + - * in double are exact (or round monotonically): no ulps needed.
[[gnu::always_inline]] inline Interval add(Interval a, Interval b) {
  using namespace detail;
  if (a.empty() || b.empty()) return Interval::nan_only();
  bool nan = a.nan || b.nan || (a.hi == kInfF && b.lo == -kInfF) || (a.lo == -kInfF && b.hi == kInfF);
  double lo = static_cast<double>(a.lo) + b.lo, hi = static_cast<double>(a.hi) + b.hi;
  return make(lo != lo ? -kInf : lo, hi != hi ? kInf : hi, nan, 0);
}

[[gnu::always_inline]] inline Interval neg(Interval a) { return {-a.hi, -a.lo, a.nan}; }
[[gnu::always_inline]] inline Interval sub(Interval a, Interval b) {
  return add(a, neg(b));
}  // a - b is a + (-b), bit for bit

[[gnu::always_inline]] inline Interval mul(Interval a, Interval b) {
  using namespace detail;
  if (a.empty() || b.empty()) return Interval::nan_only();
  bool nan = a.nan || b.nan || (has_zero(a) && has_inf(b)) || (has_zero(b) && has_inf(a));
  double p[] = {static_cast<double>(a.lo) * b.lo, static_cast<double>(a.lo) * b.hi, static_cast<double>(a.hi) * b.lo,
                static_cast<double>(a.hi) * b.hi};
  for (double v : p)
    if (v != v) return {-kInfF, kInfF, true};
  return make(std::min(std::min(p[0], p[1]), std::min(p[2], p[3])),
              std::max(std::max(p[0], p[1]), std::max(p[2], p[3])), nan, 0);
}

[[gnu::always_inline]] inline Interval square(Interval a) {
  using namespace detail;
  if (a.empty()) return Interval::nan_only();
  double x = static_cast<double>(a.lo) * a.lo, y = static_cast<double>(a.hi) * a.hi;
  return make(has_zero(a) ? 0 : std::min(x, y), std::max(x, y), a.nan, 0);
}

[[gnu::always_inline]] inline Interval min(Interval a, Interval b) {
  if (a.empty() || b.empty()) return Interval::nan_only();
  return {std::min(a.lo, b.lo), std::min(a.hi, b.hi), a.nan || b.nan};
}

[[gnu::always_inline]] inline Interval max(Interval a, Interval b) {
  if (a.empty() || b.empty()) return Interval::nan_only();
  return {std::max(a.lo, b.lo), std::max(a.hi, b.hi), a.nan || b.nan};
}

}  // namespace iv
}  // namespace fscript::math
