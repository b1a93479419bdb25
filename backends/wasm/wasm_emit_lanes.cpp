// The wasm emitter's ops: each IR instruction as SIMD instructions with runtime/math's bits (the
// exact rules, or the speculating forms straight code guesses with), sin and cos inline, the
// batch functions and array helpers through scratch.
#include <climits>

#include "backends/jit_support.h"
#include "backends/wasm/wasm_emitter.h"
#include "runtime/math/math.h"
#include "runtime/math/trig_constants.h"

namespace fscript::wasm::detail {

// One instruction: every op is named (no default), so a new op fails the build until it is here.
bool Emitter::inst(const Inst& in, const ir::Block& b, std::string& error) {
  Code& c = c_;
  switch (in.op) {
    case Op::Const:
    case Op::Phi: return true;  // constants are made where used; phis are written on edges
    case Op::Param:
      if (callee_) {
        c.local_get(static_cast<uint32_t>(in.aux));
        break;
      }
      c.local_get(kFirstPointer + static_cast<uint32_t>(in.aux)), c.local_get(kAt), c.op(Opc::I32Add);
      c.v128_load_any(16 * u_);
      break;
    case Op::Add: simd2(Simd::F32x4Add, in); break;
    case Op::Sub: simd2(Simd::F32x4Sub, in); break;
    case Op::Mul: simd2(Simd::F32x4Mul, in); break;
    case Op::Div: simd2(Simd::F32x4Div, in); break;
    // (the sign bit by a mask: the engine would build the mask at every use of abs or neg)
    case Op::Neg: push(in.args[0]), i32(INT32_MIN), c.simd(Simd::V128Xor); break;
    case Op::Abs: push(in.args[0]), i32(INT32_MAX), c.simd(Simd::V128And); break;
    case Op::Sqrt: push(in.args[0]), c.simd(Simd::F32x4Sqrt); break;
    case Op::Floor: push(in.args[0]), c.simd(Simd::F32x4Floor); break;
    case Op::Ceil: push(in.args[0]), c.simd(Simd::F32x4Ceil); break;
    case Op::Min:
    case Op::Max: min_max(in.op == Op::Min, in.args[0], in.args[1]); break;
    case Op::Clamp:  // min(max(a, lo), hi)
      min_max(false, in.args[0], in.args[1]);
      c.local_set(temp_);
      min_max_with_temp(in.args[2]);
      break;
    case Op::Round: round(in.args[0]); break;
    case Op::Sign: sign(in.args[0]); break;
    case Op::Eq: simd2(Simd::F32x4Eq, in), one_where_mask(); break;
    case Op::Ne: simd2(Simd::F32x4Ne, in), one_where_mask(); break;
    case Op::Lt: simd2(Simd::F32x4Lt, in), one_where_mask(); break;
    case Op::Le: simd2(Simd::F32x4Le, in), one_where_mask(); break;
    case Op::Gt: simd2(Simd::F32x4Gt, in), one_where_mask(); break;
    case Op::Ge: simd2(Simd::F32x4Ge, in), one_where_mask(); break;
    case Op::Not: truthy(in.args[0]), c.simd(Simd::V128Not), one_where_mask(); break;
    case Op::Truth: truthy(in.args[0]), one_where_mask(); break;
    case Op::Select: push(in.args[1]), push(in.args[2]), truthy(in.args[0]), c.simd(Simd::V128Bitselect); break;
    case Op::Mod:
#define FS_MATH(N, FN, A, HOW) FS_WASM_MATH_##HOW(N)
#define FS_WASM_MATH_Lane(N)
#define FS_WASM_MATH_Batch(N) case Op::N:
#define FS_WASM_MATH_Trig(N)
#include "ir/math_ops.def"
#undef FS_WASM_MATH_Lane
#undef FS_WASM_MATH_Batch
#undef FS_WASM_MATH_Trig
      batch(in, batch_of(in.op));
      break;
    case Op::Sin:
    case Op::Cos: return true;  // made by block() for every copy
    case Op::GLoad:
      if (program_.globals_in_memory) c.local_get(scratch_), c.v128_load(global_at(in));
      else c.local_get(global_ + static_cast<uint32_t>(in.aux));
      break;
    case Op::GStore:
      if (!program_.globals_in_memory) return push(in.args[0]), assign(global_ + static_cast<uint32_t>(in.aux)), true;
      c.local_get(scratch_), push(in.args[0]), c.local_get(scratch_), c.v128_load(global_at(in));
      c.local_get(mask_), c.simd(Simd::V128Bitselect), c.v128_store(global_at(in));
      return true;
    case Op::Tick: tick(in); return true;
    case Op::Jump: edge(b, *in.targets[0], [&] { c.local_get(mask_); }); return true;
    case Op::Branch: branch(in, b); return true;
    case Op::Ret:  // the kernel's outputs, or the callee's value
      for (size_t k = 0; k < in.args.size(); ++k) push(in.args[k]), assign(output_ + static_cast<uint32_t>(k));
      return true;
    case Op::Call: call_function(in); break;
    case Op::ANew:
    case Op::AStore: array_op(in); return true;
    case Op::ALoad:
    case Op::ALen: array_op(in); break;
  }
  (void)error;
  assign(val(&in));
  return true;
}

// The first operand on the stack.
void Emitter::min_max_tail(bool min, const Inst* b) {
  Code& c = c_;
  Simd op = min ? Simd::F32x4Pmin : Simd::F32x4Pmax;
  if (never_nan(b)) return push(b), c.simd(op);
  if (fast_) {
    push(b), c.simd(op);
    c.local_get(nan_sum_ + u_), push(b), c.simd(Simd::F32x4Add), c.local_set(nan_sum_ + u_);
    return;
  }
  c.local_set(temp_);
  push(b), c.local_get(temp_), push(b), c.simd(op);
  push(b), push(b), c.simd(Simd::F32x4Ne), c.simd(Simd::V128Bitselect);
}

// f = floor(a); a - f >= 0.5 ? f + 1 : f, then a's sign.
void Emitter::round(const Inst* a) {
  Code& c = c_;
  push(a), c.simd(Simd::F32x4Floor), c.local_set(temp_);
  c.local_get(temp_), f32(1), c.simd(Simd::F32x4Add), c.local_get(temp_);
  push(a), c.local_get(temp_), c.simd(Simd::F32x4Sub), f32(0.5f), c.simd(Simd::F32x4Ge);
  c.simd(Simd::V128Bitselect);
  i32(INT32_MAX), c.simd(Simd::V128And);
  push(a), i32(INT32_MIN), c.simd(Simd::V128And), c.simd(Simd::V128Or);
}

// a > 0 ? 1 : (a < 0 ? -1 : a)
void Emitter::sign(const Inst* a) {
  Code& c = c_;
  f32(1), f32(-1), push(a), push(a), f32(0), c.simd(Simd::F32x4Lt);
  c.simd(Simd::V128Bitselect);
  push(a), f32(0), c.simd(Simd::F32x4Gt), c.simd(Simd::V128Bitselect);
}

// sin and cos inline: runtime/math/batch.cpp's trig_lane step for step (the argument reduced in
// double, two lanes at a time; Cephes' polynomials; the quadrant by bit tricks), so the result is
// the batch function's, bit for bit. A group with a lane outside the fast range (huge, inf, NaN)
// calls the batch function instead. Both polynomials are made whatever the quadrant, so a later
// cos (sin) of the same value in the block (the gyroid's pairs) is made here too and skipped at
// its turn (partner_, found by block()). Every copy's steps side by side, under one test of all
// their lanes.
void Emitter::trig(const Inst& in) {
  Code& c = c_;
  const Inst* partner = partner_;
  const int offset = in.op == Op::Cos;
  auto range = [&](uint32_t u) {
    push(in.args[0]), c.local_tee(trig_ + kX), i32(INT32_MAX), c.simd(Simd::V128And);
    f32(math::trig::kFastLimit), c.simd(Simd::F32x4Le);
    if (u) c.simd(Simd::V128And);
  };
  auto inline_path = [&](auto each) {
    each([&] { reduce_half(0, kRLo, kQLo); });
    each([&] { reduce_half(1, kRHi, kQHi); });
    each([&] {
      static constexpr uint8_t kJoin[16] = {0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23};
      c.local_get(trig_ + kRLo), c.local_get(trig_ + kRHi), c.i8x16_shuffle(kJoin), c.local_set(trig_ + kR);
      static constexpr uint8_t kLowWords[16] = {0, 1, 2, 3, 8, 9, 10, 11, 16, 17, 18, 19, 24, 25, 26, 27};
      c.local_get(trig_ + kQLo), c.local_get(trig_ + kQHi), c.i8x16_shuffle(kLowWords), c.local_set(trig_ + kQ);
    });
    each([&] { trig_polynomials(); });
    each([&] { quadrant_value(offset), assign(val(&in)); });
    if (partner) each([&] { quadrant_value(1 - offset), assign(val(partner)); });
  };
  auto each = [&](auto step) {
    for (uint32_t u = 0; u < copies_; ++u) copy(u), step();
    copy(0);
  };
  for (uint32_t u = 0; u < copies_; ++u) copy(u), range(u);
  copy(0);
  c.simd(Simd::I32x4AllTrue);
  if (fast_) {
    // Speculating: the values made, then the test (to the exact code where a lane is out of
    // range). The engine places a computation in the last block before its first use: stores
    // of the values (to scratch, never read) keep each trig op's work in its own block, ahead
    // of the test, rather than all of them in one block at the end where the engine would
    // interleave every copy of every one and run out of registers.
    c.local_set(trig_ok_);
    inline_path(each);
    each([&] {
      c.local_get(scratch_), c.local_get(val(&in)), c.v128_store(16 * u_);
      if (partner) c.local_get(scratch_), c.local_get(val(partner)), c.v128_store(16 * (copies_ + u_));
    });
    c.local_get(trig_ok_), c.op(Opc::I32Eqz), c.br_if(0);
    return;
  }
  c.if_();
  inline_path(each);
  c.op(Opc::Else);
  each([&] {
    batch(in, batch_of(in.op)), assign(val(&in));
    if (partner) batch(*partner, batch_of(partner->op)), assign(val(partner));
  });
  c.end();
}

// The first later cos (sin) of the same value in this block, for a sin (cos).
const Inst* Emitter::trig_partner(const Inst& in, const ir::Block& b, size_t pos) const {
  Op want = in.op == Op::Sin ? Op::Cos : Op::Sin;
  for (size_t k : trig_uses_.at(in.args[0]))
    if (k > pos && b.insts[k]->op == want && !made_early_[b.insts[k]->id]) return b.insts[k];
  return nullptr;
}

// Lanes 0-1 (half 0) or 2-3 of x in double: j = round(x 2/pi) by adding and taking away 1.5 2^52,
// r = x - j pi/2 in two parts, then r to float in the half's low two lanes, and the sum with the
// magic number kept: its low 32 bits are j as an int32 (the quadrant).
void Emitter::reduce_half(int half, uint32_t r_out, uint32_t q_out) {
  using namespace math::trig;
  Code& c = c_;
  static constexpr uint8_t kHigh[16] = {8, 9, 10, 11, 12, 13, 14, 15, 8, 9, 10, 11, 12, 13, 14, 15};
  c.local_get(trig_ + kX);
  if (half) c.local_get(trig_ + kX), c.i8x16_shuffle(kHigh);
  c.simd(Simd::F64x2PromoteLowF32x4), c.local_set(trig_ + kD);
  c.local_get(trig_ + kD), f64(kTwoOverPi), c.simd(Simd::F64x2Mul), f64(kRoundMagic), c.simd(Simd::F64x2Add);
  c.local_tee(trig_ + q_out), f64(kRoundMagic), c.simd(Simd::F64x2Sub), c.local_set(trig_ + kJ);
  c.local_get(trig_ + kD), c.local_get(trig_ + kJ), f64(kPio2Hi), c.simd(Simd::F64x2Mul);
  c.simd(Simd::F64x2Sub), c.local_get(trig_ + kJ), f64(kPio2Lo), c.simd(Simd::F64x2Mul);
  c.simd(Simd::F64x2Sub), c.simd(Simd::F32x4DemoteF64x2Zero), c.local_set(trig_ + r_out);
}

// sin(r) with r's sign (the sum has it, or is +0 at r = -0, where sin(-0) is -0: or-ing the sign
// bit is copysign here) and cos(r), z = r r; then the quadrant's masks.
void Emitter::trig_polynomials() {
  using namespace math::trig;
  Code& c = c_;
  auto z = [&] { c.local_get(trig_ + kZ); };
  auto r = [&] { c.local_get(trig_ + kR); };
  r(), r(), c.simd(Simd::F32x4Mul), c.local_set(trig_ + kZ);
  f32(kSin1), z(), c.simd(Simd::F32x4Mul), f32(kSin2), c.simd(Simd::F32x4Add);
  z(), c.simd(Simd::F32x4Mul), f32(kSin3), c.simd(Simd::F32x4Sub);
  z(), c.simd(Simd::F32x4Mul), r(), c.simd(Simd::F32x4Mul), r(), c.simd(Simd::F32x4Add);
  r(), i32(INT32_MIN), c.simd(Simd::V128And), c.simd(Simd::V128Or), c.local_set(trig_ + kSin);
  f32(kCos1), z(), c.simd(Simd::F32x4Mul), f32(kCos2), c.simd(Simd::F32x4Sub);
  z(), c.simd(Simd::F32x4Mul), f32(kCos3), c.simd(Simd::F32x4Add);
  z(), c.simd(Simd::F32x4Mul), z(), c.simd(Simd::F32x4Mul);
  f32(0.5f), z(), c.simd(Simd::F32x4Mul), c.simd(Simd::F32x4Sub);
  f32(1), c.simd(Simd::F32x4Add), c.local_set(trig_ + kCos);
  quadrant_masks();
}

// Quadrant q's picks by shifts alone (no constants to hold): q31 = q << 31 (bit 0 of q in the
// sign bit); where q is odd the polynomials swap, by xor with m = (sin ^ cos) & odd; bit 1 of q
// is the sign of sin in quadrant q. flip = m ^ that sign. For q + 1 (cos) the swap is the other
// way round (sin ^ m is cos's pick where q is even) and the sign bit is bit 1 of q + 1: bit 1
// of q xor bit 0 of q, the sign of q31.
void Emitter::quadrant_masks() {
  Code& c = c_;
  c.local_get(trig_ + kQ), c.i32_const(31), c.simd(Simd::I32x4Shl), c.local_tee(trig_ + kQ31);
  c.i32_const(31), c.simd(Simd::I32x4ShrS);
  c.local_get(trig_ + kSin), c.local_get(trig_ + kCos), c.simd(Simd::V128Xor), c.simd(Simd::V128And);
  c.local_get(trig_ + kQ), c.i32_const(1), c.simd(Simd::I32x4ShrU), c.i32_const(31), c.simd(Simd::I32x4Shl);
  c.simd(Simd::V128Xor), c.local_set(trig_ + kFlip);
}

// sin in quadrant q + offset (cos x = sin(x + pi/2)).
void Emitter::quadrant_value(int offset) {
  Code& c = c_;
  c.local_get(trig_ + (offset ? kCos : kSin)), c.local_get(trig_ + kFlip), c.simd(Simd::V128Xor);
  if (offset) c.local_get(trig_ + kQ31), c.simd(Simd::V128Xor);
}

// A runtime batch function on the four lanes, through the scratch area.
void Emitter::batch(const Inst& in, const void* fn) {
  Code& c = c_;
  for (size_t k = 0; k < in.args.size(); ++k)
    c.local_get(scratch_), push(in.args[k]), c.v128_store(16 * static_cast<uint32_t>(k));
  for (size_t k = 0; k < in.args.size(); ++k)
    c.local_get(scratch_), c.i32_const(16 * static_cast<int32_t>(k)), c.op(Opc::I32Add);
  c.local_get(scratch_), c.i32_const(kScratchResult), c.op(Opc::I32Add);
  c.i32_const(4);
  c.call(import(fn));
  c.local_get(scratch_), c.v128_load(kScratchResult);
}

// An array operation through backends/lane_arrays.h's helpers (the VM's storage and messages):
// the arrays, the slot, the operands' and result's places, the lanes' mask; a helper's 1 ends the
// run with its message.
void Emitter::array_op(const Inst& in) {
  Code& c = c_;
  for (size_t k = 0; k < in.args.size(); ++k)
    c.local_get(scratch_), push(in.args[k]), c.v128_store(16 * static_cast<uint32_t>(k));
  c.local_get(scratch_), c.local_get(mask_), c.v128_store(kScratchMask);
  uint32_t slot = in.array_global ? static_cast<uint32_t>(in.aux) : first_slot_ + static_cast<uint32_t>(in.aux);
  c.local_get(arrays_param_), c.i32_const(static_cast<int32_t>(slot));
  auto place = [&](uint32_t offset) {
    c.local_get(scratch_), c.i32_const(static_cast<int32_t>(offset)), c.op(Opc::I32Add);
  };
  switch (in.op) {
    case Op::ANew: place(0); break;
    case Op::ALoad: place(0), place(kScratchResult); break;
    case Op::AStore: place(0), place(16); break;
    default: place(kScratchResult); break;  // ALen
  }
  place(kScratchMask);
  c.call(import(helper_of(in.op)));
  c.if_(), trap(backends::trap_code(2, &in)), c.end();
  if (in.op == Op::ALoad || in.op == Op::ALen) c.local_get(scratch_), c.v128_load(kScratchResult);
}

}  // namespace fscript::wasm::detail
