// Pure-op evaluation: one switch over the op table, no default, so a new op must be handled here.
#include "ir/eval.h"

#include "runtime/math/math.h"

namespace fscript::ir {

bool eval_pure(Op op, const float* a, float& out) {
  namespace m = fscript::math;
  switch (op) {
    case Op::Add: out = m::add(a[0], a[1]); return true;
    case Op::Sub: out = m::sub(a[0], a[1]); return true;
    case Op::Mul: out = m::mul(a[0], a[1]); return true;
    case Op::Div: out = m::div(a[0], a[1]); return true;
    case Op::Mod: out = m::mod(a[0], a[1]); return true;
    case Op::Neg: out = m::neg(a[0]); return true;
    case Op::Min: out = m::min(a[0], a[1]); return true;
    case Op::Max: out = m::max(a[0], a[1]); return true;
    case Op::Abs: out = m::abs(a[0]); return true;
    case Op::Sqrt: out = m::sqrt(a[0]); return true;
    case Op::Floor: out = m::floor(a[0]); return true;
    case Op::Ceil: out = m::ceil(a[0]); return true;
    case Op::Round: out = m::round(a[0]); return true;
    case Op::Sign: out = m::sign(a[0]); return true;
    case Op::Clamp: out = m::clamp(a[0], a[1], a[2]); return true;
    case Op::Pow: out = m::pow(a[0], a[1]); return true;
    case Op::Exp: out = m::exp(a[0]); return true;
    case Op::Log: out = m::log(a[0]); return true;
    case Op::Log10: out = m::log10(a[0]); return true;
    case Op::Sin: out = m::sin(a[0]); return true;
    case Op::Cos: out = m::cos(a[0]); return true;
    case Op::Tan: out = m::tan(a[0]); return true;
    case Op::Asin: out = m::asin(a[0]); return true;
    case Op::Acos: out = m::acos(a[0]); return true;
    case Op::Atan: out = m::atan(a[0]); return true;
    case Op::Atan2: out = m::atan2(a[0], a[1]); return true;
    case Op::Sinh: out = m::sinh(a[0]); return true;
    case Op::Cosh: out = m::cosh(a[0]); return true;
    case Op::Tanh: out = m::tanh(a[0]); return true;
    case Op::Noise: out = m::noise(a[0], a[1], a[2]); return true;
    case Op::Eq: out = m::eq(a[0], a[1]); return true;
    case Op::Ne: out = m::ne(a[0], a[1]); return true;
    case Op::Lt: out = m::lt(a[0], a[1]); return true;
    case Op::Le: out = m::le(a[0], a[1]); return true;
    case Op::Gt: out = m::gt(a[0], a[1]); return true;
    case Op::Ge: out = m::ge(a[0], a[1]); return true;
    case Op::Not: out = m::not_(a[0]); return true;
    case Op::Truth: out = m::truth(a[0]); return true;
    case Op::Select: out = m::select(a[0], a[1], a[2]); return true;
    case Op::Const: case Op::Param: case Op::Phi: case Op::GLoad: case Op::GStore: case Op::ANew:
    case Op::ALoad: case Op::AStore: case Op::ALen: case Op::Call: case Op::Tick: case Op::Jump:
    case Op::Branch: case Op::Ret:
      return false;
  }
  return false;
}

}  // namespace fscript::ir
