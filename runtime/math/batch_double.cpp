// Batch twins computed in double precision and rounded once (within 1 ulp of the true result,
// by construction): tan, asin, acos, atan, atan2, sinh, cosh, tanh, log10, pow. Branch-free
// lane code that the compiler vectorises; lanes outside the fast domain (non-finite, |x| > 1
// for asin/acos, x <= 0 for pow, ...) are redone with the scalar definition. Compiled per ISA.
#include <bit>
#include <cmath>
#include <cstdint>

#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"
#include "runtime/math/trig_constants.h"

#ifndef FS_ISA
#error "batch_double.cpp is compiled once per ISA with FS_ISA set (see CMakeLists.txt)"
#endif

namespace fscript::math::FS_ISA {
namespace {

constexpr double kLn2Hi = 6.93147180369123816490e-01;  // high bits of ln 2
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kLog2e = 1.44269504088896338700e+00;
constexpr double kRound = trig::kRoundMagic;  // 1.5 * 2^52
constexpr double kPi = 3.14159265358979311600e+00;
constexpr double kPio2 = 1.57079632679489655800e+00;
constexpr double kPio4 = 7.85398163397448278999e-01;

inline uint64_t dmask(bool b) { return 0ull - static_cast<uint64_t>(b); }
inline double dpick(uint64_t m, double a, double b) {
  return std::bit_cast<double>((std::bit_cast<uint64_t>(a) & m) | (std::bit_cast<uint64_t>(b) & ~m));
}

// e^x for |x| <= 700: 2^k * e^r, |r| <= ln2/2, Taylor to r^10 (relative error < 1e-13).
inline double exp_d(double x) {
  double k = (x * kLog2e + kRound) - kRound;
  double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double p = 1.0 / 3628800;
  for (double c : {1.0 / 362880, 1.0 / 40320, 1.0 / 5040, 1.0 / 720, 1.0 / 120, 1.0 / 24, 1.0 / 6, 0.5, 1.0, 1.0})
    p = p * r + c;
  int64_t ki = static_cast<int64_t>(k);
  return p * std::bit_cast<double>((ki + 1023) << 52);
}

// ln x for a positive normal double: x = m 2^e with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(f).
inline double log_d(double x) {
  int64_t bits = std::bit_cast<int64_t>(x);
  int64_t e = ((bits >> 52) & 0x7ff) - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL);  // [1, 2)
  uint64_t big = dmask(m > 1.41421356237309504880);
  m = dpick(big, m * 0.5, m);
  e += static_cast<int64_t>(big & 1);
  double f = (m - 1.0) / (m + 1.0);
  double s = f * f;
  double p = 2.0 / 17;
  for (double c : {2.0 / 15, 2.0 / 13, 2.0 / 11, 2.0 / 9, 2.0 / 7, 2.0 / 5, 2.0 / 3, 2.0}) p = p * s + c;
  double ed = static_cast<double>(e);
  return f * p + ed * kLn2Hi + ed * kLn2Lo;
}

// atan for any double (inf included): fold to [0, 1], then to |t| <= tan(pi/8) around pi/4.
inline double atan_d(double x) {
  double a = std::fabs(x);
  uint64_t inv = dmask(a > 1.0);
  double b = dpick(inv, 1.0 / a, a);
  uint64_t mid = dmask(b > 0.41421356237309504880);
  double t = dpick(mid, (b - 1.0) / (b + 1.0), b);
  double s = t * t;
  double p = -1.0 / 31;
  for (double c : {1.0 / 29, -1.0 / 27, 1.0 / 25, -1.0 / 23, 1.0 / 21, -1.0 / 19, 1.0 / 17, -1.0 / 15, 1.0 / 13,
                   -1.0 / 11, 1.0 / 9, -1.0 / 7, 1.0 / 5, -1.0 / 3, 1.0})
    p = p * s + c;
  double r = t * p + dpick(mid, kPio4, 0.0);
  r = dpick(inv, kPio2 - r, r);
  return std::copysign(r, x);
}

// sin and cos of the reduced argument |r| <= pi/4 (Taylor to r^15 / r^16).
inline double sin_r(double r) {
  double s = r * r, p = -1.0 / 1307674368000.0;
  for (double c : {1.0 / 6227020800.0, -1.0 / 39916800.0, 1.0 / 362880.0, -1.0 / 5040.0, 1.0 / 120.0, -1.0 / 6.0, 1.0})
    p = p * s + c;
  return r * p;
}
inline double cos_r(double r) {
  double s = r * r, p = 1.0 / 20922789888000.0;
  for (double c :
       {-1.0 / 87178291200.0, 1.0 / 479001600.0, -1.0 / 3628800.0, 1.0 / 40320.0, -1.0 / 720.0, 1.0 / 24.0, -0.5, 1.0})
    p = p * s + c;
  return p;
}

inline float f(double d) { return static_cast<float>(d); }

inline float tan_lane(float x) {
  double xd = std::fabs(x) <= trig::kFastLimit ? static_cast<double>(x) : 0.0;
  double j = (xd * trig::kTwoOverPi + kRound) - kRound;
  double r = (xd - j * trig::kPio2Hi) - j * trig::kPio2Lo;
  double s = sin_r(r), c = cos_r(r);
  uint64_t odd = dmask(static_cast<int64_t>(j) & 1);
  return f(dpick(odd, -c / s, s / c));
}
inline float atan_lane(float x) { return f(atan_d(x)); }
inline float asin_lane(float x) {
  double xd = x;
  return f(atan_d(xd / std::sqrt((1.0 - xd) * (1.0 + xd))));
}
inline float acos_lane(float x) {
  double xd = x;
  double h = std::sqrt((1.0 - xd) / (1.0 + xd));  // acos x = 2 atan(sqrt((1-x)/(1+x)))
  return f(2.0 * atan_d(h));
}
inline float sinh_lane(float x) {
  double a = std::fabs(static_cast<double>(x));
  double s = a * a, p = 1.0 / 1307674368000.0;
  for (double c : {1.0 / 6227020800.0, 1.0 / 39916800.0, 1.0 / 362880.0, 1.0 / 5040.0, 1.0 / 120.0, 1.0 / 6.0, 1.0})
    p = p * s + c;
  double e = exp_d(std::fmin(a, 700.0));
  double big = 0.5 * (e - 1.0 / e);
  return f(std::copysign(dpick(dmask(a < 1.0), a * p, big), static_cast<double>(x)));
}
inline float cosh_lane(float x) {
  double e = exp_d(std::fmin(std::fabs(static_cast<double>(x)), 700.0));
  return f(0.5 * (e + 1.0 / e));
}
inline float tanh_lane(float x) {
  double a = std::fmin(std::fabs(static_cast<double>(x)), 20.0);
  double e2 = exp_d(2.0 * a);
  double big = (e2 - 1.0) / (e2 + 1.0);
  double s = a * a;
  double small = a * (1.0 - s * (1.0 / 3 - s * (2.0 / 15 - s * 17.0 / 315)));
  return f(std::copysign(dpick(dmask(a < 1e-3), small, big), static_cast<double>(x)));
}
inline float log10_lane(float x) {
  double xd = x > 0.0f ? static_cast<double>(x) : 1.0;
  return f(log_d(xd) * 0.43429448190325182765);
}
inline float pow_lane(float x, float y) {
  double xd = x > 0.0f ? static_cast<double>(x) : 1.0;
  double e = y * log_d(xd);
  return f(exp_d(std::fmax(std::fmin(e, 700.0), -700.0)));
}
inline float atan2_lane(float y, float x) {
  double xd = x, yd = y;
  double q = yd / (xd != 0.0 ? xd : 1.0);
  double r = atan_d(q);
  double adj = dpick(dmask(x < 0.0f), dpick(dmask(y < 0.0f), -kPi, kPi), 0.0);
  return f(r + adj);
}

template <float (*Lane)(float), float (*Scalar)(float), typename Fast>
void unary(const float* a, float* out, size_t n, Fast fast) {
  uint32_t slow = 0;
  for (size_t i = 0; i < n; ++i) {
    out[i] = Lane(a[i]);
    slow |= fast(a[i]) ? 0u : 1u;
  }
  if (slow)
    for (size_t i = 0; i < n; ++i)
      if (!fast(a[i])) out[i] = Scalar(a[i]);
}

template <float (*Lane)(float, float), float (*Scalar)(float, float), typename Fast>
void binary(const float* a, const float* b, float* out, size_t n, Fast fast) {
  uint32_t slow = 0;
  for (size_t i = 0; i < n; ++i) {
    out[i] = Lane(a[i], b[i]);
    slow |= fast(a[i], b[i]) ? 0u : 1u;
  }
  if (slow)
    for (size_t i = 0; i < n; ++i)
      if (!fast(a[i], b[i])) out[i] = Scalar(a[i], b[i]);
}

inline bool finite(float v) { return std::fabs(v) <= 3.40282347e+38f; }

}  // namespace

