// The public batch functions: forward to the variant of the active ISA.
#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"

namespace fscript::math {

#define FS_BATCH_DISPATCH(name)                                   \
  void name(const float* a, float* out, size_t n) {               \
    switch (active_isa()) {                                       \
      case Isa::Base: return isa_base::name(a, out, n);           \
      case Isa::Avx2: return isa_avx2::name(a, out, n);           \
      case Isa::Avx512: return isa_avx512::name(a, out, n);       \
    }                                                             \
  }
FS_BATCH_DISPATCH(sin_batch)
FS_BATCH_DISPATCH(cos_batch)
FS_BATCH_DISPATCH(exp_batch)
FS_BATCH_DISPATCH(log_batch)
FS_BATCH_DISPATCH(tan_batch)
FS_BATCH_DISPATCH(asin_batch)
FS_BATCH_DISPATCH(acos_batch)
FS_BATCH_DISPATCH(atan_batch)
FS_BATCH_DISPATCH(sinh_batch)
FS_BATCH_DISPATCH(cosh_batch)
FS_BATCH_DISPATCH(tanh_batch)
FS_BATCH_DISPATCH(log10_batch)

#define FS_BATCH2_DISPATCH(name)                                          \
  void name(const float* a, const float* b, float* out, size_t n) {       \
    switch (active_isa()) {                                               \
      case Isa::Base: return isa_base::name(a, b, out, n);                \
      case Isa::Avx2: return isa_avx2::name(a, b, out, n);                \
      case Isa::Avx512: return isa_avx512::name(a, b, out, n);            \
    }                                                                     \
  }
FS_BATCH2_DISPATCH(pow_batch)
FS_BATCH2_DISPATCH(atan2_batch)

}  // namespace fscript::math
