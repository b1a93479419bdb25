// Pure-op evaluation: the runtime/math function of each op (ir/math_ops.def); the other ops are
// listed, with no default, so a new op must be placed here.
#include "ir/eval.h"

#include "runtime/math/math.h"

namespace fscript::ir {

namespace {
float apply(float (*f)(float), const float* a) { return f(a[0]); }
float apply(float (*f)(float, float), const float* a) { return f(a[0], a[1]); }
float apply(float (*f)(float, float, float), const float* a) { return f(a[0], a[1], a[2]); }
}  // namespace

bool eval_pure(Op op, const float* a, float& out) {
  namespace m = fscript::math;
  switch (op) {
#define FS_MATH(N, FN, A, HOW) \
  case Op::N: out = apply(&m::FN, a); return true;
#include "ir/math_ops.def"
    case Op::Const:
    case Op::Param:
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
    case Op::Ret: return false;
  }
  return false;
}

}  // namespace fscript::ir
