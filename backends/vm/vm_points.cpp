// The direct tape loop, compiled once per ISA (FS_ISA): each step over the batch's lanes, the
// lane ops through the same math:: functions and the batch ops through the same batch twins as the
// VM's executor, so every bit agrees with it.
#include "backends/vm/vm_points.h"

#include "runtime/math/batch_isa.h"
#include "runtime/math/math.h"

namespace fscript::vm::FS_ISA {

namespace {
namespace M = fscript::math;
constexpr size_t K = kPointLanes;
using ir::Op;
}  // namespace

void run_tape_points(const ir::IntervalTape::Step* steps, size_t count, float* values, size_t lanes) {
  const size_t L = lanes & ~size_t{15};  // whole vectors (the caller rounds up)
  for (size_t k = 0; k < count; ++k) {
    const ir::IntervalTape::Step& s = steps[k];
    float* __restrict d = values + size_t(s.dst) * K;
    const float* __restrict a = values + size_t(s.a) * K;
    const float* __restrict b = values + size_t(s.b) * K;
    const float* __restrict c = values + size_t(s.c) * K;
    switch (s.op) {
#define FS_PT_Lane1(N, FN)                             \
  case Op::N:                                          \
    for (size_t i = 0; i < L; ++i) d[i] = M::FN(a[i]); \
    break;
#define FS_PT_Lane2(N, FN)                                   \
  case Op::N:                                                \
    for (size_t i = 0; i < L; ++i) d[i] = M::FN(a[i], b[i]); \
    break;
#define FS_PT_Lane3(N, FN)                                         \
  case Op::N:                                                      \
    for (size_t i = 0; i < L; ++i) d[i] = M::FN(a[i], b[i], c[i]); \
    break;
#define FS_PT_Batch1(N, FN) \
  case Op::N: M::FS_ISA::FN##_batch(a, d, L); break;
#define FS_PT_Batch2(N, FN) \
  case Op::N: M::FS_ISA::FN##_batch(a, b, d, L); break;
#define FS_PT_Batch3(N, FN) \
  case Op::N: M::FS_ISA::FN##_batch(a, b, c, d, L); break;
#define FS_PT_Trig1 FS_PT_Batch1
#define FS_MATH(N, FN, A, HOW) FS_PT_##HOW##A(N, FN)
#include "ir/math_ops.def"
      case Op::Const:
        for (size_t i = 0; i < L; ++i) d[i] = s.imm;
        break;
      case Op::Param:
        break;  // placed by eval_tape_points
      // Not in a straight-line tape (ir::interval_evaluable).
      case Op::Phi:
      case Op::GLoad:
      case Op::GStore:
      case Op::ANew:
      case Op::ALoad:
      case Op::AStore:
      case Op::ALen:
      case Op::Call:
      case Op::Tick:
      case Op::Jump:
      case Op::Branch:
      case Op::Ret: break;
    }
  }
}

}  // namespace fscript::vm::FS_ISA
