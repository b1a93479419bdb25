// runtime/math: every built-in against an independent higher-precision reference (long double,
// the x87 80-bit libm) over millions of inputs and the special values; batch twins against both.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "runtime/math/interval.h"
#include "runtime/math/isa.h"
#include "runtime/math/math.h"

using namespace fscript;

namespace {

int64_t ordered(float f) {
  int32_t i;
  std::memcpy(&i, &f, 4);
  return i < 0 ? static_cast<int64_t>(INT32_MIN) - i : i;
}

// Distance in units in the last place; both NaN is 0, one NaN is "infinite".
uint64_t ulps(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : UINT64_MAX;
  if (a == b) return 0;
  int64_t d = ordered(a) - ordered(b);
  return static_cast<uint64_t>(d < 0 ? -d : d);
}

float from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// Inputs: random bit patterns (every magnitude), a dense typical range, and the special values.
std::vector<float> inputs(size_t n, float lo, float hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<float> v;
  std::uniform_real_distribution<float> typical(lo, hi);
  for (size_t i = 0; i < n / 2; ++i) v.push_back(typical(rng));
  for (size_t i = 0; i < n / 2; ++i) {
    float f = from_bits(rng());
    if (std::isfinite(f)) v.push_back(f);
  }
  const float inf = std::numeric_limits<float>::infinity();
  for (float s : {0.0f, -0.0f, inf, -inf, std::numeric_limits<float>::quiet_NaN(), 1e38f, -1e38f, 3.4e38f, 1e-38f,
                  -1e-38f, 1e-45f, 1.0f, -1.0f, 0.5f, 88.7f, 89.0f, -103.0f, -104.0f})
    v.push_back(s);
  for (int k = -2000; k <= 2000; ++k) v.push_back(static_cast<float>(k * M_PI / 2));
  for (int k = 1; k < 60; ++k) v.push_back(static_cast<float>(k * 1e5 * M_PI / 2));
  return v;
}

// Worst ulp error of f against ref over the inputs (references that overflow float are fine).
template <class F, class R>
uint64_t worst(const std::vector<float>& in, F f, R ref, float* where) {
  uint64_t w = 0;
  for (float x : in) {
    float want = static_cast<float>(ref(static_cast<long double>(x)));
    uint64_t d = ulps(f(x), want);
    if (d > w) {
      w = d;
      *where = x;
    }
  }
  return w;
}

constexpr size_t kN = 2'000'000;

}  // namespace

#define UNARY_CASE(NAME, REF, LO, HI)                                                                         \
  TEST_CASE("math: " #NAME " within 1 ulp of the long double reference") {                                    \
    auto in = inputs(kN, LO, HI, __LINE__);                                                                   \
    float at = 0;                                                                                             \
    uint64_t w = worst(in, [](float x) { return math::NAME(x); }, [](long double x) { return REF(x); }, &at); \
    INFO("worst " << w << " ulp at " << at);                                                                  \
    CHECK(w <= 1);                                                                                            \
  }

UNARY_CASE(sin, sinl, -20.0f, 20.0f)
UNARY_CASE(cos, cosl, -20.0f, 20.0f)
UNARY_CASE(tan, tanl, -3.0f, 3.0f)
UNARY_CASE(asin, asinl, -1.0f, 1.0f)
UNARY_CASE(acos, acosl, -1.0f, 1.0f)
UNARY_CASE(atan, atanl, -10.0f, 10.0f)
UNARY_CASE(exp, expl, -100.0f, 90.0f)
UNARY_CASE(log, logl, 0.0f, 100.0f)
UNARY_CASE(log10, log10l, 0.0f, 100.0f)
UNARY_CASE(sinh, sinhl, -10.0f, 10.0f)
UNARY_CASE(cosh, coshl, -10.0f, 10.0f)
UNARY_CASE(tanh, tanhl, -5.0f, 5.0f)
UNARY_CASE(sqrt, sqrtl, 0.0f, 100.0f)

