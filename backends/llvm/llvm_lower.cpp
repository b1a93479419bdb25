// SSA IR to LLVM IR, one vector of floats per value (see llvm_lower.h). Values used in other
// blocks, phis, globals and pending masks live in allocas written under the block's lane mask;
// LLVM's SROA/mem2reg turns them back into SSA, so a straight-line kernel ends up as plain vector
// code. The op switch has no default: a new op does not build until it is lowered here.
#include "backends/llvm/llvm_lower.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Intrinsics.h>
#include <llvm/IR/IntrinsicsX86.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/MDBuilder.h>
#include <llvm/IR/Module.h>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "ir/ranges.h"
#include "runtime/math/trig_constants.h"

namespace fscript::llvmjit {
namespace {

using ir::Op;

// What the whole program shares: types, the runtime declarations, one LLVM function per compiled
// function of ours, and the call context type (globals, loop counters, arrays, depth, stack limit).
struct Shared {
  llvm::LLVMContext& c;
  llvm::Module& m;
  const ir::Module& module;
  uint32_t width;
  backends::Budgets budgets;
  llvm::Type *f32, *i32, *i64, *ptr;
  llvm::VectorType *vf, *vi, *vb;  // <W x float>, <W x i32>, <W x i1>
  llvm::StructType* ctx;
  std::vector<llvm::Function*> fns;  // by function index (nullptr: not compiled)
  int num_globals = 0;
  llvm::IntegerType* mask_bits;  // iW: the lanes' mask as a call argument
};

enum CtxField : unsigned { kGlobals, kCounters, kArrays, kDepth, kStackLimit };

class LlvmFunctionLowering {
 public:
  LlvmFunctionLowering(Shared& s, const ir::Function& fn, llvm::Function* out, bool callee, uint32_t local_arrays,
                       std::vector<ir::Range> ranges)
      : s_(s), fn_(fn), f_(out), b_(s.c), callee_(callee), local_arrays_(local_arrays), ranges_(std::move(ranges)) {}

  void run() {
    layout();
    llvm::BasicBlock* entry = llvm::BasicBlock::Create(s_.c, "entry", f_);
    b_.SetInsertPoint(entry);
    allocate();
    if (callee_) callee_entry();
    else kernel_entry();
  }

 private:
  // ---- layout: block order, which values cross blocks ----
  void layout() {
    order_ = ir::reverse_post_order(fn_);
    index_.assign(fn_.next_block, -1);
    for (size_t b = 0; b < order_.size(); ++b) index_[order_[b]->id] = static_cast<int>(b);
    std::vector<int> def(fn_.next_value, -1);
    cross_.assign(fn_.next_value, false);
    bool memory = false;
    for (size_t b = 0; b < order_.size(); ++b)
      for (const ir::Inst* in : order_[b]->insts) {
        if (in->defines_value()) def[in->id] = static_cast<int>(b);
        if (in->op == Op::Phi) cross_[in->id] = true;
        memory |= in->op == Op::GLoad || in->op == Op::GStore || in->op == Op::Tick || in->op == Op::Call ||
            in->op == Op::ANew || in->op == Op::ALoad || in->op == Op::AStore || in->op == Op::ALen;
      }
    for (size_t b = 0; b < order_.size(); ++b)
      for (const ir::Inst* in : order_[b]->insts)
        for (size_t k = 0; k < in->args.size(); ++k) {
          const ir::Inst* a = in->args[k];
          if (a->op == Op::Const) continue;
          if (in->op == Op::Phi || def[a->id] != static_cast<int>(b)) cross_[a->id] = true;
        }
    straight_ = order_.size() == 1 && !memory && !callee_;
  }

  llvm::Value* splat(float v) { return llvm::ConstantFP::get(s_.vf, v); }
  llvm::Value* zero_mask() { return llvm::Constant::getNullValue(s_.vb); }
  llvm::AllocaInst* slot(llvm::Type* t, const char* name) { return b_.CreateAlloca(t, nullptr, name); }

  void allocate() {
    home_.assign(fn_.next_value, nullptr);
    if (straight_) return;
    for (uint32_t v = 0; v < fn_.next_value; ++v)
      if (cross_[v]) home_[v] = slot(s_.vf, "home");
    for (size_t b = 0; b < order_.size(); ++b) pending_.push_back(slot(s_.vb, "pending"));
    for (uint32_t o = 0; o < fn_.num_results; ++o) out_.push_back(slot(s_.vf, "out"));
    scratch_ = slot(llvm::ArrayType::get(s_.f32, 4 * s_.width), "scratch");
    mask_words_ = slot(s_.vi, "mask_words");
    if (callee_ && !fn_.arrays.empty())
      save_ = slot(llvm::ArrayType::get(s_.i64, 2 * s_.width * fn_.arrays.size()), "array_save");
  }

