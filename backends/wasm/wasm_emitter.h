#pragma once
// The wasm emitter's Emitter, shared by wasm_compile.cpp (functions, control flow, straight code's
// speculation, the module) and wasm_emit_lanes.cpp (each op as SIMD instructions, sin and cos).
//
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
//
// Straight code speculates (straight_block): the batch's inputs within the bound under which the
// value ranges (ir/ranges) drop NaN tests, trig arguments in the fast range, the second operands
// of min and max not NaN otherwise; a group whose guess fails runs again with the exact code.
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/wasm/wasm_encoder.h"
#include "ir/ir.h"
#include "ir/ranges.h"

namespace fscript::wasm::detail {

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
  uint32_t next_index = 0;  // the next function index after the program's own (a kernel's exact code)
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
  // The function's frame, its groups and blocks, straight code's speculation (wasm_compile.cpp).
  bool run_callee(std::string& error);

  void enter_arrays();
  void leave_arrays();
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
  bool scan(std::string& error);
  bool run_kernel(std::string& error);
  void store_outputs();
  bool straight_block(std::string& error);
  void inputs_in_bound();
  bool check(std::string& error);
  void speculation();
  void order();
  void layout();
  void vconst(const std::array<uint8_t, 16>& bytes);
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
  Code with_constants(const Code& body);  // the constants' locals set, then the body
  void set_pointers();

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
  void start_group();
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
  bool block(const ir::Block& b, std::string& error);

  // Each op as SIMD instructions (wasm_emit_lanes.cpp).
  bool inst(const Inst& in, const ir::Block& b, std::string& error);

  // math::min/max: b < a ? b : a (a where a is NaN; pmin's rule, pmax's for max), then b where b is
  // NaN: the zeros' order and the NaN rule exactly (the IEEE min would give -0 for min(+0, -0)).
  // Where b cannot be NaN (a constant) pmin is the rule; speculating, b joins the group's NaN sum.
  void min_max(bool min, const Inst* a, const Inst* b) { push(a), min_max_tail(min, b); }
  // min(temp, hi) with the same rule, `temp` holding the first operand.
  void min_max_with_temp(const Inst* hi) { c_.local_get(temp_), min_max_tail(true, hi); }
  void min_max_tail(bool min, const Inst* b);
  // Speculating, by the value ranges under the input bound; otherwise constants only.
  bool never_nan(const Inst* v) const { return !ir::may_be_nan(v, fast_ ? ranges_ : no_ranges_); }
  void round(const Inst* a);
  void sign(const Inst* a);

  void trig(const Inst& in);
  const Inst* trig_partner(const Inst& in, const ir::Block& b, size_t pos) const;
  void reduce_half(int half, uint32_t r_out, uint32_t q_out);
  void trig_polynomials();
  void quadrant_masks();
  void quadrant_value(int offset);

  void batch(const Inst& in, const void* fn);  // (fn: batch_of(in.op), declared by declare_imports)
  // An array operation through backends/lane_arrays.h's helpers (the VM's storage and messages):
  // the arrays, the slot, the operands' and result's places, the lanes' mask; a helper's 1 ends the
  // run with its message.
  void array_op(const Inst& in);

  uint32_t import(const void* fn) const { return program_.imports.at(fn); }
  uint32_t global_at(const Inst& in) const { return kScratchGlobals + 16 * static_cast<uint32_t>(in.aux); }
  uint32_t ticks_at() const { return kScratchGlobals + 16 * static_cast<uint32_t>(program_.num_globals); }

  void call_function(const Inst& in);
  void trap(uint64_t code);
  void pass_status();
  void tick(const Inst& in);
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
  void branch(const Inst& in, const ir::Block& b);
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
  // Speculating: per copy, the sum of min's and max's second operands; whether a trig op's
  // arguments are in the fast range.
  uint32_t nan_sum_ = 0, trig_ok_ = 0;
  double bound_ = 0;  // speculating: the inputs' bound (0: none)
  std::vector<ir::Range> ranges_, no_ranges_;  // the value ranges under bound_; none
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
  std::vector<uint32_t> constant_globals_;                  // its number -> its global
  Code exact_;                // speculating straight code's exact group, a function of its own
  uint32_t exact_index_ = 0;  // that function's index (0: none)
};

}  // namespace fscript::wasm::detail