TEST_CASE("math: pow and atan2 within 1 ulp; JavaScript special cases") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> base(0.0f, 10.0f), expo(-10.0f, 10.0f), any(-100.0f, 100.0f);
  uint64_t wp = 0, wa = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    float a = base(rng), b = expo(rng);
    wp = std::max(wp, ulps(math::pow(a, b), static_cast<float>(powl(a, b))));
    float y = any(rng), x = any(rng);
    wa = std::max(wa, ulps(math::atan2(y, x), static_cast<float>(atan2l(y, x))));
  }
  INFO("pow " << wp << " ulp, atan2 " << wa << " ulp");
  CHECK(wp <= 1);
  CHECK(wa <= 1);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  CHECK(std::isnan(math::pow(1, nan)));
  CHECK(math::pow(nan, 0) == 1);
  CHECK(std::isnan(math::pow(1, inf)));
  CHECK(std::isnan(math::pow(-1, -inf)));
  CHECK(math::pow(-2, 3) == -8);
  CHECK(std::isnan(math::pow(-2, 0.5f)));
}

TEST_CASE("math: exact operations and their NaN rules") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK(std::isnan(math::min(nan, 1)));
  CHECK(std::isnan(math::min(1, nan)));
  CHECK(std::isnan(math::max(nan, 1)));
  CHECK(std::isnan(math::max(1, nan)));
  CHECK(math::min(-1, 2) == -1);
  CHECK(math::max(-1, 2) == 2);
  CHECK(math::round(2.5f) == 3);
  CHECK(math::round(-2.5f) == -2);
  CHECK(math::round(0.49999997f) == 0);
  CHECK(math::round(8388609.0f) == 8388609.0f);
  // JavaScript's zero signs: -0 for [-0.5, -0], +0 for [+0, 0.5).
  for (float z : {-0.5f, -0.4f, -1e-30f, -0.0f}) CHECK(std::signbit(math::round(z)));
  for (float z : {0.0f, 1e-30f, 0.49999997f}) CHECK(!std::signbit(math::round(z)));
  CHECK(math::round(-0.50000006f) == -1);
  math::Interval r = math::iv::round(math::Interval{-0.4f, 0.3f, 0});  // zero signs are not tracked in intervals
  CHECK((r.lo == 0 && r.hi == 0 && !r.nan));
  CHECK(math::mod(-7, 3) == -1);
  CHECK(std::isnan(math::sign(nan)));
  CHECK(math::sign(-0.0f) == 0);
  CHECK(math::clamp(5, 0, 1) == 1);
  CHECK(!math::truthy(nan));
  CHECK(!math::truthy(-0.0f));
  CHECK(math::array_index(1.5f, 3) == 2);
  CHECK(math::array_index(2.5f, 3) == -1);
  CHECK(math::array_index(nan, 3) == -1);
  CHECK(math::array_index(-0.5f, 3) == 0);
}

TEST_CASE("math: batch twins within 2 ulp of the scalar definitions and 4 of the reference") {
  struct Fn {
    const char* name;
    void (*batch)(const float*, float*, size_t);
    float (*scalar)(float);
    long double (*ref)(long double);
    float lo, hi;
  } fns[] = {{"sin", math::sin_batch, math::sin, sinl, -100, 100},
             {"cos", math::cos_batch, math::cos, cosl, -100, 100},
             {"tan", math::tan_batch, math::tan, tanl, -100, 100},
             {"exp", math::exp_batch, math::exp, expl, -100, 100},
             {"log", math::log_batch, math::log, logl, 0, 100},
             {"log10", math::log10_batch, math::log10, log10l, 0, 100},
             {"asin", math::asin_batch, math::asin, asinl, -1, 1},
             {"acos", math::acos_batch, math::acos, acosl, -1, 1},
             {"atan", math::atan_batch, math::atan, atanl, -100, 100},
             {"sinh", math::sinh_batch, math::sinh, sinhl, -10, 10},
             {"cosh", math::cosh_batch, math::cosh, coshl, -10, 10},
             {"tanh", math::tanh_batch, math::tanh, tanhl, -5, 5}};
  for (const auto& f : fns) {
    auto in = inputs(kN / 2, f.lo, f.hi, 99);
    std::vector<float> out(in.size());
    // Odd lengths and offsets exercise the vector loops' tails.
    for (size_t start = 0; start < in.size(); start += 1021)
      f.batch(in.data() + start, out.data() + start, std::min<size_t>(1021, in.size() - start));
    uint64_t w = 0, wr = 0;
    float at = 0, atr = 0;
    for (size_t i = 0; i < in.size(); ++i) {
      uint64_t d = ulps(out[i], f.scalar(in[i]));
      uint64_t dr = ulps(out[i], static_cast<float>(f.ref(in[i])));
      if (d > w) w = d, at = in[i];
      if (dr > wr) wr = dr, atr = in[i];
    }
    INFO(f.name << " (" << math::isa_name(math::active_isa()) << "): worst " << w << " ulp from scalar at " << at
                << ", " << wr << " from the reference at " << atr);
    CHECK(w <= 2);
    CHECK(wr <= 4);
  }
}

