#pragma once
// Instruction-set variants. Hot loops (batch math, the VM executor) are compiled once per ISA:
// isa_base (x86-64, SSE2, 4 lanes), isa_avx2 (x86-64-v3, 8 lanes), isa_avx512 (x86-64-v4, 16
// lanes), each in its own namespace; the best one the CPU runs is picked once, at first use.
// Contraction stays off everywhere, so every variant computes bit-identical results.
#include <string>

namespace fscript::math {

enum class Isa { Base, Avx2, Avx512 };

// The ISA in use: the best the CPU supports, or FSCRIPT_ISA=base|avx2|avx512 if set (and supported).
Isa active_isa();
const char* isa_name(Isa isa);

}  // namespace fscript::math

// Declares `decl` in each ISA namespace (inside an enclosing namespace).
#define FS_FOR_EACH_ISA_DECLARE(decl) \
  namespace isa_base {                \
  decl;                               \
  }                                   \
  namespace isa_avx2 {                \
  decl;                               \
  }                                   \
  namespace isa_avx512 {              \
  decl;                               \
  }
