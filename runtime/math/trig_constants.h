#pragma once
// The constants of the batch sine and cosine (and tan's reduction): the argument reduced in double
// by a two-part pi/2, then Cephes' minimax polynomials in float. One copy for every implementation
// that must agree with runtime/math's batch functions bit for bit: batch.cpp, batch_double.cpp,
// the SSE emitter (backends/sse/sse_compile_lanes.h) and the LLVM lowering (backends/llvm/llvm_lower.cpp).
// Each writes the polynomials in the same order:
//   sin(r) = ((kSin1 z + kSin2) z - kSin3) z r + r              z = r * r, |r| <= pi/4
//   cos(r) = ((kCos1 z - kCos2) z + kCos3) z z - 0.5 z + 1

namespace fscript::math::trig {

constexpr double kTwoOverPi = 0.63661977236758134308;
constexpr double kPio2Hi = 1.57079632673412561417e+00;  // first 33 bits of pi/2: j * kPio2Hi is exact
constexpr double kPio2Lo = 6.07710050650619224932e-11;  // pi/2 - kPio2Hi
constexpr double kRoundMagic = 6755399441055744.0;     // 1.5 * 2^52: adding it rounds to an integer
constexpr float kFastLimit = 8.0e5f;                    // |x| up to here: j stays below 2^20

constexpr float kSin1 = -1.9515295891e-4f;
constexpr float kSin2 = 8.3321608736e-3f;
constexpr float kSin3 = 1.6666654611e-1f;  // subtracted
constexpr float kCos1 = 2.443315711809948e-5f;
constexpr float kCos2 = 1.388731625493765e-3f;  // subtracted
constexpr float kCos3 = 4.166664568298827e-2f;

}  // namespace fscript::math::trig
