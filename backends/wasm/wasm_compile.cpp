// SSA to WebAssembly (wasm_compile.h). Every value is a v128 local of four lanes; the engine that
// loads the module allocates registers. Lane operations are SIMD instructions that give
// runtime/math's bits (min and max with its NaN rule and its zero order, round with its sign,
// truthiness as "not 0 and not NaN"), sin and cos as runtime/math's batch functions compute them;
// the other Batch rows of ir/math_ops.def call the batch twin.
//
// Control flow is masked, as in the SSE emitter: blocks run in reverse post-order, each for the
// lanes waiting at it (skipped when none), under a scan that repeats while lanes wait (a back edge
// leaves its lanes waiting at an earlier block). Values, phis and globals are written under the
// block's mask, so a lane keeps what it computed where it last ran; phi moves are parallel copies
// on each edge under the edge's mask; the loop budget is a per-lane count. A kernel of one block
// without globals or ticks needs none of this and runs as straight-line code.
#include "backends/wasm/wasm_compile.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <map>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/wasm/wasm_encoder.h"
#include "ir/ranges.h"
#include "runtime/math/math.h"
#include "runtime/math/trig_constants.h"

namespace fscript::wasm {
namespace {

using ir::Inst;
using ir::Op;

// The kernel's parameters and fixed locals. A callee (a recursive function, called for the four
// lanes of its caller under the caller's mask) takes its arguments, the mask, scratch, arrays and
// its call depth, and returns its value and a status.
constexpr uint32_t kIn = 0, kOut = 1, kN = 2, kScratch = 3, kArrays = 4, kAt = 5, kEnd = 6, kFirstPointer = 7;
// Scratch: the arguments at 0, 16, 32, the result at 48, the lane mask at 64 (array helpers), then
// the globals where the program has callees (they share them).
constexpr uint32_t kScratchResult = 48, kScratchMask = 64, kScratchGlobals = 80;
// Straight code runs kCopies groups of four points side by side, the loop's body a chain of
// dependent operations (csg8's smooth unions) that one group alone leaves the processor waiting on.
constexpr uint32_t kCopies = 4;
// Speculating straight code stores a sin/cos pair's values per copy to scratch (straight_block).
constexpr uint32_t kScratchPins = 2 * 16 * kCopies;
// What recursion may take of the browser's stack, by frame_bytes() (V8's is about 984 KiB, the
// estimate about 1.2x the frames measured, and the VM's and the page's frames below the kernel
// take the rest): deeper budgets leave a recursive kernel to the VM.
constexpr size_t kStackForCalls = 768 << 10;

// What every function of the program shares: their indices, the imports, globals in memory.
struct Program {
  std::vector<uint32_t> index_of;  // wasm function index by the module's function index
  std::map<const void*, uint32_t> imports;
  bool globals_in_memory = false;
  int num_globals = 0;
  bool arrays = false;    // some function of the program has array operations
  uint32_t save_at = 0;   // scratch's room for a recursive function's saved array slots
};

const void* helper_of(Op op);
const void* batch_of(Op op);

class Emitter {
 public:
  Emitter(const ir::Module& m, const ir::Function& fn, bool callee, uint32_t first_slot, const backends::Budgets& b,
          Program& program, Module& mod)
      : module_(m), fn_(fn), callee_(callee), budgets_(b), program_(program), mod_(mod), first_slot_(first_slot) {
    uint32_t np = fn.num_params;
    scratch_ = callee ? np + 1 : kScratch, arrays_param_ = callee ? np + 2 : kArrays, depth_ = np + 3;
  }

  bool run(std::string& error) {
    if (!check(error)) return false;
    order();
    layout();
    return callee_ ? run_callee(error) : run_kernel(error);
  }
  uint32_t points_per_turn() const { return 4 * copies_; }
  // What a call of this function takes of the engine's stack, about: V8 spills every v128 local
  // (parameters among them) to a frame of about 20 bytes each (measured in Node), plus its own.
  size_t frame_bytes() const { return 20 * (next_v128_ - first_v128_ + num_constants() + fn_.num_params + 1) + 96; }

 private:
  // The callee: one pass of the scan for its caller's lanes (the mask parameter), its value under
  // the lanes' masks, and status 0.
  bool run_callee(std::string& error) {
    Code& c = c_;
    straight_ = false;
    for (const ir::Block* b : rpo_) {
      if (b == rpo_[0]) c.local_get(fn_.num_params);
      else i32(0);
      c.local_set(pending(*b));
    }
    f32(0), c.local_set(output_);
    if (!fn_.arrays.empty()) enter_arrays();
    if (!scan(error)) return false;
    if (!fn_.arrays.empty()) leave_arrays();
    c.local_get(output_), c.i64_const(0);
    std::vector<ValType> params(fn_.num_params + 1, ValType::V128);
    params.insert(params.end(), 3, ValType::I32);
    mod_.function({params, {ValType::V128, ValType::I64}},
                  {{next_v128_ - first_v128_, ValType::V128}, {1, ValType::I64}, {num_constants(), ValType::V128}},
                  with_constants());
    return true;
  }

