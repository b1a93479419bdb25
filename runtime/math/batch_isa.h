#pragma once
// The per-ISA batch functions (see isa.h), for callers that are themselves compiled per ISA.
#include <cstddef>

#include "runtime/math/isa.h"

namespace fscript::math {

#define FS_BATCH_DECL(name) void name(const float* a, float* out, size_t n)
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(sin_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(cos_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(exp_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(log_batch))
#undef FS_BATCH_DECL

}  // namespace fscript::math
