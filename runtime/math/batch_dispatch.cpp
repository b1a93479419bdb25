// The public batch functions: forward to the variant of the active ISA.
#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"

namespace fscript::math {

#define FS_BATCH_FN(name, arity)                                                \
  void name##_batch(FS_BATCH_PARAMS_##arity) {                                  \
    switch (active_isa()) {                                                     \
      case Isa::Base: return isa_base::name##_batch(FS_BATCH_ARGS_##arity);     \
      case Isa::Avx2: return isa_avx2::name##_batch(FS_BATCH_ARGS_##arity);     \
      case Isa::Avx512: return isa_avx512::name##_batch(FS_BATCH_ARGS_##arity); \
    }                                                                           \
  }
#include "runtime/math/batch_functions.def"

}  // namespace fscript::math