  // ---- the kernel: a loop over groups of `width` points ----
  void kernel_entry() {
    llvm::Argument *inputs = f_->getArg(0), *outputs = f_->getArg(1), *begin = f_->getArg(2), *end = f_->getArg(3);
    arrays_ = f_->getArg(4);
    if (!straight_) {
      globals_ = slot(llvm::ArrayType::get(s_.vf, std::max(1, s_.num_globals)), "globals");
      counters_ = slot(counter_type(), "counters");
      ctx_ = slot(s_.ctx, "ctx");
      b_.CreateStore(globals_, b_.CreateStructGEP(s_.ctx, ctx_, kGlobals));
      b_.CreateStore(counters_, b_.CreateStructGEP(s_.ctx, ctx_, kCounters));
      b_.CreateStore(arrays_, b_.CreateStructGEP(s_.ctx, ctx_, kArrays));
      b_.CreateStore(b_.getInt64(0), b_.CreateStructGEP(s_.ctx, ctx_, kDepth));
      b_.CreateStore(f_->getArg(5), b_.CreateStructGEP(s_.ctx, ctx_, kStackLimit));
    }
    llvm::BasicBlock* pre = b_.GetInsertBlock();
    llvm::BasicBlock* loop = llvm::BasicBlock::Create(s_.c, "loop", f_);
    llvm::BasicBlock* group = llvm::BasicBlock::Create(s_.c, "group", f_);
    llvm::BasicBlock* done = llvm::BasicBlock::Create(s_.c, "done", f_);
    b_.CreateBr(loop);
    b_.SetInsertPoint(loop);
    llvm::PHINode* i = b_.CreatePHI(s_.i64, 2, "i");
    i->addIncoming(begin, pre);
    b_.CreateCondBr(b_.CreateICmpULT(i, end), group, done);
    b_.SetInsertPoint(done);
    b_.CreateRet(b_.getInt64(0));
    b_.SetInsertPoint(group);
    point_ = i;
    inputs_ = inputs;
    outputs_ = outputs;
    if (!straight_) start_group();
    blocks();
    if (!straight_)
      finish_scan([&] {
        for (uint32_t o = 0; o < fn_.num_results; ++o) store_output(o, b_.CreateLoad(s_.vf, out_[o]));
      });
    llvm::Value* next = b_.CreateAdd(i, b_.getInt64(s_.width));
    i->addIncoming(next, b_.GetInsertBlock());
    b_.CreateBr(loop);
  }

  void start_group() {
    b_.CreateStore(llvm::Constant::getAllOnesValue(s_.vb), pending_[0]);
    for (size_t b = 1; b < pending_.size(); ++b) b_.CreateStore(zero_mask(), pending_[b]);
    b_.CreateStore(llvm::Constant::getNullValue(counter_type()), counters_);
    for (auto* o : out_) b_.CreateStore(splat(0), o);
    for (int g = 0; g < s_.num_globals; ++g) b_.CreateStore(splat(__builtin_nanf("")), global_ptr(g));
    if (has_arrays()) call_runtime("fs_lanes_reset", s_.i32, {arrays_});
  }

  // ---- a callee: (ctx, result, mask, args...) runs once for its caller's lanes ----
  void callee_entry() {
    ctx_ = f_->getArg(0);
    arrays_ = b_.CreateLoad(s_.ptr, b_.CreateStructGEP(s_.ctx, ctx_, kArrays));
    llvm::Value* limit = b_.CreateLoad(s_.i64, b_.CreateStructGEP(s_.ctx, ctx_, kStackLimit));
    llvm::Value* frame =
        b_.CreatePtrToInt(b_.CreateIntrinsic(llvm::Intrinsic::frameaddress, {s_.ptr}, {b_.getInt32(0)}), s_.i64);
    trap_if(b_.CreateICmpULT(frame, limit), 4, backends::first_located(fn_));
    b_.CreateStore(b_.CreateBitCast(f_->getArg(2), s_.vb), pending_[0]);
    for (size_t b = 1; b < pending_.size(); ++b) b_.CreateStore(zero_mask(), pending_[b]);
    for (auto* o : out_) b_.CreateStore(splat(0), o);
    if (!fn_.arrays.empty()) local_arrays("fs_lanes_enter");
    blocks();
    finish_scan([&] {
      b_.CreateAlignedStore(b_.CreateLoad(s_.vf, out_[0]), f_->getArg(1), llvm::Align(4));
      if (!fn_.arrays.empty()) local_arrays("fs_lanes_leave");
    });
    b_.CreateRet(b_.getInt64(0));
  }
  void local_arrays(const char* helper) {
    call_runtime(helper, s_.i32,
                 {arrays_, b_.getInt32(local_arrays_), b_.getInt32(static_cast<uint32_t>(fn_.arrays.size())), save_});
  }

  // ---- blocks in reverse post-order, each for its waiting lanes ----
  void blocks() {
    for (size_t b = 0; b <= order_.size(); ++b)
      labels_.push_back(llvm::BasicBlock::Create(s_.c, b < order_.size() ? "block" : "scanned", f_));
    b_.CreateBr(labels_[0]);
    for (size_t b = 0; b < order_.size(); ++b) block(static_cast<int>(b));
    b_.SetInsertPoint(labels_[order_.size()]);
  }
  // After the scan: lanes still waiting (sent back by a later block) rescan; then `finish`.
  template <typename Finish>
  void finish_scan(Finish finish) {
    llvm::Value* any = llvm::ConstantInt::getFalse(s_.c);
    for (auto* p : pending_) any = b_.CreateOr(any, b_.CreateOrReduce(b_.CreateLoad(s_.vb, p)));
    llvm::BasicBlock* out = llvm::BasicBlock::Create(s_.c, "finish", f_);
    b_.CreateCondBr(any, labels_[0], out);
    b_.SetInsertPoint(out);
    finish();
  }

