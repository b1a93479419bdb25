// Batch (SIMD) twins of the hot transcendentals, written as branch-free loops that the compiler
// vectorises (built with -O3). Argument reduction runs in double so the result stays within 2 ulp
// of the scalar definition on the whole fast range; lanes outside it (huge, inf, NaN) are redone
// with the scalar function afterwards.
#include <bit>
#include <cmath>
#include <cstdint>

#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"
#include "runtime/math/trig_constants.h"

#ifndef FS_ISA
#error "batch.cpp is compiled once per ISA with FS_ISA set (see CMakeLists.txt)"
#endif

namespace fscript::math::FS_ISA {
namespace {

using namespace trig;

// sin and cos on the reduced argument r in [-pi/4, pi/4] (trig_constants.h).
// sin keeps r's sign: r + (-0) * ... is +0 at r = -0, where sin(-0) is -0 (the node oracle).
inline float sin_poly(float r) {
  float z = r * r;
  return std::copysign(((kSin1 * z + kSin2) * z - kSin3) * z * r + r, r);
}
inline float cos_poly(float r) {
  float z = r * r;
  return ((kCos1 * z - kCos2) * z + kCos3) * z * z - 0.5f * z + 1.0f;
}

// Branch-free selection by bit masks: the vectoriser if-converts these where it gives up on ?:.
inline uint32_t mask_of(bool b) { return 0u - static_cast<uint32_t>(b); }
inline float pick(uint32_t m, float a, float b) {
  return std::bit_cast<float>((std::bit_cast<uint32_t>(a) & m) | (std::bit_cast<uint32_t>(b) & ~m));
}

// x reduced to r in [-pi/4, pi/4] and its quadrant q (0 outside the fast range: fix_up redoes those).
struct Reduced {
  float r;
  int q;
};
inline Reduced reduce(float x) {
  float xs = pick(mask_of(std::fabs(x) <= kFastLimit), x, 0.0f);
  double xd = static_cast<double>(xs);
  double jd = (xd * kTwoOverPi + kRoundMagic) - kRoundMagic;
  double r = (xd - jd * kPio2Hi) - jd * kPio2Lo;
  return {static_cast<float>(r), static_cast<int>(jd)};
}

// sin in quadrant q, from both polynomials on the reduced argument (cos x = sin(x + pi/2): q + 1).
inline float quadrant_value(int q, float sin_r, float cos_r) {
  float v = pick(mask_of(q & 1), cos_r, sin_r);
  return std::bit_cast<float>(std::bit_cast<uint32_t>(v) ^ (static_cast<uint32_t>(q & 2) << 30));
}

// quadrant_offset 0: sin, 1: cos.
inline float trig_lane(float x, int quadrant_offset) {
  Reduced d = reduce(x);
  return quadrant_value(d.q + quadrant_offset, sin_poly(d.r), cos_poly(d.r));
}

// Redoes lanes outside the fast range with the scalar definition. The test is a vectorised
// OR-reduction first, so the common case (every lane in range) costs one cheap pass.
template <float (*Scalar)(float), typename Pred>
void fix_up(const float* a, float* out, size_t n, Pred outside_fast_range) {
  uint32_t any = 0;
  for (size_t i = 0; i < n; ++i) any |= mask_of(outside_fast_range(a[i]));
  if (!any) return;
  for (size_t i = 0; i < n; ++i)
    if (outside_fast_range(a[i])) out[i] = Scalar(a[i]);
}

constexpr float kExpHi = 88.7228394f;    // above: +inf
constexpr float kExpLo = -103.972084f;   // below: 0
inline float pow2i(int k) { return std::bit_cast<float>((k + 127) << 23); }

inline float exp_lane(float x) {
  float xc = pick(mask_of((x <= kExpHi) & (x >= kExpLo)), x, 0.0f);
  float kf = (xc * 1.44269504088896341f + 12582912.0f) - 12582912.0f;
  float r = (xc - kf * 0.693359375f) - kf * -2.12194440e-4f;
  float p = ((((((1.9875691500e-4f * r + 1.3981999507e-3f) * r + 8.3334519073e-3f) * r + 4.1665795894e-2f) * r +
               1.6666665459e-1f) *
                  r +
              5.0000001201e-1f) *
                 r * r +
             r) +
      1.0f;
  int k = static_cast<int>(kf);
  int k1 = k / 2;
  return p * pow2i(k1) * pow2i(k - k1);  // two steps, so subnormal results round only once
}

inline float log_lane(float x) {
  uint32_t tiny = mask_of(x < 1.17549435e-38f);
  float xs = pick(tiny, x * 8388608.0f, x);
  int32_t bits = std::bit_cast<int32_t>(xs);
  int e = ((bits >> 23) & 0xff) - 126 - static_cast<int>(tiny & 23u);
  float m = std::bit_cast<float>((bits & 0x007fffff) | 0x3f000000);  // [0.5, 1)
  uint32_t low = mask_of(m < 0.707106781186547524f);
  e -= static_cast<int>(low & 1u);
  m = pick(low, (m + m) - 1.0f, m - 1.0f);
  float z = m * m;
  float y = ((((((((7.0376836292e-2f * m - 1.1514610310e-1f) * m + 1.1676998740e-1f) * m - 1.2420140846e-1f) * m +
                 1.4249322787e-1f) *
                    m -
                1.6668057665e-1f) *
                   m +
               2.0000714765e-1f) *
                  m -
              2.4999993993e-1f) *
                 m +
             3.3333331174e-1f) *
      m * z;
  float ef = static_cast<float>(e);
  y += -2.12194440e-4f * ef;
  y += -0.5f * z;
  return (m + y) + 0.693359375f * ef;
}

}  // namespace

void sin_batch(const float* a, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = trig_lane(a[i], 0);
  fix_up<fscript::math::sin>(a, out, n, [](float v) { return !(std::fabs(v) <= kFastLimit); });
}

void cos_batch(const float* a, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = trig_lane(a[i], 1);
  fix_up<fscript::math::cos>(a, out, n, [](float v) { return !(std::fabs(v) <= kFastLimit); });
}

// Both of one argument: one reduction for the two (the VM's sin and cos of the same value), the
// bits of sin_batch and cos_batch.
void sincos_batch(const float* a, float* sin_out, float* cos_out, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    Reduced d = reduce(a[i]);
    float sp = sin_poly(d.r), cp = cos_poly(d.r);
    sin_out[i] = quadrant_value(d.q, sp, cp), cos_out[i] = quadrant_value(d.q + 1, sp, cp);
  }
  fix_up<fscript::math::sin>(a, sin_out, n, [](float v) { return !(std::fabs(v) <= kFastLimit); });
  fix_up<fscript::math::cos>(a, cos_out, n, [](float v) { return !(std::fabs(v) <= kFastLimit); });
}

void exp_batch(const float* a, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = exp_lane(a[i]);
  fix_up<fscript::math::exp>(a, out, n, [](float v) { return !((v <= kExpHi) & (v >= kExpLo)); });
}

void log_batch(const float* a, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = log_lane(a[i]);
  // Non-positive, infinite and NaN inputs take the scalar path (NaN, -inf, inf).
  fix_up<fscript::math::log>(a, out, n, [](float v) { return !((v > 0.0f) & (v < INFINITY)); });
}

}  // namespace fscript::math::FS_ISA