void tan_batch(const float* a, float* o, size_t n) {
  unary<tan_lane, math::tan>(a, o, n, [](float v) { return std::fabs(v) <= trig::kFastLimit; });
}
void asin_batch(const float* a, float* o, size_t n) {
  unary<asin_lane, math::asin>(a, o, n, [](float v) { return std::fabs(v) < 1.0f; });
}
void acos_batch(const float* a, float* o, size_t n) {
  unary<acos_lane, math::acos>(a, o, n, [](float v) { return std::fabs(v) < 1.0f; });
}
void atan_batch(const float* a, float* o, size_t n) {
  unary<atan_lane, math::atan>(a, o, n, [](float v) { return v == v; });
}
void sinh_batch(const float* a, float* o, size_t n) { unary<sinh_lane, math::sinh>(a, o, n, finite); }
void cosh_batch(const float* a, float* o, size_t n) { unary<cosh_lane, math::cosh>(a, o, n, finite); }
void tanh_batch(const float* a, float* o, size_t n) { unary<tanh_lane, math::tanh>(a, o, n, finite); }
void log10_batch(const float* a, float* o, size_t n) {
  unary<log10_lane, math::log10>(a, o, n, [](float v) { return (v > 0.0f) & finite(v); });
}
void pow_batch(const float* a, const float* b, float* o, size_t n) {
  binary<pow_lane, math::pow>(a, b, o, n, [](float x, float y) { return (x > 0.0f) & finite(x) & finite(y); });
}
void atan2_batch(const float* y, const float* x, float* o, size_t n) {
  binary<atan2_lane, math::atan2>(
      y, x, o, n, [](float yy, float xx) { return finite(xx) & finite(yy) & (xx != 0.0f) & (yy != 0.0f); });
}

// The scalar definition's arithmetic lane by lane (so the bits agree); infinities take the scalar.
inline float hypot_lane(float x, float y) {
  double dx = x, dy = y;
  return f(std::sqrt(dx * dx + dy * dy));
}
void hypot_batch(const float* a, const float* b, float* o, size_t n) {
  binary<hypot_lane, math::hypot>(a, b, o, n, [](float x, float y) { return !std::isinf(x) & !std::isinf(y); });
}

void noise_batch(const float* x, const float* y, const float* z, float* o, size_t n) {
  for (size_t i = 0; i < n; ++i) o[i] = math::noise(x[i], y[i], z[i]);
}

}  // namespace fscript::math::FS_ISA