  // A recursive function's own arrays belong to its activation (the VM's rule): entering saves
  // their slots' state (backends::fs_lanes_enter, through scratch) into this activation's locals,
  // leaving puts it back (an error return ends the run, arrays and all).
  void enter_arrays() {
    Code& c = c_;
    lanes_call(&backends::fs_lanes_enter);
    for (uint32_t k = 0; k < save_vectors(); ++k)
      c.local_get(scratch_), c.v128_load(program_.save_at + 16 * k), c.local_set(saved_ + k);
  }
  void leave_arrays() {
    Code& c = c_;
    for (uint32_t k = 0; k < save_vectors(); ++k)
      c.local_get(scratch_), c.local_get(saved_ + k), c.v128_store(program_.save_at + 16 * k);
    lanes_call(&backends::fs_lanes_leave);
  }
  template <typename Helper>
  void lanes_call(Helper* helper) {
    Code& c = c_;
    c.local_get(arrays_param_), c.i32_const(static_cast<int32_t>(first_slot_));
    c.i32_const(static_cast<int32_t>(fn_.arrays.size()));
    c.local_get(scratch_), c.i32_const(static_cast<int32_t>(program_.save_at)), c.op(Opc::I32Add);
    c.call(import(reinterpret_cast<const void*>(helper))), c.op(Opc::Drop);
  }
  // Four lanes' offset and length (int64) per array.
  uint32_t save_vectors() const { return 4 * static_cast<uint32_t>(fn_.arrays.size()); }

  // Blocks in reverse post-order, each for its waiting lanes, again while lanes wait.
  bool scan(std::string& error) {
    Code& c = c_;
    c.loop();
    for (const ir::Block* b : rpo_) {
      c.local_get(pending(*b)), c.simd(Simd::V128AnyTrue), c.if_();
      c.local_get(pending(*b)), c.local_set(mask_);
      i32(0), c.local_set(pending(*b));
      if (!block(*b, error)) return false;
      c.end();
    }
    for (size_t k = 0; k < rpo_.size(); ++k) {
      c.local_get(pending(*rpo_[k]));
      if (k) c.simd(Simd::V128Or);
    }
    c.simd(Simd::V128AnyTrue), c.br_if(0);
    c.end();
    return true;
  }

  bool run_kernel(std::string& error) {
    Code& c = c_;
    for (uint32_t k = 0; k < fn_.num_params; ++k) pointer(kIn, k, kFirstPointer + k);
    for (uint32_t k = 0; k < fn_.num_results; ++k) pointer(kOut, k, kFirstPointer + fn_.num_params + k);
    c.local_get(kN), c.i32_const(2), c.op(Opc::I32Shl), c.local_set(kEnd);
    if (bound_ > 0) inputs_in_bound();
    c.block();  // exit
    c.loop();   // one group of 4 x copies_ points a turn
    c.local_get(kAt), c.local_get(kEnd), c.op(Opc::I32GeU), c.br_if(1);
    start_group();
    if (straight_ ? !straight_block(error) : !scan(error)) return false;
    if (!straight_) store_outputs();
    c.local_get(kAt), c.i32_const(16 * static_cast<int32_t>(copies_)), c.op(Opc::I32Add), c.local_set(kAt);
    c.br(0);
    c.end();
    c.end();
    c.i32_const(0);
    FuncType t{{ValType::I32, ValType::I32, ValType::I32, ValType::I32, ValType::I32}, {ValType::I32}};
    uint32_t pointers = kFirstPointer - kAt + fn_.num_params + fn_.num_results + 2;  // trig_ok_, in_bound_
    uint32_t f = mod_.function(t,
                               {{pointers, ValType::I32},
                                {next_v128_ - first_v128_, ValType::V128},
                                {1, ValType::I64},
                                {num_constants(), ValType::V128}},
                               with_constants());
    mod_.export_function("kernel", f);
    return true;
  }

  void store_outputs() {
    Code& c = c_;
    for (uint32_t u = 0; u < copies_; ++u) {
      copy(u);
      for (uint32_t k = 0; k < fn_.num_results; ++k) {
        c.local_get(kFirstPointer + fn_.num_params + k), c.local_get(kAt), c.op(Opc::I32Add);
        c.local_get(output_ + k), c.v128_store_any(16 * u);
      }
    }
    copy(0);
  }

  // Straight code, speculating where it pays: the block's trig arguments in the fast range (tested
  // after each trig op) and the second operands of its min and max not NaN (the exact rules then
  // need no per-op test; their sum is tested at the end). A failed test runs the group again with
  // the exact code (straight code has no effects but its values: running it twice is safe).
  bool straight_block(std::string& error) {
    Code& c = c_;
    if (!speculate_) {
      if (!block(*rpo_[0], error)) return false;
      return store_outputs(), true;
    }
    c.block();  // done
    c.block();  // exact: the fast code's tests branch here
    fast_ = true;
    std::fill(made_early_.begin(), made_early_.end(), 0);
    if (bound_ > 0) c.local_get(in_bound_), c.op(Opc::I32Eqz), c.br_if(0);
    if (!block(*rpo_[0], error)) return false;
    store_outputs();  // (before the test: the engine then computes them ahead of it, not after)
    if (checked_) {
      for (uint32_t u = 0; u < copies_; ++u) {
        c.local_get(nan_sum_ + u), c.local_get(nan_sum_ + u), c.simd(Simd::F32x4Eq);
        if (u) c.simd(Simd::V128And);
      }
      c.simd(Simd::I32x4AllTrue), c.op(Opc::I32Eqz), c.br_if(0);
    }
    c.br(1);
    c.end();
    fast_ = false;
    std::fill(made_early_.begin(), made_early_.end(), 0);
    if (!block(*rpo_[0], error)) return false;
    store_outputs();
    c.end();
    return true;
  }