  void block(int b) {
    cur_ = b;
    b_.SetInsertPoint(labels_[b]);
    local_.assign(fn_.next_value, nullptr);
    if (straight_) {
      active_ = llvm::Constant::getAllOnesValue(s_.vb);
    } else {
      llvm::Value* p = b_.CreateLoad(s_.vb, pending_[b]);
      llvm::BasicBlock* body = llvm::BasicBlock::Create(s_.c, "run", f_);
      b_.CreateCondBr(b_.CreateOrReduce(p), body, labels_[b + 1]);
      b_.SetInsertPoint(body);
      b_.CreateStore(zero_mask(), pending_[b]);
      active_ = p;
    }
    for (const ir::Inst* in : order_[b]->insts)
      if (in->op != Op::Phi) inst(*in);
  }

  // ---- values ----
  llvm::Value* val(const ir::Inst* v) {
    if (v->op == Op::Const) return splat(v->imm);
    if (local_[v->id]) return local_[v->id];
    return b_.CreateLoad(s_.vf, home_[v->id]);
  }
  void define(const ir::Inst& in, llvm::Value* v) {
    local_[in.id] = v;
    if (home_[in.id]) masked_store(home_[in.id], v, active_);
  }
  void masked_store(llvm::Value* at, llvm::Value* v, llvm::Value* mask) {
    b_.CreateStore(b_.CreateSelect(mask, v, b_.CreateLoad(s_.vf, at)), at);
  }
  llvm::Value* global_ptr(int g) {
    llvm::Value* base = globals_;
    if (callee_) base = b_.CreateLoad(s_.ptr, b_.CreateStructGEP(s_.ctx, ctx_, kGlobals));
    return b_.CreateConstGEP1_64(s_.vf, base, static_cast<uint64_t>(g));
  }
  llvm::Type* counter_type() const { return llvm::FixedVectorType::get(s_.i64, s_.width); }
  llvm::Value* counters_ptr() {
    if (callee_) return b_.CreateLoad(s_.ptr, b_.CreateStructGEP(s_.ctx, ctx_, kCounters));
    return counters_;
  }
  llvm::Value* lane_ptr(llvm::Value* array_of_ptrs, uint32_t k) {
    llvm::Value* base = b_.CreateLoad(s_.ptr, b_.CreateConstGEP1_64(s_.ptr, array_of_ptrs, k));
    return b_.CreateGEP(s_.f32, base, point_);
  }
  void store_output(uint32_t o, llvm::Value* v) { b_.CreateAlignedStore(v, lane_ptr(outputs_, o), llvm::Align(4)); }
  bool has_arrays() const {
    for (const ir::Block* blk : order_)
      for (const ir::Inst* in : blk->insts)
        if (in->op == Op::ANew || in->op == Op::ALoad || in->op == Op::AStore || in->op == Op::ALen) return true;
    return false;
  }

  // ---- semantics (runtime/math/math.h, lane by lane) ----
  llvm::Value* truthy(const ir::Inst* v) {  // ordered and != 0
    llvm::Value* x = val(v);
    if (!ir::may_be_nan(v, ranges_)) return b_.CreateFCmpUNE(x, splat(0));
    return b_.CreateFCmpONE(x, splat(0));
  }
  llvm::Value* bool_float(llvm::Value* m) { return b_.CreateSelect(m, splat(1), splat(0)); }
  // min: b NaN ? NaN : (b < a ? b : a); max alike with >.
  // min: b < a ? b : a (max with >), then a NaN b. The first part is x86's minps/maxps with b
  // first, and is written as that instruction's intrinsic, not as fcmp + select: LLVM 19's
  // InstCombine folds nested selects of this shape as if -0 and +0 were one value (min(-0,
  // min(y, -0)) became min(y, -0): +0 at y = +0 where the language says -0; found by the
  // backend_diff campaign). The intrinsics are opaque to it.
  llvm::Value* minmax(llvm::Value* a, const ir::Inst* bi, llvm::Value* b, bool is_min) {
    llvm::Value* m = x86_minmax(b, a, is_min);
    if (!ir::may_be_nan(bi, ranges_)) return m;
    return b_.CreateSelect(b_.CreateFCmpUNO(b, b), b, m);
  }
  llvm::Value* x86_minmax(llvm::Value* first, llvm::Value* second, bool is_min) {
    using namespace llvm::Intrinsic;
    const int w = static_cast<int>(s_.width);
    if (w == 16)  // the AVX-512 form takes a rounding operand: 4, the current direction
      return b_.CreateIntrinsic(is_min ? x86_avx512_min_ps_512 : x86_avx512_max_ps_512, {},
                                {first, second, b_.getInt32(4)});
    if (w == 8) return b_.CreateIntrinsic(is_min ? x86_avx_min_ps_256 : x86_avx_max_ps_256, {}, {first, second});
    ID four = is_min ? x86_sse_min_ps : x86_sse_max_ps;
    if (w == 4) return b_.CreateIntrinsic(four, {}, {first, second});
    // Fewer lanes (the one-point kernel's one): through the four-lane instruction, lanes past w unused.
    std::vector<int> widen(4, -1), narrow(static_cast<size_t>(w));
    for (int i = 0; i < w; ++i) widen[static_cast<size_t>(i)] = i, narrow[static_cast<size_t>(i)] = i;
    llvm::Value* r =
        b_.CreateIntrinsic(four, {}, {b_.CreateShuffleVector(first, widen), b_.CreateShuffleVector(second, widen)});
    return b_.CreateShuffleVector(r, narrow);
  }
  llvm::Value* unary(llvm::Intrinsic::ID id, llvm::Value* a) { return b_.CreateUnaryIntrinsic(id, a); }

