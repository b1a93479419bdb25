#pragma once
// runtime/math: THE definition of every FScript built-in on float. The VM and constant folding
// call these; the JIT backends call the same symbols (or the batch twins below, tested against them).
// Transcendentals are computed in double and rounded once, so they are within 1 ulp.
#include <cstddef>

// The parameter list of a batch function of `arity` inputs (batch_functions.def), and its names.
#define FS_BATCH_PARAMS_1 const float *a, float *out, size_t n
#define FS_BATCH_PARAMS_2 const float *a, const float *b, float *out, size_t n
#define FS_BATCH_PARAMS_3 const float *a, const float *b, const float *c, float *out, size_t n
#define FS_BATCH_ARGS_1 a, out, n
#define FS_BATCH_ARGS_2 a, b, out, n
#define FS_BATCH_ARGS_3 a, b, c, out, n

namespace fscript::math {

// ---- exact operations (bit-identical on every backend, up to the sign of a zero result) ----
// Defined inline so the VM's lane loops vectorise them; constant folding uses the same code.
inline float add(float a, float b) { return a + b; }
inline float sub(float a, float b) { return a - b; }
inline float mul(float a, float b) { return a * b; }
inline float div(float a, float b) { return a / b; }
float mod(float a, float b);  // fmod: the sign of a (JavaScript %); exact
inline float neg(float a) { return -a; }
// NaN if either operand is NaN (JavaScript Math.min/max), else the smaller/larger. Written as
// two selects without short-circuit logic, so lane loops vectorise (cmpps + blend).
inline float min(float a, float b) {
  float m = b < a ? b : a;  // a when a is NaN
  return b != b ? b : m;
}
inline float max(float a, float b) {
  float m = b > a ? b : a;
  return b != b ? b : m;
}
inline float abs(float a) { return __builtin_fabsf(a); }
inline float sqrt(float a) { return __builtin_sqrtf(a); }
inline float floor(float a) { return __builtin_floorf(a); }
inline float ceil(float a) { return __builtin_ceilf(a); }
// Nearest integer, ties toward +infinity (Math.round); a - floor(a) is exact for every float.
// The result keeps a's sign, as in JavaScript: round(-0.4) and round(-0.5) are -0 (f + 1 is +0).
inline float round(float a) {
  float f = __builtin_floorf(a);
  return __builtin_copysignf((a - f >= 0.5f) ? f + 1.0f : f, a);
}
inline float sign(float a) { return a > 0 ? 1.0f : (a < 0 ? -1.0f : a); }  // NaN stays NaN
inline float clamp(float a, float lo, float hi) { return min(max(a, lo), hi); }
inline bool truthy(float a) { return (a == a) & (a != 0.0f); }  // != 0 and not NaN
inline float eq(float a, float b) { return a == b ? 1.0f : 0.0f; }
inline float ne(float a, float b) { return a != b ? 1.0f : 0.0f; }
inline float lt(float a, float b) { return a < b ? 1.0f : 0.0f; }
inline float le(float a, float b) { return a <= b ? 1.0f : 0.0f; }
inline float gt(float a, float b) { return a > b ? 1.0f : 0.0f; }
inline float ge(float a, float b) { return a >= b ? 1.0f : 0.0f; }
inline float not_(float a) { return truthy(a) ? 0.0f : 1.0f; }
inline float truth(float a) { return truthy(a) ? 1.0f : 0.0f; }
inline float select(float c, float a, float b) { return truthy(c) ? a : b; }

// ---- transcendental (within 4 ulp; here within 1) ----
float pow(float a, float b);    // JavaScript Math.pow: pow(x, NaN) = NaN, pow(NaN, 0) = 1, pow(+-1, +-inf) = NaN
float exp(float a);
float log(float a);
float log10(float a);
float sin(float a);
float cos(float a);
float tan(float a);
float asin(float a);
float acos(float a);
float atan(float a);
float atan2(float y, float x);
float hypot(float x, float y);  // Math.hypot of two: +inf if either is infinite (even with a NaN)
float sinh(float a);
float cosh(float a);
float tanh(float a);
float noise(float x, float y, float z);  // Ken Perlin's improved noise, in [-1, 1]

// Array index rule: round(a) as an integer, or -1 when out of [0, length) or NaN.
long array_index(float a, long length);

// ---- batch twins for the vectorised paths: out[i] = f(a[i]) for i < n ----
// Vectorised lane code, compiled per ISA (isa.h): 4 lanes SSE2, 8 AVX2, 16 AVX-512. sin, cos, exp
// and log evaluate float polynomials after a double-precision reduction (within 2 ulp of the
// scalar definition); the others compute in double and round once (within 1 ulp).
// noise_batch is the scalar noise per lane. Every one is listed in batch_functions.def.
#define FS_BATCH_FN(name, arity) void name##_batch(FS_BATCH_PARAMS_##arity);
#include "runtime/math/batch_functions.def"

}  // namespace fscript::math
