#pragma once
// The per-ISA batch functions (see isa.h), for callers that are themselves compiled per ISA.
#include <cstddef>

#include "runtime/math/isa.h"
#include "runtime/math/math.h"

namespace fscript::math {

#define FS_BATCH_FN(name, arity) FS_FOR_EACH_ISA_DECLARE(void name##_batch(FS_BATCH_PARAMS_##arity))
#include "runtime/math/batch_functions.def"

// sin_batch and cos_batch of one argument at once, with their bits (one range reduction for both).
FS_FOR_EACH_ISA_DECLARE(void sincos_batch(const float* a, float* sin_out, float* cos_out, size_t n))

}  // namespace fscript::math
