// Scalar definitions of every built-in. Transcendentals: double-precision libm, rounded once to
// float, which is within 1 ulp of the correctly rounded result (tested in tests/unit/math_test.cpp).
#include <cmath>
#include <limits>

#include "runtime/math/math.h"

namespace fscript::math {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
float d2f(double d) { return static_cast<float>(d); }
}  // namespace

float mod(float a, float b) { return std::fmod(a, b); }

float pow(float a, float b) {
  if (b != b) return kNaN;
  if (std::isinf(b) && std::fabs(a) == 1.0f) return kNaN;
  return d2f(std::pow(static_cast<double>(a), static_cast<double>(b)));
}
float exp(float a) { return d2f(std::exp(static_cast<double>(a))); }
float log(float a) { return d2f(std::log(static_cast<double>(a))); }
float log10(float a) { return d2f(std::log10(static_cast<double>(a))); }
float sin(float a) { return d2f(std::sin(static_cast<double>(a))); }
float cos(float a) { return d2f(std::cos(static_cast<double>(a))); }
float tan(float a) { return d2f(std::tan(static_cast<double>(a))); }
float asin(float a) { return d2f(std::asin(static_cast<double>(a))); }
float acos(float a) { return d2f(std::acos(static_cast<double>(a))); }
float atan(float a) { return d2f(std::atan(static_cast<double>(a))); }
float atan2(float y, float x) { return d2f(std::atan2(static_cast<double>(y), static_cast<double>(x))); }
// In double the squares are exact and the sum cannot overflow: one rounding, then sqrt, then float.
float hypot(float x, float y) {
  if (std::isinf(x) || std::isinf(y)) return INFINITY;
  double dx = x, dy = y;
  return d2f(std::sqrt(dx * dx + dy * dy));
}
float sinh(float a) { return d2f(std::sinh(static_cast<double>(a))); }
float cosh(float a) { return d2f(std::cosh(static_cast<double>(a))); }
float tanh(float a) { return d2f(std::tanh(static_cast<double>(a))); }

long array_index(float a, long length) {
  float r = math::round(a);
  if (!(r >= 0.0f) || r >= static_cast<float>(length)) return -1;
  return static_cast<long>(r);
}

}  // namespace fscript::math