  // Whether every input of the batch is within the bound the value ranges assume (|x| <= bound,
  // or a row parameter's own range, ir::row_param_range), into in_bound_: one pass over the
  // inputs before the groups, a group's vectors a turn (a batch is whole groups), so the
  // groups' code tests nothing of its inputs. |x| <= bound as integers: the bits shifted left by
  // one (the sign gone) at most the bound's, NaN and the infinities above it.
  void inputs_in_bound() {
    Code& c = c_;
    uint32_t widest = temp_, ranged = mask_, value = ticks_;  // (free before the groups)
    i32(0), c.local_set(widest), i32(-1), c.local_set(ranged);
    std::vector<bool> seen(fn_.num_params, false);
    for (const Inst* in : fn_.entry()->insts) {
      if (in->op != Op::Param || seen[static_cast<size_t>(in->aux)]) continue;
      seen[static_cast<size_t>(in->aux)] = true;
      const ir::ParamRange* r = ir::row_param_range(fn_, bound_, static_cast<uint32_t>(in->aux));
      const uint32_t pointer = kFirstPointer + static_cast<uint32_t>(in->aux);
      c.i32_const(0), c.local_set(kAt);
      c.block(), c.loop();
      c.local_get(kAt), c.local_get(kEnd), c.op(Opc::I32GeU), c.br_if(1);
      for (uint32_t k = 0; k < copies_; ++k) {
        auto load = [&] { c.local_get(pointer), c.local_get(kAt), c.op(Opc::I32Add), c.v128_load_any(16 * k); };
        if (!r) {
          c.local_get(widest), load(), c.i32_const(1), c.simd(Simd::I32x4Shl), c.simd(Simd::I32x4MaxU);
          c.local_set(widest);
          continue;
        }
        load(), c.local_set(value);
        c.local_get(value), f32(r->lo), c.simd(Simd::F32x4Ge);
        c.local_get(value), f32(r->hi), c.simd(Simd::F32x4Le), c.simd(Simd::V128And);
        if (r->nan) c.local_get(value), c.local_get(value), c.simd(Simd::F32x4Ne), c.simd(Simd::V128Or);
        c.local_get(ranged), c.simd(Simd::V128And), c.local_set(ranged);
      }
      c.local_get(kAt), c.i32_const(16 * static_cast<int32_t>(copies_)), c.op(Opc::I32Add), c.local_set(kAt);
      c.br(0);
      c.end(), c.end();
    }
    const float bound = static_cast<float>(bound_);
    uint32_t bound_bits;
    std::memcpy(&bound_bits, &bound, 4);
    c.local_get(widest), i32(static_cast<int32_t>(bound_bits << 1)), c.simd(Simd::I32x4LeU);
    c.simd(Simd::I32x4AllTrue);
    c.local_get(ranged), c.simd(Simd::I32x4AllTrue), c.op(Opc::I32And), c.local_set(in_bound_);
    c.i32_const(0), c.local_set(kAt);
  }

  // What this emitter compiles (the rest runs on the VM until it does).
  bool check(std::string& error) {
    if (callee_ && fn_.num_results != 1) return error = "a function of several results", false;
    if (budgets_.max_loop_iterations > static_cast<uint64_t>(INT32_MAX - 1))
      return error = "a loop budget past 2^31 - 2", false;
    for (const auto& b : fn_.blocks)
      for (const Inst* in : b->insts) switch (in->op) {
          case Op::ANew:
          case Op::ALoad:
          case Op::AStore:
          case Op::ALen: arrays_ = true; break;
          case Op::Call:
          case Op::Tick:
          case Op::GLoad:
          case Op::GStore: straight_ = false; break;
          case Op::Sin:
          case Op::Cos: trig_used_ = true; break;
          default: break;
        }
    if (fn_.blocks.size() > 1) straight_ = false;
    if (straight_ && !arrays_) copies_ = kCopies;
    if (straight_ && !arrays_ && !callee_) speculation();
    return true;
  }

