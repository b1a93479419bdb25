// CPU detection for the ISA variants.
#include "runtime/math/isa.h"

#include <cstdlib>
#include <cstring>

namespace fscript::math {

static Isa detect() {
#if !defined(__x86_64__)
  return Isa::Base;  // WebAssembly (the browser build): one variant, 128-bit SIMD
#else
  __builtin_cpu_init();
  Isa best = Isa::Base;
  if (__builtin_cpu_supports("x86-64-v3")) best = Isa::Avx2;
  if (__builtin_cpu_supports("x86-64-v4")) best = Isa::Avx512;
  if (const char* want = std::getenv("FSCRIPT_ISA")) {
    Isa w = std::strcmp(want, "base") == 0 ? Isa::Base : std::strcmp(want, "avx2") == 0 ? Isa::Avx2 : best;
    if (static_cast<int>(w) <= static_cast<int>(best)) best = w;
  }
  return best;
#endif
}

Isa active_isa() {
  static const Isa isa = detect();
  return isa;
}

const char* isa_name(Isa isa) {
  switch (isa) {
    case Isa::Base: return "base";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
  }
  return "base";
}

}  // namespace fscript::math