  llvm::Value* call_runtime(const char* name, llvm::Type* ret, std::vector<llvm::Value*> args) {
    std::vector<llvm::Type*> types;
    for (auto* a : args) types.push_back(a->getType());
    llvm::FunctionCallee f = s_.m.getOrInsertFunction(name, llvm::FunctionType::get(ret, types, false));
    return b_.CreateCall(f, args);
  }
  // A batch function of runtime/math over the group's lanes, through the scratch area.
  llvm::Value* batch(const char* name, const ir::Inst& in) {
    std::vector<llvm::Value*> args;
    for (size_t k = 0; k <= in.args.size(); ++k) args.push_back(b_.CreateConstGEP1_64(s_.f32, scratch(), k * s_.width));
    for (size_t k = 0; k < in.args.size(); ++k) b_.CreateAlignedStore(val(in.args[k]), args[k], llvm::Align(4));
    args.push_back(b_.getInt64(s_.width));
    call_runtime(name, b_.getVoidTy(), args);
    return b_.CreateAlignedLoad(s_.vf, args[in.args.size()], llvm::Align(4));
  }
  llvm::Value* scratch() {
    if (!scratch_) {  // straight-line kernels allocate it on first use, in the entry block
      llvm::IRBuilder<>::InsertPointGuard guard(b_);
      b_.SetInsertPoint(&f_->getEntryBlock(), f_->getEntryBlock().getFirstInsertionPt());
      scratch_ = slot(llvm::ArrayType::get(s_.f32, 4 * s_.width), "scratch");
    }
    return scratch_;
  }

  // sin (quadrant offset 0) and cos (1) inline: runtime/math/batch.cpp's trig_lane step for step
  // (reduction in double, Cephes polynomials, quadrant by integer bit operations), so the result
  // is the batch function's bit for bit; a group with a lane beyond its fast range (huge, inf,
  // NaN) calls the batch function instead.
  llvm::Value* trig(const ir::Inst& in, int offset, const char* batch_name) {
    llvm::Value* x = val(in.args[0]);
    auto* vd = llvm::FixedVectorType::get(b_.getDoubleTy(), s_.width);
    auto f = [&](float v) { return llvm::ConstantFP::get(s_.vf, v); };
    auto d = [&](double v) { return llvm::ConstantFP::get(vd, v); };
    auto i = [&](uint32_t v) { return llvm::ConstantInt::get(s_.vi, v); };
    using namespace math::trig;
    llvm::Value* fast = b_.CreateFCmpOLE(unary(llvm::Intrinsic::fabs, x), f(kFastLimit));
    llvm::Value* xd = b_.CreateFPExt(b_.CreateSelect(fast, x, f(0.0f)), vd);
    llvm::Value* magic = d(kRoundMagic);
    llvm::Value* jd = b_.CreateFSub(b_.CreateFAdd(b_.CreateFMul(xd, d(kTwoOverPi)), magic), magic);
    llvm::Value* r = b_.CreateFSub(b_.CreateFSub(xd, b_.CreateFMul(jd, d(kPio2Hi))), b_.CreateFMul(jd, d(kPio2Lo)));
    llvm::Value* q = b_.CreateAdd(b_.CreateFPToSI(jd, s_.vi), i(static_cast<uint32_t>(offset)));
    llvm::Value* rf = b_.CreateFPTrunc(r, s_.vf);
    llvm::Value* z = b_.CreateFMul(rf, rf);
    auto mul = [&](llvm::Value* a, llvm::Value* b) { return b_.CreateFMul(a, b); };
    // sin: ((kSin1 z + kSin2) z - kSin3) z r + r;  cos: ((kCos1 z - kCos2) z + kCos3) z z - 0.5 z + 1
    // sin with r's sign: the sum is +0 at r = -0, where sin(-0) is -0.
    llvm::Value* sp = b_.CreateBinaryIntrinsic(
        llvm::Intrinsic::copysign,
        b_.CreateFAdd(mul(mul(b_.CreateFSub(mul(b_.CreateFAdd(mul(f(kSin1), z), f(kSin2)), z), f(kSin3)), z), rf), rf),
        rf);
    llvm::Value* cp = b_.CreateFAdd(
        b_.CreateFSub(mul(mul(b_.CreateFAdd(mul(b_.CreateFSub(mul(f(kCos1), z), f(kCos2)), z), f(kCos3)), z), z),
                      mul(f(0.5f), z)),
        f(1.0f));
    llvm::Value* odd = b_.CreateICmpNE(b_.CreateAnd(q, i(1)), i(0));
    llvm::Value* v = b_.CreateBitCast(b_.CreateSelect(odd, cp, sp), s_.vi);
    llvm::Value* result = b_.CreateBitCast(b_.CreateXor(v, b_.CreateShl(b_.CreateAnd(q, i(2)), i(30))), s_.vf);
    // Out-of-range lanes: the whole group through the batch function.
    llvm::BasicBlock* here = b_.GetInsertBlock();
    llvm::BasicBlock* slow = llvm::BasicBlock::Create(s_.c, "trig_slow", f_);
    llvm::BasicBlock* join = llvm::BasicBlock::Create(s_.c, "trig_done", f_);
    llvm::Value* all_fast = b_.CreateAndReduce(fast);
    b_.CreateCondBr(all_fast, join, slow, llvm::MDBuilder(s_.c).createBranchWeights(1 << 20, 1));
    b_.SetInsertPoint(slow);
    llvm::Value* slow_result = batch(batch_name, in);
    llvm::BasicBlock* slow_end = b_.GetInsertBlock();
    b_.CreateBr(join);
    b_.SetInsertPoint(join);
    llvm::PHINode* phi = b_.CreatePHI(s_.vf, 2);
    phi->addIncoming(result, here);
    phi->addIncoming(slow_result, slow_end);
    return phi;
  }

