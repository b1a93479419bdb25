#pragma once
// Interval arithmetic for every built-in: iv::FN bounds what math::FN (and its batch twin, as every
// backend computes it, rounding included) can return for any inputs in the given intervals.
// ir/math_ops.def names each op's FN; the interval evaluator calls iv::FN for that row.
#include <cmath>
#include <limits>

namespace fscript::math {

// Every non-NaN value lies in [lo, hi] (bounds may be infinite; lo > hi: no number, only NaN);
// `nan`: NaN may come out. Signs of zero are not tracked (-0 lies in [0, 0]).
struct Interval {
  float lo = -std::numeric_limits<float>::infinity();
  float hi = std::numeric_limits<float>::infinity();
  bool nan = true;

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

Interval add(Interval a, Interval b);
Interval sub(Interval a, Interval b);
Interval mul(Interval a, Interval b);
Interval square(Interval a);  // a * a for one value (never negative)
Interval div(Interval a, Interval b);
Interval mod(Interval a, Interval b);
Interval neg(Interval a);
Interval min(Interval a, Interval b);
Interval max(Interval a, Interval b);
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
Interval hull(Interval a, Interval b);

}  // namespace iv
}  // namespace fscript::math