TEST_CASE("math: binary batch twins (pow, atan2)") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> base(-4.0f, 10.0f), expo(-12.0f, 12.0f);
  const size_t n = 1'000'000;
  std::vector<float> a(n), b(n), out(n);
  for (size_t i = 0; i < n; ++i) {
    a[i] = base(rng);
    b[i] = (i % 7 == 0) ? std::round(expo(rng)) : expo(rng);
  }
  const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, INFINITY, -INFINITY, NAN, 2.0f, 0.5f};
  for (float x : specials)
    for (float y : specials) {
      a.push_back(x);
      b.push_back(y);
    }
  out.resize(a.size());
  math::pow_batch(a.data(), b.data(), out.data(), a.size());
  uint64_t wp = 0;
  for (size_t i = 0; i < a.size(); ++i) wp = std::max(wp, ulps(out[i], math::pow(a[i], b[i])));
  CHECK(wp <= 2);
  math::atan2_batch(a.data(), b.data(), out.data(), a.size());
  uint64_t wa = 0;
  for (size_t i = 0; i < a.size(); ++i) wa = std::max(wa, ulps(out[i], math::atan2(a[i], b[i])));
  CHECK(wa <= 2);
  math::hypot_batch(a.data(), b.data(), out.data(), a.size());
  uint64_t wh = 0;
  for (size_t i = 0; i < a.size(); ++i) wh = std::max(wh, ulps(out[i], math::hypot(a[i], b[i])));
  CHECK(wh == 0);  // the same arithmetic lane by lane
}

TEST_CASE("math: hypot within 1 ulp, without overflow or underflow; Math.hypot's special cases") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> any(-100.0f, 100.0f);
  std::uniform_int_distribution<int> scale(-140, 120);
  uint64_t w = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    float x = std::ldexp(any(rng), scale(rng)), y = std::ldexp(any(rng), scale(rng));
    w = std::max(w, ulps(math::hypot(x, y), static_cast<float>(hypotl(x, y))));
  }
  INFO("worst " << w << " ulp");
  CHECK(w <= 1);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  CHECK(math::hypot(3, 4) == 5);
  CHECK(math::hypot(-3, 4) == 5);
  CHECK(math::hypot(3e30f, 4e30f) == 5e30f);  // no overflow in the squares
  CHECK(math::hypot(3e-30f, 4e-30f) == 5e-30f);  // no underflow either
  CHECK(math::hypot(inf, nan) == inf);
  CHECK(math::hypot(nan, -inf) == inf);
  CHECK(std::isnan(math::hypot(nan, 1)));
  CHECK(math::hypot(0, -0.0f) == 0);
}

TEST_CASE("math: noise is in [-1, 1], zero on the lattice, continuous, NaN for non-finite input") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> d(-300.0f, 300.0f);
  int out_of_range = 0, jumps = 0;
  for (int i = 0; i < 200000; ++i) {
    float x = d(rng), y = d(rng), z = d(rng);
    float v = math::noise(x, y, z);
    out_of_range += !(v >= -1.0f && v <= 1.0f);
    jumps += !(std::fabs(math::noise(x + 1e-4f, y, z) - v) < 0.01f);
  }
  CHECK(out_of_range == 0);
  CHECK(jumps == 0);
  CHECK(math::noise(3, -7, 12) == 0);
  CHECK(std::isnan(math::noise(std::numeric_limits<float>::infinity(), 0, 0)));
  CHECK(std::isfinite(math::noise(3e38f, -3e38f, 1e30f)));
}
