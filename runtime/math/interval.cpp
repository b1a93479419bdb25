// Interval rules of the built-ins. Bounds are computed in double at the ends (and the extrema) and
// rounded outward to float: exact operations need no more; the rest are widened by the ulps the
// accuracy statement allows (docs/language.md), so every backend's point result stays inside.
#include "runtime/math/interval.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "runtime/math/math.h"

namespace fscript::math {
namespace {

using detail::down;
using detail::has_inf;
using detail::has_zero;
using detail::kInf;
using detail::kInfF;
using detail::make;
using detail::next_down;
using detail::next_up;
using detail::up;
constexpr double kPi = 3.14159265358979323846;
constexpr int kRoundedUlps = 1; // / and sqrt: rounded in double, then to float
constexpr int kMathUlps = 4;    // every other built-in: the language's bound

double least_magnitude(const Interval& a) { return has_zero(a) ? 0.0 : std::min(std::fabs(a.lo), std::fabs(a.hi)); }
double most_magnitude(const Interval& a) { return std::max(std::fabs(a.lo), std::fabs(a.hi)); }

// An increasing function f of one argument over its domain's part [lo, hi].
template <class F>
Interval increasing(const Interval& a, F f, bool nan) {
  return make(f(static_cast<double>(a.lo)), f(static_cast<double>(a.hi)), nan, kMathUlps);
}

// floor and ceil without a library call (the build targets baseline x86-64, which has no
// rounding instruction): exact, as every double past 2^52 is an integer.
double floor_of(double x) {
  if (!(std::fabs(x) < 4503599627370496.0)) return x;
  double t = static_cast<double>(static_cast<int64_t>(x));
  return t > x ? t - 1 : t;
}
double ceil_of(double x) { return -floor_of(-x); }

// Whether lo <= c + k * period <= hi for some integer k (a little generous, never less: the
// slack, a billionth of the ends' size, is far beyond the rounding of multiplying by 1 / period).
bool hits(double lo, double hi, double c, double inv_period) {
  double slack = 1e-9 * (1 + std::fabs(lo) + std::fabs(hi));
  return floor_of((hi - c + slack) * inv_period) >= ceil_of((lo - c - slack) * inv_period);
}

// sin or cos over a: the ends, and -1 / 1 where the interval reaches a trough / crest.
Interval periodic(const Interval& a, double (*f)(double), double crest, double trough) {
  if (a.empty()) return Interval::nan_only();
  bool nan = a.nan || has_inf(a);
  if (has_inf(a) || static_cast<double>(a.hi) - a.lo >= 2 * kPi) return make(-1, 1, nan, kMathUlps);
  double x = f(a.lo), y = f(a.hi);
  double lo = hits(a.lo, a.hi, trough, 1 / (2 * kPi)) ? -1 : std::min(x, y);
  double hi = hits(a.lo, a.hi, crest, 1 / (2 * kPi)) ? 1 : std::max(x, y);
  return make(lo, hi, nan, kMathUlps);
}

Interval from_truth(Truth t) {
  if (t == Truth::Always) return {1, 1, false};
  if (t == Truth::Never) return {0, 0, false};
  return {0, 1, false};
}

Truth negate(Truth t) { return t == Truth::Always ? Truth::Never : t == Truth::Never ? Truth::Always : Truth::Either; }

// a < b (strict) or a <= b for every pair of numbers, and for none (NaN compares false).
Truth less(const Interval& a, const Interval& b, bool strict) {
  if (a.empty() || b.empty()) return Truth::Never;
  bool always = !a.nan && !b.nan && (strict ? a.hi < b.lo : a.hi <= b.lo);
  bool never = strict ? a.lo >= b.hi : a.lo > b.hi;
  return always ? Truth::Always : never ? Truth::Never : Truth::Either;
}

Truth equal(const Interval& a, const Interval& b) {
  if (a.empty() || b.empty() || a.hi < b.lo || b.hi < a.lo) return Truth::Never;
  if (!a.nan && !b.nan && a.lo == a.hi && b.lo == b.hi && a.lo == b.lo) return Truth::Always;
  return Truth::Either;
}

// pow(a, k) for one exponent k (not NaN, not 0, finite).
Interval pow_point(const Interval& a, double k) {
  auto p = [k](double x) { return std::pow(x, k); };
  bool integer = k == std::floor(k);
  if (a.lo > 0 || (a.lo >= 0 && k > 0)) {  // monotone on [0, inf) (-0 ** negative is -inf: excluded)
    double x = p(a.lo), y = p(a.hi);
    return make(std::min(x, y), std::max(x, y), a.nan, kMathUlps);
  }
  if (!integer) {  // finite negative bases give NaN, -inf gives inf or 0; on [0, hi] it is monotone
    Interval r = a.hi < 0 ? Interval::nan_only()
        : k < 0           ? make(p(a.hi), kInf, true, kMathUlps)
                          : make(0, p(a.hi), true, kMathUlps);
    return a.lo == -kInfF ? iv::hull(r, Interval::point(k < 0 ? 0.0f : kInfF)) : r;
  }
  bool even = std::fmod(k, 2) == 0;
  if (has_zero(a)) {
    if (k < 0) return {-kInfF, kInfF, a.nan};  // through a pole
    if (even) return make(0, std::max(p(a.lo), p(a.hi)), a.nan, kMathUlps);
  }
  double x = p(a.lo), y = p(a.hi);  // integer powers are monotone where the sign is fixed
  return make(std::min(x, y), std::max(x, y), a.nan, kMathUlps);
}

}  // namespace

Truth truth_of(const Interval& a) {
  if (a.empty() || (a.lo == 0 && a.hi == 0)) return Truth::Never;
  if (!a.nan && (a.lo > 0 || a.hi < 0)) return Truth::Always;
  return Truth::Either;
}

namespace iv {

Interval div(Interval a, Interval b) {
  if (a.empty() || b.empty()) return Interval::nan_only();
  bool inf_inf = has_inf(a) && has_inf(b);
  if (has_zero(b)) return {-kInfF, kInfF, a.nan || b.nan || has_zero(a) || inf_inf};
  double q[] = {static_cast<double>(a.lo) / b.lo, static_cast<double>(a.lo) / b.hi, static_cast<double>(a.hi) / b.lo,
                static_cast<double>(a.hi) / b.hi};
  for (double v : q)
    if (v != v) return {-kInfF, kInfF, true};
  return make(*std::min_element(q, q + 4), *std::max_element(q, q + 4), a.nan || b.nan || inf_inf, kRoundedUlps);
}

Interval mod(Interval a, Interval b) {  // fmod: exact, the sign of a, smaller than |b| and |a|
  if (a.empty() || b.empty()) return Interval::nan_only();
  bool nan = a.nan || b.nan || has_inf(a) || has_zero(b);
  if (!has_zero(b) && most_magnitude(a) < least_magnitude(b)) return {a.lo, a.hi, nan};  // fmod(a, b) = a
  float m = static_cast<float>(most_magnitude(b));
  return {a.lo >= 0 ? 0.0f : std::max(a.lo, -m), a.hi <= 0 ? 0.0f : std::min(a.hi, m), nan};
}

Interval abs(Interval a) {
  if (a.empty()) return Interval::nan_only();
  return {static_cast<float>(least_magnitude(a)), static_cast<float>(most_magnitude(a)), a.nan};
}

Interval sqrt(Interval a) {
  if (a.empty() || a.hi < 0) return Interval::nan_only();
  Interval r = make(std::sqrt(std::max(0.0, static_cast<double>(a.lo))), std::sqrt(static_cast<double>(a.hi)),
                    a.nan || a.lo < 0, kRoundedUlps);
  r.lo = std::max(r.lo, 0.0f);  // IEEE sqrt is never below zero (-0 counts as 0)
  return r;
}

Interval floor(Interval a) { return a.empty() ? a : Interval{math::floor(a.lo), math::floor(a.hi), a.nan}; }
Interval ceil(Interval a) { return a.empty() ? a : Interval{math::ceil(a.lo), math::ceil(a.hi), a.nan}; }
Interval round(Interval a) { return a.empty() ? a : Interval{math::round(a.lo), math::round(a.hi), a.nan}; }
Interval sign(Interval a) { return a.empty() ? a : Interval{math::sign(a.lo), math::sign(a.hi), a.nan}; }
Interval clamp(Interval a, Interval lo, Interval hi) { return min(max(a, lo), hi); }

Interval pow(Interval a, Interval b) {  // JavaScript's Math.pow
  if (b.empty()) return Interval::nan_only();
  if (b.lo != b.hi || b.nan || std::isinf(b.lo)) return Interval::everything();
  if (b.lo == 0) return {1, 1, false};  // pow(x, 0) is 1, even for NaN
  if (a.empty()) return Interval::nan_only();
  return pow_point(a, b.lo);
}

Interval exp(Interval a) {
  return a.empty() ? a : increasing(a, [](double x) { return std::exp(x); }, a.nan);
}

Interval log(Interval a) {
  if (a.empty() || a.hi < 0) return Interval::nan_only();
  return make(std::log(std::max(0.0, static_cast<double>(a.lo))), std::log(static_cast<double>(a.hi)),
              a.nan || a.lo < 0, kMathUlps);
}

Interval log10(Interval a) {
  if (a.empty() || a.hi < 0) return Interval::nan_only();
  return make(std::log10(std::max(0.0, static_cast<double>(a.lo))), std::log10(static_cast<double>(a.hi)),
              a.nan || a.lo < 0, kMathUlps);
}

Interval sin(Interval a) {
  return periodic(a, [](double x) { return std::sin(x); }, kPi / 2, -kPi / 2);
}
Interval cos(Interval a) {
  return periodic(a, [](double x) { return std::cos(x); }, 0, kPi);
}

Interval tan(Interval a) {
  if (a.empty()) return Interval::nan_only();
  bool nan = a.nan || has_inf(a);
  if (has_inf(a) || static_cast<double>(a.hi) - a.lo >= kPi || hits(a.lo, a.hi, kPi / 2, 1 / kPi))
    return {-kInfF, kInfF, nan};
  return increasing(a, [](double x) { return std::tan(x); }, nan);
}

Interval asin(Interval a) {
  if (a.empty() || a.hi < -1 || a.lo > 1) return Interval::nan_only();
  return make(std::asin(std::max(-1.0, static_cast<double>(a.lo))), std::asin(std::min(1.0, static_cast<double>(a.hi))),
              a.nan || a.lo < -1 || a.hi > 1, kMathUlps);
}

Interval acos(Interval a) {
  if (a.empty() || a.hi < -1 || a.lo > 1) return Interval::nan_only();
  return make(std::acos(std::min(1.0, static_cast<double>(a.hi))), std::acos(std::max(-1.0, static_cast<double>(a.lo))),
              a.nan || a.lo < -1 || a.hi > 1, kMathUlps);
}

Interval atan(Interval a) {
  return a.empty() ? a : increasing(a, [](double x) { return std::atan(x); }, a.nan);
}

Interval atan2(Interval y, Interval x) {
  if (y.empty() || x.empty()) return Interval::nan_only();
  return make(-kPi, kPi, y.nan || x.nan, kMathUlps);
}

Interval hypot(Interval x, Interval y) {  // Math.hypot: +inf when either is infinite, even beside NaN
  if (x.empty() || y.empty()) return {0, kInfF, true};
  double mx = most_magnitude(x), my = most_magnitude(y);
  Interval r =
      make(std::max(least_magnitude(x), least_magnitude(y)), std::sqrt(mx * mx + my * my), x.nan || y.nan, kMathUlps);
  r.lo = std::max(r.lo, 0.0f);  // computed in double and rounded once: never below zero
  return r;
}

Interval sinh(Interval a) {
  return a.empty() ? a : increasing(a, [](double x) { return std::sinh(x); }, a.nan);
}

Interval cosh(Interval a) {
  if (a.empty()) return a;
  Interval r = make(std::cosh(least_magnitude(a)), std::cosh(most_magnitude(a)), a.nan, kMathUlps);
  r.lo = std::max(r.lo, 1.0f);  // computed in double and rounded once: never below one
  return r;
}

Interval tanh(Interval a) {
  return a.empty() ? a : increasing(a, [](double x) { return std::tanh(x); }, a.nan);
}

Interval noise(Interval x, Interval y, Interval z) {  // clamped to [-1, 1]; NaN on NaN or infinity
  if (x.empty() || y.empty() || z.empty()) return Interval::nan_only();
  return {-1, 1, x.nan || y.nan || z.nan || has_inf(x) || has_inf(y) || has_inf(z)};
}

Interval eq(Interval a, Interval b) { return from_truth(equal(a, b)); }
Interval ne(Interval a, Interval b) { return from_truth(negate(equal(a, b))); }
Interval lt(Interval a, Interval b) { return from_truth(less(a, b, true)); }
Interval le(Interval a, Interval b) { return from_truth(less(a, b, false)); }
Interval gt(Interval a, Interval b) { return from_truth(less(b, a, true)); }
Interval ge(Interval a, Interval b) { return from_truth(less(b, a, false)); }
Interval not_(Interval a) { return from_truth(negate(truth_of(a))); }
Interval truth(Interval a) { return from_truth(truth_of(a)); }

Interval select(Interval c, Interval a, Interval b) {
  Truth t = truth_of(c);
  return t == Truth::Always ? a : t == Truth::Never ? b : hull(a, b);
}

}  // namespace iv
}  // namespace fscript::math