  // What straight code may guess (straight_block): inputs within the bound that removes the most
  // NaN tests (ir/ranges), trig arguments in the fast range; the min and max whose second operand
  // may still be NaN then keep a NaN sum (checked_).
  void speculation() {
    bound_ = ir::best_param_bound(fn_);
    if (bound_ > 0) ranges_ = ir::value_ranges(fn_, bound_);
    fast_ = true;
    for (const Inst* in : fn_.entry()->insts) switch (in->op) {
        case Op::Min:
        case Op::Max: checked_ |= !never_nan(in->args[1]); break;
        case Op::Clamp: checked_ |= !never_nan(in->args[1]) || !never_nan(in->args[2]); break;
        default: break;
      }
    fast_ = false;
    speculate_ = trig_used_ || checked_ || bound_ > 0;
  }

  // Reverse post-order from the entry.
  void order() {
    std::vector<char> seen(fn_.next_block + 1, 0);
    std::vector<const ir::Block*> post;
    std::vector<std::pair<const ir::Block*, size_t>> stack = {{fn_.entry(), 0}};
    seen[fn_.entry()->id] = 1;
    while (!stack.empty()) {
      auto& [b, k] = stack.back();
      auto succs = b->succs();
      if (k < succs.size()) {
        const ir::Block* s = succs[k++];
        if (!seen[s->id]) seen[s->id] = 1, stack.push_back({s, 0});
        continue;
      }
      post.push_back(b);
      stack.pop_back();
    }
    rpo_.assign(post.rbegin(), post.rend());
  }

  // v128 locals: the values made, outputs, globals, the mask, the loop counter, pending masks, temps.
  void layout() {
    trig_ok_ = kFirstPointer + fn_.num_params + fn_.num_results;  // (the kernel's i32s after its pointers)
    in_bound_ = trig_ok_ + 1;
    first_v128_ = next_v128_ = callee_ ? fn_.num_params + 4 : in_bound_ + 1;
    local_of_.assign(fn_.next_value, 0);
    for (const auto& b : fn_.blocks)
      for (const Inst* in : b->insts)
        if (has_value(in->op)) local_of_[in->id] = num_values_++;
    value_ = take(num_values_ * copies_);
    output_ = take(fn_.num_results * copies_);
    global_ = take(program_.globals_in_memory ? 0 : static_cast<uint32_t>(program_.num_globals));
    mask_ = take(1);
    ticks_ = take(1);
    temp_ = take(copies_);
    pending_ = take(static_cast<uint32_t>(rpo_.size()));
    rpo_index_.assign(fn_.next_block + 1, 0);
    for (size_t k = 0; k < rpo_.size(); ++k) rpo_index_[rpo_[k]->id] = static_cast<uint32_t>(k);
    size_t phis = 0;
    for (const auto& b : fn_.blocks) phis = std::max(phis, b->first_non_phi());
    phi_temp_ = take(static_cast<uint32_t>(phis));
    trig_ = take(trig_used_ ? kTrigLocals * copies_ : 0);
    nan_sum_ = take(speculate_ ? copies_ : 0);
    saved_ = take(callee_ ? save_vectors() : 0);
    base_ = {value_, output_, temp_, trig_};
    made_early_.assign(fn_.next_value, 0);
    status_ = next_v128_;  // the one i64 local, after the v128 ones
  }
  // Vector constants live in locals set once at the function's start (after the one i64 local):
  // the engine would otherwise build the vector again at every use inside the loop. Zero and
  // all-ones stay inline, one instruction each.
  void vconst(const std::array<uint8_t, 16>& bytes) {
    bool zeros = true, ones = true;
    for (uint8_t b : bytes) zeros &= b == 0, ones &= b == 0xff;
    if (zeros || ones || callee_) return c_.v128_const(bytes.data());  // (a callee's frame stays small)
    auto [at, added] = constants_.try_emplace(bytes, static_cast<uint32_t>(constants_.size()));
    (void)added;
    c_.local_get(status_ + 1 + at->second);
  }
  template <typename T>
  void splat(T v) {
    std::array<uint8_t, 16> b;
    for (size_t k = 0; k < 16; k += sizeof v) std::memcpy(b.data() + k, &v, sizeof v);
    vconst(b);
  }
  void f32(float v) { splat(v); }
  void i32(int32_t v) { splat(v); }
  void f64(double v) { splat(v); }
  uint32_t num_constants() const { return static_cast<uint32_t>(constants_.size()); }
  // The constants' locals set, then the body.
  Code with_constants() {
    Code out;
    for (const auto& [bytes, k] : constants_) out.global_get(mod_.global_v128(bytes)), out.local_set(status_ + 1 + k);
    out.append(c_);
    return out;
  }

  // Copy u of the straight code's values: the locals of values, outputs, temp and trig's move to
  // its own (copy 0's are the layout's).
  void copy(uint32_t u) {
    value_ = base_[0] + u * num_values_, output_ = base_[1] + u * fn_.num_results;
    temp_ = base_[2] + u, trig_ = base_[3] + u * kTrigLocals;
    u_ = u;
  }

  // A value's local (a recursive function's frame holds every local: only values that are made
  // have one).
  uint32_t val(const Inst* v) const { return value_ + local_of_[v->id]; }
  static bool has_value(Op op) {
    return op != Op::Const && op != Op::GStore && op != Op::Tick && op != Op::Jump && op != Op::Branch &&
        op != Op::Ret && op != Op::ANew && op != Op::AStore;
  }

