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
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(tan_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(asin_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(acos_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(atan_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(sinh_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(cosh_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(tanh_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH_DECL(log10_batch))
#undef FS_BATCH_DECL
#define FS_BATCH2_DECL(name) void name(const float* a, const float* b, float* out, size_t n)
FS_FOR_EACH_ISA_DECLARE(FS_BATCH2_DECL(pow_batch))
FS_FOR_EACH_ISA_DECLARE(FS_BATCH2_DECL(atan2_batch))
#undef FS_BATCH2_DECL

}  // namespace fscript::math