  // A runtime error when any lane meets `bad`: the function returns trap_code(kind, at).
  void trap_if(llvm::Value* bad, uint64_t kind, const ir::Inst* at) {
    llvm::BasicBlock* trap = llvm::BasicBlock::Create(s_.c, "trap", f_);
    llvm::BasicBlock* ok = llvm::BasicBlock::Create(s_.c, "ok", f_);
    b_.CreateCondBr(bad, trap, ok, llvm::MDBuilder(s_.c).createBranchWeights(1, 1 << 20));
    b_.SetInsertPoint(trap);
    b_.CreateRet(b_.getInt64(backends::trap_code(kind, at)));
    b_.SetInsertPoint(ok);
  }

  void inst(const ir::Inst& in) {
    auto a = [&](int k) { return val(in.args[static_cast<size_t>(k)]); };
    switch (in.op) {
      case Op::Const:
      case Op::Phi: return;  // constants inline; a phi's home is written on edges
      case Op::Param:
        if (callee_) return define(in, f_->getArg(3 + static_cast<unsigned>(in.aux)));
        if (fn_.row_params_from && static_cast<uint32_t>(in.aux) >= fn_.row_params_from) {  // one value per call
          llvm::Value* base =
              b_.CreateLoad(s_.ptr, b_.CreateConstGEP1_64(s_.ptr, inputs_, static_cast<uint32_t>(in.aux)));
          return define(in, b_.CreateVectorSplat(s_.width, b_.CreateAlignedLoad(s_.f32, base, llvm::Align(4))));
        }
        return define(in,
                      b_.CreateAlignedLoad(s_.vf, lane_ptr(inputs_, static_cast<uint32_t>(in.aux)), llvm::Align(4)));
      case Op::Add: return define(in, b_.CreateFAdd(a(0), a(1)));
      case Op::Sub: return define(in, b_.CreateFSub(a(0), a(1)));
      case Op::Mul: return define(in, b_.CreateFMul(a(0), a(1)));
      case Op::Div: return define(in, b_.CreateFDiv(a(0), a(1)));
      case Op::Mod: return define(in, b_.CreateFRem(a(0), a(1)));  // fmod, exact
      case Op::Neg: return define(in, b_.CreateFNeg(a(0)));
      case Op::Min: return define(in, minmax(a(0), in.args[1], a(1), true));
      case Op::Max: return define(in, minmax(a(0), in.args[1], a(1), false));
      case Op::Abs: return define(in, unary(llvm::Intrinsic::fabs, a(0)));
      case Op::Sqrt: return define(in, unary(llvm::Intrinsic::sqrt, a(0)));
      case Op::Floor: return define(in, unary(llvm::Intrinsic::floor, a(0)));
      case Op::Ceil: return define(in, unary(llvm::Intrinsic::ceil, a(0)));
      case Op::Round: {  // f = floor(a); a - f >= 0.5 ? f + 1 : f, with a's sign (round(-0.4) is -0)
        llvm::Value* f = unary(llvm::Intrinsic::floor, a(0));
        llvm::Value* up = b_.CreateFCmpOGE(b_.CreateFSub(a(0), f), splat(0.5f));
        llvm::Value* r = b_.CreateSelect(up, b_.CreateFAdd(f, splat(1)), f);
        return define(in, b_.CreateBinaryIntrinsic(llvm::Intrinsic::copysign, r, a(0)));
      }
      case Op::Sign: {  // a > 0 ? 1 : (a < 0 ? -1 : a)
        llvm::Value* x = a(0);
        llvm::Value* neg = b_.CreateSelect(b_.CreateFCmpOLT(x, splat(0)), splat(-1), x);
        return define(in, b_.CreateSelect(b_.CreateFCmpOGT(x, splat(0)), splat(1), neg));
      }
      case Op::Clamp: {
        llvm::Value* lo = minmax(a(0), in.args[1], a(1), false);
        return define(in, minmax(lo, in.args[2], a(2), true));
      }
      // Batch rows of ir/math_ops.def call runtime/math's batch function through its runtime
      // symbol (llvm_jit.cpp); Trig rows inline it; Lane rows have their own cases.
#define FS_LLVM_Lane(N, FN)
#define FS_LLVM_Batch(N, FN) \
  case Op::N: return define(in, batch("fs_rt_" #FN, in));
#define FS_LLVM_Trig(N, FN) \
  case Op::N: return define(in, trig(in, in.op == Op::Cos, "fs_rt_" #FN));
#define FS_MATH(N, FN, A, HOW) FS_LLVM_##HOW(N, FN)
#include "ir/math_ops.def"
#undef FS_LLVM_Lane
#undef FS_LLVM_Batch
#undef FS_LLVM_Trig
      case Op::Eq: return define(in, bool_float(b_.CreateFCmpOEQ(a(0), a(1))));
      case Op::Ne: return define(in, bool_float(b_.CreateFCmpUNE(a(0), a(1))));
      case Op::Lt: return define(in, bool_float(b_.CreateFCmpOLT(a(0), a(1))));
      case Op::Le: return define(in, bool_float(b_.CreateFCmpOLE(a(0), a(1))));
      case Op::Gt: return define(in, bool_float(b_.CreateFCmpOGT(a(0), a(1))));
      case Op::Ge: return define(in, bool_float(b_.CreateFCmpOGE(a(0), a(1))));
      case Op::Not: return define(in, b_.CreateSelect(truthy(in.args[0]), splat(0), splat(1)));
      case Op::Truth: return define(in, bool_float(truthy(in.args[0])));
      case Op::Select: return define(in, b_.CreateSelect(truthy(in.args[0]), a(1), a(2)));
      case Op::GLoad: return define(in, b_.CreateLoad(s_.vf, global_ptr(in.aux)));
      case Op::GStore: return masked_store(global_ptr(in.aux), a(0), active_);
      case Op::ANew:
      case Op::ALoad:
      case Op::AStore:
      case Op::ALen: return array_op(in);
      case Op::Call: return call(in);
      case Op::Tick: {  // per-lane iteration counters, 64-bit like the VM's
        llvm::Value* at = counters_ptr();
        llvm::Value* n = b_.CreateAdd(b_.CreateLoad(counter_type(), at), b_.CreateZExt(active_, counter_type()));
        b_.CreateStore(n, at);
        llvm::Value* budget = llvm::ConstantInt::get(counter_type(), s_.budgets.max_loop_iterations);
        trap_if(b_.CreateOrReduce(b_.CreateICmpUGT(n, budget)), 1, &in);
        return cancel_check(in);
      }
      case Op::Jump: return jump(in);
      case Op::Branch: return branch(in);
      case Op::Ret: return ret(in);
    }
  }

  // A run cancelled from another thread (support/cancel.h) ends the loop or the recursion. The JIT
  // resolves fs_cancel_slot to the host's word that holds the current flag's address (llvm_jit.cpp):
  // a symbol, not a constant, so objects in the disk cache stay valid in another process.
  void cancel_check(const ir::Inst& in) {
    llvm::GlobalVariable* slot = s_.m.getGlobalVariable("fs_cancel_slot");
    if (!slot)
      slot =
          new llvm::GlobalVariable(s_.m, s_.ptr, false, llvm::GlobalValue::ExternalLinkage, nullptr, "fs_cancel_slot");
    llvm::LoadInst* flag_at = b_.CreateAlignedLoad(s_.ptr, slot, llvm::Align(8));
    flag_at->setAtomic(llvm::AtomicOrdering::Monotonic);
    llvm::LoadInst* flag = b_.CreateAlignedLoad(b_.getInt8Ty(), flag_at, llvm::Align(1));
    flag->setAtomic(llvm::AtomicOrdering::Monotonic);
    trap_if(b_.CreateICmpNE(flag, b_.getInt8(0)), 5, &in);
  }

  // ---- arrays and calls ----
  void array_op(const ir::Inst& in) {
    uint32_t slot = in.array_global ? static_cast<uint32_t>(in.aux) : local_arrays_ + static_cast<uint32_t>(in.aux);
    b_.CreateStore(b_.CreateSExt(active_, s_.vi), mask_words_);
    std::vector<llvm::Value*> args{arrays_, b_.getInt32(slot)};
    for (size_t k = 0; k < in.args.size(); ++k) {
      llvm::Value* at = b_.CreateConstGEP1_64(s_.f32, scratch(), k * s_.width);
      b_.CreateAlignedStore(val(in.args[k]), at, llvm::Align(4));
      args.push_back(at);
    }
    llvm::Value* result = b_.CreateConstGEP1_64(s_.f32, scratch(), 3 * s_.width);
    const char* name = "fs_lanes_alen";
    switch (in.op) {
      case Op::ANew: name = "fs_lanes_anew"; break;
      case Op::ALoad: name = "fs_lanes_aload", args.push_back(result); break;
      case Op::AStore: name = "fs_lanes_astore"; break;
      default: args.push_back(result); break;  // ALen
    }
    args.push_back(mask_words_);
    llvm::Value* status = call_runtime(name, s_.i32, args);
    trap_if(b_.CreateICmpNE(status, b_.getInt32(0)), 2, &in);
    if (in.op == Op::ALoad || in.op == Op::ALen) define(in, b_.CreateAlignedLoad(s_.vf, result, llvm::Align(4)));
  }

  // The callee runs for this block's lanes; recursive callees count against the depth budget.
  void call(const ir::Inst& in) {
    bool counted = s_.module.functions[static_cast<size_t>(in.aux)]->recursive;
    llvm::Value* depth_at = b_.CreateStructGEP(s_.ctx, ctx_, kDepth);
    llvm::Value* depth = b_.CreateLoad(s_.i64, depth_at);
    if (counted) {
      trap_if(b_.CreateICmpUGE(depth, b_.getInt64(s_.budgets.max_call_depth)), 3, &in);
      cancel_check(in);
      b_.CreateStore(b_.CreateAdd(depth, b_.getInt64(1)), depth_at);
    }
    llvm::Value* result = b_.CreateConstGEP1_64(s_.f32, scratch(), 3 * s_.width);
    std::vector<llvm::Value*> args{ctx_, result, b_.CreateBitCast(active_, s_.mask_bits)};
    for (const ir::Inst* a : in.args) args.push_back(val(a));
    llvm::CallInst* status = b_.CreateCall(s_.fns[static_cast<size_t>(in.aux)], args);
    llvm::BasicBlock* fail = llvm::BasicBlock::Create(s_.c, "callee_error", f_);
    llvm::BasicBlock* ok = llvm::BasicBlock::Create(s_.c, "returned", f_);
    b_.CreateCondBr(b_.CreateICmpNE(status, b_.getInt64(0)), fail, ok);
    b_.SetInsertPoint(fail);
    b_.CreateRet(status);
    b_.SetInsertPoint(ok);
    if (counted) b_.CreateStore(depth, depth_at);
    define(in, b_.CreateAlignedLoad(s_.vf, result, llvm::Align(4)));
  }

  // ---- terminators: phi moves under the edge mask, lanes wait at the target ----
  void edge(const ir::Block* to, llvm::Value* mask) {
    const ir::Block* from = order_[static_cast<size_t>(cur_)];
    std::vector<std::pair<llvm::Value*, llvm::Value*>> moves;  // (home, value): a parallel copy
    for (const ir::Inst* phi : to->insts)
      if (phi->op == Op::Phi)
        for (size_t j = 0; j < phi->args.size(); ++j)
          if (phi->targets[j] == from) moves.push_back({home_[phi->id], val(phi->args[j])});
    for (auto& [home, v] : moves) masked_store(home, v, mask);
    llvm::Value* p = pending_[static_cast<size_t>(index_[to->id])];
    b_.CreateStore(b_.CreateOr(b_.CreateLoad(s_.vb, p), mask), p);
  }
  // After the edges: a back edge that carried lanes jumps to its target; else on to the next block.
  void leave(std::vector<std::pair<const ir::Block*, llvm::Value*>> edges) {
    for (auto& [to, mask] : edges) {
      int t = index_[to->id];
      if (t > cur_) continue;
      llvm::BasicBlock* next = llvm::BasicBlock::Create(s_.c, "no_back_edge", f_);
      b_.CreateCondBr(b_.CreateOrReduce(mask), labels_[static_cast<size_t>(t)], next);
      b_.SetInsertPoint(next);
    }
    b_.CreateBr(labels_[static_cast<size_t>(cur_) + 1]);
  }
  void jump(const ir::Inst& in) {
    edge(in.targets[0], active_);
    leave({{in.targets[0], active_}});
  }
  void branch(const ir::Inst& in) {
    llvm::Value* c = truthy(in.args[0]);
    llvm::Value* yes = b_.CreateAnd(active_, c);
    llvm::Value* no = b_.CreateAnd(active_, b_.CreateNot(c));
    edge(in.targets[0], yes);
    edge(in.targets[1], no);
    bool first_back = index_[in.targets[0]->id] <= index_[in.targets[1]->id];
    if (first_back) leave({{in.targets[0], yes}, {in.targets[1], no}});
    else leave({{in.targets[1], no}, {in.targets[0], yes}});
  }
  void ret(const ir::Inst& in) {
    if (straight_) {
      for (size_t o = 0; o < in.args.size(); ++o) store_output(static_cast<uint32_t>(o), val(in.args[o]));
      b_.CreateBr(labels_[static_cast<size_t>(cur_) + 1]);
      return;
    }
    for (size_t o = 0; o < in.args.size(); ++o) masked_store(out_[o], val(in.args[o]), active_);
    b_.CreateBr(labels_[static_cast<size_t>(cur_) + 1]);
  }

  Shared& s_;
  const ir::Function& fn_;
  llvm::Function* f_;
  llvm::IRBuilder<> b_;
  bool callee_, straight_ = true;
  uint32_t local_arrays_;
  std::vector<ir::Range> ranges_;
  std::vector<ir::Block*> order_;
  std::vector<int> index_;
  std::vector<bool> cross_;
  std::vector<llvm::AllocaInst*> home_, pending_, out_;
  std::vector<llvm::Value*> local_;
  std::vector<llvm::BasicBlock*> labels_;
  llvm::AllocaInst *globals_ = nullptr, *counters_ = nullptr, *scratch_ = nullptr, *mask_words_ = nullptr,
                   *save_ = nullptr;
  llvm::Value *ctx_ = nullptr, *arrays_ = nullptr, *point_ = nullptr, *inputs_ = nullptr, *outputs_ = nullptr,
              *active_ = nullptr;
  int cur_ = 0;
};

// The one-point entry: the kernel inlined into a function that points its input and output
// lists at the caller's plain arrays and runs one group (1 lane) of it.
void add_point_entry(Shared& s, llvm::Function* kernel, uint32_t inputs, uint32_t outputs) {
  auto* t = llvm::FunctionType::get(s.i64, {s.ptr, s.ptr, s.ptr, s.i64}, false);
  auto* f = llvm::Function::Create(t, llvm::Function::ExternalLinkage, kPointSymbol, s.m);
  llvm::IRBuilder<> b(llvm::BasicBlock::Create(s.c, "entry", f));
  auto list = [&](llvm::Value* base, uint32_t n) {
    llvm::Value* l = b.CreateAlloca(s.ptr, b.getInt32(std::max(1u, n)));
    for (uint32_t k = 0; k < n; ++k)
      b.CreateStore(b.CreateConstInBoundsGEP1_64(s.f32, base, k), b.CreateConstInBoundsGEP1_64(s.ptr, l, k));
    return l;
  };
  llvm::Value *in = list(f->getArg(0), inputs), *out = list(f->getArg(1), outputs);
  b.CreateRet(b.CreateCall(kernel, {in, out, b.getInt64(0), b.getInt64(1), f->getArg(2), f->getArg(3)}));
  kernel->setLinkage(llvm::Function::InternalLinkage);
  kernel->addFnAttr(llvm::Attribute::AlwaysInline);
}

}  // namespace

Lowered::Lowered() = default;
Lowered::~Lowered() = default;
Lowered::Lowered(Lowered&&) noexcept = default;

bool lower_to_llvm(const ir::Module& module, uint32_t width, const backends::Budgets& budgets, bool bounded,
                   Lowered& out, std::string& error) {
  backends::JitProgram jp;
  if (!backends::prepare_program(module, jp, error)) return false;
  const ir::Module& m = *jp.module;
  int kernel = jp.kernel;
  out.context = std::make_unique<llvm::LLVMContext>();
  out.module = std::make_unique<llvm::Module>("fscript", *out.context);
  llvm::LLVMContext& c = *out.context;
  Shared s{c,
           *out.module,
           m,
           width,
           budgets,
           llvm::Type::getFloatTy(c),
           llvm::Type::getInt32Ty(c),
           llvm::Type::getInt64Ty(c),
           llvm::PointerType::get(c, 0),
           nullptr,
           nullptr,
           nullptr,
           nullptr,
           {},
           0,
           nullptr};
  s.vf = llvm::FixedVectorType::get(s.f32, width);
  s.vi = llvm::FixedVectorType::get(s.i32, width);
  s.vb = llvm::FixedVectorType::get(llvm::Type::getInt1Ty(c), width);
  s.mask_bits = llvm::IntegerType::get(c, static_cast<unsigned>(width));
  s.ctx = llvm::StructType::create(c, {s.ptr, s.ptr, s.ptr, s.i64, s.i64}, "fs_ctx");
  const std::vector<int>& fns = jp.functions;
  s.num_globals = jp.num_globals;
  s.fns.assign(m.functions.size(), nullptr);
  for (int f : fns) {
    const ir::Function& fn = *m.functions[static_cast<size_t>(f)];
    if (f == kernel) {
      auto* t = llvm::FunctionType::get(s.i64, {s.ptr, s.ptr, s.i64, s.i64, s.ptr, s.i64}, false);
      s.fns[static_cast<size_t>(f)] = llvm::Function::Create(t, llvm::Function::ExternalLinkage, kKernelSymbol, s.m);
      continue;
    }
    // The lanes' mask crosses calls as an integer: LLVM 19 with AVX-512 cannot copy an <N x i1>
    // argument between mask registers at a call ("Cannot emit physreg copy instruction").
    std::vector<llvm::Type*> params{s.ptr, s.ptr, s.mask_bits};
    params.insert(params.end(), fn.num_params, s.vf);
    auto* t = llvm::FunctionType::get(s.i64, params, false);
    s.fns[static_cast<size_t>(f)] = llvm::Function::Create(t, llvm::Function::InternalLinkage, "fs_fn_" + fn.name, s.m);
  }
  out.array_names = m.arrays;
  for (int f : fns) {
    const ir::Function& fn = *m.functions[static_cast<size_t>(f)];
    std::vector<ir::Range> ranges;
    if (f == kernel && bounded && (out.param_bound = ir::best_param_bound(fn)) > 0)
      ranges = ir::value_ranges(fn, out.param_bound);
    LlvmFunctionLowering(s, fn, s.fns[static_cast<size_t>(f)], f != kernel,
                         static_cast<uint32_t>(out.array_names.size()), std::move(ranges))
        .run();
    out.array_names.insert(out.array_names.end(), fn.arrays.begin(), fn.arrays.end());
    if (f == kernel) out.num_inputs = fn.num_params, out.num_outputs = fn.num_results;
  }
  if (out.point_entry) add_point_entry(s, s.fns[static_cast<size_t>(kernel)], out.num_inputs, out.num_outputs);
  return true;
}

}  // namespace fscript::llvmjit