  uint32_t take(uint32_t n) {
    uint32_t first = next_v128_;
    next_v128_ += n;
    return first;
  }
  uint32_t pending(const ir::Block& b) const { return pending_ + rpo_index_[b.id]; }

  // Local `dst` = the k-th pointer of the array at param `array`.
  void pointer(uint32_t array, uint32_t k, uint32_t dst) { c_.local_get(array), c_.i32_load(4 * k), c_.local_set(dst); }

  void start_group() {
    Code& c = c_;
    for (uint32_t k = 0; k < fn_.num_results; ++k) f32(0), c.local_set(output_ + k);
    i32(-1), c.local_set(mask_);
    if (program_.arrays) {  // every array of every lane gone: a new evaluation
      c.local_get(kArrays), c.call(import(reinterpret_cast<const void*>(&backends::fs_lanes_reset)));
      c.op(Opc::Drop);
    }
    if (straight_) {
      for (uint32_t u = 0; speculate_ && u < copies_; ++u) f32(0), c.local_set(nan_sum_ + u);
      return;
    }
    for (const ir::Block* b : rpo_) i32(b == rpo_[0] ? -1 : 0), c.local_set(pending(*b));
    for (int g = 0; g < program_.num_globals; ++g) {
      if (!program_.globals_in_memory) {
        f32(__builtin_nanf("")), c.local_set(global_ + static_cast<uint32_t>(g));
        continue;
      }
      c.local_get(kScratch), f32(__builtin_nanf("")), c.v128_store(kScratchGlobals + 16 * static_cast<uint32_t>(g));
    }
    if (program_.globals_in_memory) c.local_get(kScratch), i32(0), c.v128_store(ticks_at());
    else i32(0), c.local_set(ticks_);
  }

  void push(const Inst* v) {
    if (v->op == Op::Const) f32(v->imm);
    else c_.local_get(val(v));
  }
  // The value on the stack into `local`, under the block's mask where control flow is masked.
  void assign(uint32_t local) {
    if (!straight_) c_.local_get(local), c_.local_get(mask_), c_.simd(Simd::V128Bitselect);
    c_.local_set(local);
  }
  void simd2(Simd s, const Inst& in) { push(in.args[0]), push(in.args[1]), c_.simd(s); }
  // The lanes where `v` is truthy (not 0, not NaN), as a mask.
  void truthy(const Inst* v) {
    push(v), f32(0), c_.simd(Simd::F32x4Ne);
    if (!never_nan(v)) push(v), push(v), c_.simd(Simd::F32x4Eq), c_.simd(Simd::V128And);
  }
  void one_where_mask() { f32(1), c_.simd(Simd::V128And); }  // mask -> 1.0 or 0.0

  // The block's instructions in order, each for every copy in turn (straight code's groups side
  // by side: independent work the processor overlaps).
  bool block(const ir::Block& b, std::string& error) {
    trig_uses_.clear();
    for (size_t k = 0; k < b.insts.size(); ++k)
      if (b.insts[k]->op == Op::Sin || b.insts[k]->op == Op::Cos) trig_uses_[b.insts[k]->args[0]].push_back(k);
    for (size_t k = 0; k < b.insts.size(); ++k) {
      const Inst& in = *b.insts[k];
      if (made_early_[in.id]) continue;
      if (in.op == Op::Sin || in.op == Op::Cos) {  // (all copies at once)
        partner_ = trig_partner(in, b, k);
        trig(in);
        if (partner_) made_early_[partner_->id] = 1;
        continue;
      }
      for (uint32_t u = 0; u < copies_; ++u) {
        copy(u);
        if (!inst(in, b, error)) return false;
      }
      copy(0);
    }
    return true;
  }

