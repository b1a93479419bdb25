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

}  // namespace fscript::math