  // One instruction: every op is named (no default), so a new op fails the build until it is here.
  bool inst(const Inst& in, const ir::Block& b, std::string& error) {
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

  // math::min/max: b < a ? b : a (a where a is NaN; pmin's rule, pmax's for max), then b where b is
  // NaN: the zeros' order and the NaN rule exactly (the IEEE min would give -0 for min(+0, -0)).
  // Where b cannot be NaN (a constant) pmin is the rule; speculating, b joins the group's NaN sum.
  void min_max(bool min, const Inst* a, const Inst* b) { push(a), min_max_tail(min, b); }
  // min(temp, hi) with the same rule, `temp` holding the first operand.
  void min_max_with_temp(const Inst* hi) { c_.local_get(temp_), min_max_tail(true, hi); }
  // The first operand on the stack.
  void min_max_tail(bool min, const Inst* b) {
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
  // Speculating, by the value ranges under the input bound; otherwise constants only.
  bool never_nan(const Inst* v) const { return !ir::may_be_nan(v, fast_ ? ranges_ : no_ranges_); }
  // f = floor(a); a - f >= 0.5 ? f + 1 : f, then a's sign.
  void round(const Inst* a) {
    Code& c = c_;
    push(a), c.simd(Simd::F32x4Floor), c.local_set(temp_);
    c.local_get(temp_), f32(1), c.simd(Simd::F32x4Add), c.local_get(temp_);
    push(a), c.local_get(temp_), c.simd(Simd::F32x4Sub), f32(0.5f), c.simd(Simd::F32x4Ge);
    c.simd(Simd::V128Bitselect);
    i32(INT32_MAX), c.simd(Simd::V128And);
    push(a), i32(INT32_MIN), c.simd(Simd::V128And), c.simd(Simd::V128Or);
  }
  // a > 0 ? 1 : (a < 0 ? -1 : a)
  void sign(const Inst* a) {
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
  void trig(const Inst& in) {
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
  const Inst* trig_partner(const Inst& in, const ir::Block& b, size_t pos) const {
    Op want = in.op == Op::Sin ? Op::Cos : Op::Sin;
    for (size_t k : trig_uses_.at(in.args[0]))
      if (k > pos && b.insts[k]->op == want && !made_early_[b.insts[k]->id]) return b.insts[k];
    return nullptr;
  }
  // Lanes 0-1 (half 0) or 2-3 of x in double: j = round(x 2/pi) by adding and taking away 1.5 2^52,
  // r = x - j pi/2 in two parts, then r to float in the half's low two lanes, and the sum with the
  // magic number kept: its low 32 bits are j as an int32 (the quadrant).
  void reduce_half(int half, uint32_t r_out, uint32_t q_out) {
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
  void trig_polynomials() {
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
  void quadrant_masks() {
    Code& c = c_;
    c.local_get(trig_ + kQ), c.i32_const(31), c.simd(Simd::I32x4Shl), c.local_tee(trig_ + kQ31);
    c.i32_const(31), c.simd(Simd::I32x4ShrS);
    c.local_get(trig_ + kSin), c.local_get(trig_ + kCos), c.simd(Simd::V128Xor), c.simd(Simd::V128And);
    c.local_get(trig_ + kQ), c.i32_const(1), c.simd(Simd::I32x4ShrU), c.i32_const(31), c.simd(Simd::I32x4Shl);
    c.simd(Simd::V128Xor), c.local_set(trig_ + kFlip);
  }
  // sin in quadrant q + offset (cos x = sin(x + pi/2)).
  void quadrant_value(int offset) {
    Code& c = c_;
    c.local_get(trig_ + (offset ? kCos : kSin)), c.local_get(trig_ + kFlip), c.simd(Simd::V128Xor);
    if (offset) c.local_get(trig_ + kQ31), c.simd(Simd::V128Xor);
  }

  // A runtime batch function on the four lanes, through the scratch area.
  void batch(const Inst& in, const void* fn) {  // (fn: batch_of(in.op), declared by declare_imports)
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
  void array_op(const Inst& in) {
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

  uint32_t import(const void* fn) const { return program_.imports.at(fn); }
  uint32_t global_at(const Inst& in) const { return kScratchGlobals + 16 * static_cast<uint32_t>(in.aux); }
  uint32_t ticks_at() const { return kScratchGlobals + 16 * static_cast<uint32_t>(program_.num_globals); }

  // A recursive function for this block's lanes: its depth checked (as the VM counts it), its
  // status passed on, its value under the block's mask.
  void call_function(const Inst& in) {
    Code& c = c_;
    const ir::Function& callee = *module_.functions[static_cast<size_t>(in.aux)];
    auto depth = [&] { callee_ ? c.local_get(depth_) : c.i32_const(0); };
    if (callee.recursive) {
      depth(), c.i32_const(static_cast<int32_t>(std::min<uint64_t>(budgets_.max_call_depth, INT32_MAX))),
          c.op(Opc::I32GeU);
      c.if_(), trap(backends::trap_code(3, &in)), c.end();
    }
    for (const Inst* a : in.args) push(a);
    c.local_get(mask_), c.local_get(scratch_), c.local_get(arrays_param_);
    depth();
    if (callee.recursive) c.i32_const(1), c.op(Opc::I32Add);
    c.call(program_.index_of[static_cast<size_t>(in.aux)]);
    c.local_set(status_), c.local_set(temp_);
    c.local_get(status_), c.op(Opc::I64Eqz), c.op(Opc::I32Eqz), c.if_(), pass_status(), c.end();
    c.local_get(temp_);
  }
  // A callee returns (any value, status); the kernel stores the status at scratch's start and
  // returns 1 (no 64-bit value crosses into JavaScript, where it would be a BigInt).
  void trap(uint64_t code) {
    if (callee_) return f32(0), c_.i64_const(static_cast<int64_t>(code)), c_.op(Opc::Return);
    c_.local_get(kScratch), c_.i64_const(static_cast<int64_t>(code)), c_.i64_store(0);
    c_.i32_const(1), c_.op(Opc::Return);
  }
  void pass_status() {
    if (callee_) return f32(0), c_.local_get(status_), c_.op(Opc::Return);
    c_.local_get(kScratch), c_.local_get(status_), c_.i64_store(0);
    c_.i32_const(1), c_.op(Opc::Return);
  }

  // One iteration per active lane; a lane past the budget ends the run with the loop's position.
  // Where the program has callees the counts are in memory (scratch), one evaluation's for all of
  // its functions, as the VM counts them.
  void tick(const Inst& in) {
    Code& c = c_;
    const uint32_t at = ticks_at();
    if (program_.globals_in_memory) c.local_get(scratch_), c.local_get(scratch_), c.v128_load(at);
    else c.local_get(ticks_);
    c.local_get(mask_), c.simd(Simd::I32x4Sub), c.local_tee(temp_);
    if (program_.globals_in_memory) c.v128_store(at);
    else c.local_set(ticks_);
    c.local_get(temp_), i32(static_cast<int32_t>(budgets_.max_loop_iterations)), c.simd(Simd::I32x4GtS);
    c.simd(Simd::V128AnyTrue), c.if_(), trap(backends::trap_code(1, &in)), c.end();
  }

  // The lanes of `edge_mask` (pushed by the function) go from `from` to `to`: its phis take their
  // operands from `from` (all read before any is written), and the lanes wait at `to`.
  template <typename PushMask>
  void edge(const ir::Block& from, const ir::Block& to, PushMask edge_mask) {
    Code& c = c_;
    size_t phis = to.first_non_phi(), pred = 0;
    while (pred < to.preds.size() && to.preds[pred] != &from) ++pred;
    for (size_t k = 0; k < phis; ++k) {
      const Inst* phi = to.insts[k];
      push(phi->args[pred]), c.local_get(val(phi)), edge_mask(), c.simd(Simd::V128Bitselect);
      c.local_set(phi_temp_ + static_cast<uint32_t>(k));
    }
    for (size_t k = 0; k < phis; ++k) c.local_get(phi_temp_ + static_cast<uint32_t>(k)), c.local_set(val(to.insts[k]));
    c.local_get(pending(to)), edge_mask(), c.simd(Simd::V128Or), c.local_set(pending(to));
  }

  void branch(const Inst& in, const ir::Block& b) {
    Code& c = c_;
    truthy(in.args[0]);
    c.local_set(temp_);
    edge(b, *in.targets[0], [&] { c.local_get(temp_), c.local_get(mask_), c.simd(Simd::V128And); });
    edge(b, *in.targets[1], [&] { c.local_get(mask_), c.local_get(temp_), c.simd(Simd::V128AndNot); });
  }

  const ir::Module& module_;
  const ir::Function& fn_;
  bool callee_;
  const backends::Budgets& budgets_;
  Program& program_;
  Module& mod_;
  Code c_;
  bool straight_ = true, arrays_ = false, trig_used_ = false;
  // Straight code speculates (straight_block) where it has trig or a min or max whose second
  // operand may be NaN (checked_); fast_ while its speculating copy is written.
  bool checked_ = false, speculate_ = false, fast_ = false;
  uint32_t scratch_ = 0, arrays_param_ = 0, depth_ = 0;  // parameters' locals
  std::vector<const ir::Block*> rpo_;
  uint32_t first_v128_ = 0, next_v128_ = 0, value_ = 0, output_ = 0, global_ = 0, mask_ = 0, ticks_ = 0, temp_ = 0;
  uint32_t pending_ = 0, phi_temp_ = 0, status_ = 0, trig_ = 0, saved_ = 0;
  uint32_t nan_sum_ = 0, trig_ok_ = 0, in_bound_ = 0;
  double bound_ = 0;  // speculating: the inputs' bound (0: none)
  std::vector<ir::Range> ranges_,
      no_ranges_;  // the value ranges under bound_; none  // per copy: the sum of min's and max's second operands (speculating)
  uint32_t first_slot_ = 0;  // this function's own arrays' first slot
  std::vector<uint32_t> local_of_;  // value id -> its number among the values made
  std::vector<uint32_t> rpo_index_;  // block id -> its place in rpo_
  uint32_t num_values_ = 0;
  uint32_t copies_ = 1, u_ = 0;
  std::array<uint32_t, 4> base_{};  // copy 0's value, output, temp and trig locals
  const Inst* partner_ = nullptr;  // the later trig op the current one makes too
  // sin and cos's locals, from trig_: the argument, a half in double, its j, the halves' r and q,
  // the joined r and q, z = r r, the two polynomials, q << 31, the flip (quadrant_masks).
  enum : uint32_t { kX, kD, kJ, kRLo, kQLo, kRHi, kQHi, kR, kQ, kZ, kSin, kCos, kQ31, kFlip, kTrigLocals };
  std::map<const Inst*, std::vector<size_t>> trig_uses_;  // this block's sin and cos by argument
  std::vector<char> made_early_;  // values made ahead (a trig pair's second)
  std::map<std::array<uint8_t, 16>, uint32_t> constants_;  // vector constant -> its number
};

// The runtime function an array op calls.
const void* helper_of(Op op) {
  switch (op) {
    case Op::ANew: return reinterpret_cast<const void*>(&backends::fs_lanes_anew);
    case Op::ALoad: return reinterpret_cast<const void*>(&backends::fs_lanes_aload);
    case Op::AStore: return reinterpret_cast<const void*>(&backends::fs_lanes_astore);
    default: return reinterpret_cast<const void*>(&backends::fs_lanes_alen);  // ALen
  }
}

// The batch function a math op calls (nullptr: it is made of SIMD instructions).
const void* batch_of(Op op) {
  switch (op) {
    case Op::Mod: return reinterpret_cast<const void*>(&backends::mod_batch);
#define FS_MATH(N, FN, A, HOW) FS_WASM_BATCH_##HOW(N, FN)
#define FS_WASM_BATCH_Lane(N, FN)
#define FS_WASM_BATCH_Batch(N, FN) \
  case Op::N: return reinterpret_cast<const void*>(&math::FN##_batch);
#define FS_WASM_BATCH_Trig(N, FN) FS_WASM_BATCH_Batch(N, FN)
#include "ir/math_ops.def"
#undef FS_WASM_BATCH_Lane
#undef FS_WASM_BATCH_Batch
#undef FS_WASM_BATCH_Trig
    default: return nullptr;
  }
}

// Every import the program's functions call, in the order first met: imports precede the module's
// own functions in its index space, so all are declared before any body.
void declare_imports(const backends::JitProgram& jp, Program& p, Module& mod, CompiledModule& out) {
  auto add = [&](const void* fn, size_t params, bool returns) {
    if (!fn || p.imports.count(fn)) return;
    FuncType t{std::vector<ValType>(params, ValType::I32), {}};
    if (returns) t.results.push_back(ValType::I32);
    p.imports[fn] = mod.import_function("env", "f" + std::to_string(out.imports.size()), t);
    out.imports.push_back(fn);
  };
  for (int f : jp.functions) {
    const ir::Function& fn = *jp.module->functions[static_cast<size_t>(f)];
    if (f != jp.kernel && !fn.arrays.empty())
      for (const void* h : {reinterpret_cast<const void*>(&backends::fs_lanes_enter),
                            reinterpret_cast<const void*>(&backends::fs_lanes_leave)})
        add(h, 4, true);
    for (const auto& b : fn.blocks)
      for (const Inst* in : b->insts) {
        const bool array = in->op == Op::ANew || in->op == Op::ALoad || in->op == Op::AStore || in->op == Op::ALen;
        if (array) {
          p.arrays = true;
          add(reinterpret_cast<const void*>(&backends::fs_lanes_reset), 1, true);
          add(helper_of(in->op), in->op == Op::ALoad || in->op == Op::AStore ? 5 : 4, true);
        }
        if (const void* batch = batch_of(in->op)) add(batch, in->args.size() + 2, false);
      }
  }
}

}  // namespace

bool compile_module(const ir::Module& m, const backends::Budgets& budgets, CompiledModule& out, std::string& error) {
  backends::JitProgram jp;
  if (!backends::prepare_program(m, jp, error)) return false;
  const ir::Module& pm = *jp.module;
  const ir::Function& fn = *pm.functions[static_cast<size_t>(jp.kernel)];
  out = CompiledModule{};
  out.inputs = fn.num_params, out.outputs = fn.num_results, out.row_from = fn.row_params_from;
  Module mod;
  mod.import_memory("env", "memory", 1);
  Program p;
  declare_imports(jp, p, mod, out);
  p.num_globals = jp.num_globals;
  p.globals_in_memory = jp.functions.size() > 1;  // the callees share them
  p.index_of.assign(pm.functions.size(), 0);
  for (size_t k = 0; k < jp.functions.size(); ++k)
    p.index_of[static_cast<size_t>(jp.functions[k])] = static_cast<uint32_t>(out.imports.size() + k);
  // Slots: the global arrays, then each function's own (the SSE emitter's layout).
  out.array_names = pm.arrays;
  size_t most_saved = 0;
  for (size_t k = 1; k < jp.functions.size(); ++k)
    most_saved = std::max(most_saved, pm.functions[static_cast<size_t>(jp.functions[k])]->arrays.size());
  p.save_at = kScratchGlobals + 16 * static_cast<uint32_t>(jp.num_globals) + 16;  // after the loop counts
  out.scratch_bytes = std::max<size_t>(p.save_at + 64 * most_saved, kScratchPins);
  for (size_t k = 0; k < jp.functions.size(); ++k) {  // the kernel first, then its callees
    const ir::Function& f = *pm.functions[static_cast<size_t>(jp.functions[k])];
    Emitter e(pm, f, k > 0, static_cast<uint32_t>(out.array_names.size()), budgets, p, mod);
    out.array_names.insert(out.array_names.end(), f.arrays.begin(), f.arrays.end());
    if (!e.run(error)) return false;
    if (k == 0) out.group = e.points_per_turn();
    if (k > 0 && e.frame_bytes() * budgets.max_call_depth > kStackForCalls)
      return error = std::to_string(budgets.max_call_depth) + " nested calls of `" + f.name + "` (frames of about " +
                 std::to_string(e.frame_bytes()) + " bytes) could outgrow the browser's stack (about " +
                 std::to_string(kStackForCalls >> 10) + " KiB for them)",
             false;
  }
  out.bytes = mod.encode();
  return true;
}

}  // namespace fscript::wasm
