// SSA to WebAssembly (wasm_compile.h; the design in wasm_emitter.h): functions, masked control
// flow, straight code's speculation, and the module of the kernel and its callees.
#include "backends/wasm/wasm_compile.h"

#include <algorithm>
#include <climits>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/wasm/wasm_emitter.h"
#include "runtime/math/math.h"

namespace fscript::wasm {
namespace detail {

// The callee: one pass of the scan for its caller's lanes (the mask parameter), its value under
// the lanes' masks, and status 0.
bool Emitter::run_callee(std::string& error) {
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
                with_constants(c_));
  return true;
}

// A recursive function's own arrays belong to its activation (the VM's rule): entering saves
// their slots' state (backends::fs_lanes_enter, through scratch) into this activation's locals,
// leaving puts it back (an error return ends the run, arrays and all).
void Emitter::enter_arrays() {
  Code& c = c_;
  lanes_call(&backends::fs_lanes_enter);
  for (uint32_t k = 0; k < save_vectors(); ++k)
    c.local_get(scratch_), c.v128_load(program_.save_at + 16 * k), c.local_set(saved_ + k);
}

void Emitter::leave_arrays() {
  Code& c = c_;
  for (uint32_t k = 0; k < save_vectors(); ++k)
    c.local_get(scratch_), c.local_get(saved_ + k), c.v128_store(program_.save_at + 16 * k);
  lanes_call(&backends::fs_lanes_leave);
}

// Blocks in reverse post-order, each for its waiting lanes, again while lanes wait.
bool Emitter::scan(std::string& error) {
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

bool Emitter::run_kernel(std::string& error) {
  Code& c = c_;
  set_pointers();
  c.local_get(kN), c.i32_const(2), c.op(Opc::I32Shl), c.local_set(kEnd);
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
  uint32_t pointers = kFirstPointer - kAt + fn_.num_params + fn_.num_results + 1;  // trig_ok_
  auto locals = [&](uint32_t i32s) {
    return std::vector<std::pair<uint32_t, ValType>>{{i32s, ValType::I32},
                                                     {next_v128_ - first_v128_, ValType::V128},
                                                     {1, ValType::I64},
                                                     {num_constants(), ValType::V128}};
  };
  mod_.export_function("kernel", mod_.function(t, locals(pointers), with_constants(c_)));
  if (exact_index_) {  // (params: the kernel's and its group's offset, kAt)
    FuncType e{std::vector<ValType>(kAt + 1, ValType::I32), {}};
    uint32_t f = mod_.function(e, locals(pointers - 1), with_constants(exact_));
    if (f != exact_index_) return error = "the wasm emitter numbered its exact function wrongly", false;
  }
  return true;
}

void Emitter::set_pointers() {
  for (uint32_t k = 0; k < fn_.num_params; ++k) pointer(kIn, k, kFirstPointer + k);
  for (uint32_t k = 0; k < fn_.num_results; ++k) pointer(kOut, k, kFirstPointer + fn_.num_params + k);
}

void Emitter::store_outputs() {
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
bool Emitter::straight_block(std::string& error) {
  Code& c = c_;
  if (!speculate_) {
    if (!block(*rpo_[0], error)) return false;
    return store_outputs(), true;
  }
  c.block();  // done
  c.block();  // exact: the fast code's tests branch here
  fast_ = true;
  std::fill(made_early_.begin(), made_early_.end(), 0);
  if (bound_ > 0) inputs_in_bound(), c.op(Opc::I32Eqz), c.br_if(0);
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
  for (uint32_t k : {kIn, kOut, kN, kScratch, kArrays, kAt}) c.local_get(k);
  c.call(exact_index_ = program_.next_index++);
  c.end();
  // The exact code is a function of its own: the kernel's loop stays half the size, which the
  // engine optimises sooner, and the exact code, seldom run, stays in its baseline compiler.
  Code kernel = std::move(c_);
  c_ = Code();
  set_pointers();
  start_group();
  fast_ = false;
  std::fill(made_early_.begin(), made_early_.end(), 0);
  if (!block(*rpo_[0], error)) return false;
  store_outputs();
  exact_ = std::move(c_);
  c_ = std::move(kernel);
  return true;
}

// Whether every input of the group is within the bound the value ranges assume (|x| <= bound,
// or a row parameter's own range, ir::row_param_range), on the stack as an i32: the group's
// inputs read ahead of its code (a pass over the batch before the groups read every input from
// memory twice: 10% of csg8's time at 10^7 points). |x| <= bound as integers: the bits shifted
// left by one (the sign gone) at most the bound's, NaN and the infinities above it.
void Emitter::inputs_in_bound() {
  Code& c = c_;
  uint32_t widest = temp_, ranged = mask_, value = ticks_;  // (free before the group's code)
  bool any_widest = false, any_ranged = false;
  std::vector<bool> seen(fn_.num_params, false);
  for (const Inst* in : fn_.entry()->insts) {
    if (in->op != Op::Param || seen[static_cast<size_t>(in->aux)]) continue;
    seen[static_cast<size_t>(in->aux)] = true;
    const ir::ParamRange* r = ir::row_param_range(fn_, bound_, static_cast<uint32_t>(in->aux));
    const uint32_t pointer = kFirstPointer + static_cast<uint32_t>(in->aux);
    for (uint32_t k = 0; k < copies_; ++k) {
      auto load = [&] { c.local_get(pointer), c.local_get(kAt), c.op(Opc::I32Add), c.v128_load_any(16 * k); };
      if (!r) {
        load(), c.i32_const(1), c.simd(Simd::I32x4Shl);
        if (any_widest) c.local_get(widest), c.simd(Simd::I32x4MaxU);
        c.local_set(widest), any_widest = true;
        continue;
      }
      load(), c.local_set(value);
      c.local_get(value), f32(r->lo), c.simd(Simd::F32x4Ge);
      c.local_get(value), f32(r->hi), c.simd(Simd::F32x4Le), c.simd(Simd::V128And);
      if (r->nan) c.local_get(value), c.local_get(value), c.simd(Simd::F32x4Ne), c.simd(Simd::V128Or);
      if (any_ranged) c.local_get(ranged), c.simd(Simd::V128And);
      c.local_set(ranged), any_ranged = true;
    }
  }
  const float bound = static_cast<float>(bound_);
  uint32_t bound_bits;
  std::memcpy(&bound_bits, &bound, 4);
  if (any_widest)
    c.local_get(widest), i32(static_cast<int32_t>(bound_bits << 1)), c.simd(Simd::I32x4LeU), c.simd(Simd::I32x4AllTrue);
  if (any_ranged) c.local_get(ranged), c.simd(Simd::I32x4AllTrue);
  if (any_widest && any_ranged) c.op(Opc::I32And);
  if (!any_widest && !any_ranged) c.i32_const(1);
}

// What this emitter compiles (the rest runs on the VM until it does).
bool Emitter::check(std::string& error) {
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
void Emitter::speculation() {
  bound_ = ir::best_param_bound(fn_);
  if (bound_ > 0) ranges_ = ir::value_ranges(fn_, bound_);
  auto maybe_nan = [&](const Inst* v) { return ir::may_be_nan(v, ranges_); };
  for (const Inst* in : fn_.entry()->insts) switch (in->op) {
      case Op::Min:
      case Op::Max: checked_ |= maybe_nan(in->args[1]); break;
      case Op::Clamp: checked_ |= maybe_nan(in->args[1]) || maybe_nan(in->args[2]); break;
      default: break;
    }
  speculate_ = trig_used_ || checked_ || bound_ > 0;
}

// Reverse post-order from the entry.
void Emitter::order() {
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
void Emitter::layout() {
  trig_ok_ = kFirstPointer + fn_.num_params + fn_.num_results;  // (the kernel's i32s after its pointers)
  first_v128_ = next_v128_ = callee_ ? fn_.num_params + 4 : trig_ok_ + 1;
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

// Vector constants live in locals set once at the function's start (after the one i64 local)
// from mutable globals: the engine would otherwise build the vector again at every use inside
// the loop (a v128.const it takes for a constant, and a mutable global it cannot). Zero and
// all-ones stay inline, one instruction each.
void Emitter::vconst(const std::array<uint8_t, 16>& bytes) {
  bool zeros = true, ones = true;
  for (uint8_t b : bytes) zeros &= b == 0, ones &= b == 0xff;
  if (zeros || ones || callee_) return c_.v128_const(bytes.data());  // (a callee's frame stays small)
  auto [at, added] = constants_.try_emplace(bytes, static_cast<uint32_t>(constants_.size()));
  (void)added;
  c_.local_get(status_ + 1 + at->second);
}

Code Emitter::with_constants(const Code& body) {
  Code out;
  if (constant_globals_.size() != constants_.size()) {  // (once: the kernel and its exact function share them)
    constant_globals_.assign(constants_.size(), 0);
    for (const auto& [bytes, k] : constants_) constant_globals_[k] = mod_.global_v128(bytes);
  }
  for (uint32_t k = 0; k < constant_globals_.size(); ++k)
    out.global_get(constant_globals_[k]), out.local_set(status_ + 1 + k);
  out.append(body);
  return out;
}

void Emitter::start_group() {
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

// The block's instructions in order, each for every copy in turn (straight code's groups side
// by side: independent work the processor overlaps).
bool Emitter::block(const ir::Block& b, std::string& error) {
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

// A recursive function for this block's lanes: its depth checked (as the VM counts it), its
// status passed on, its value under the block's mask.
void Emitter::call_function(const Inst& in) {
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
void Emitter::trap(uint64_t code) {
  if (callee_) return f32(0), c_.i64_const(static_cast<int64_t>(code)), c_.op(Opc::Return);
  c_.local_get(kScratch), c_.i64_const(static_cast<int64_t>(code)), c_.i64_store(0);
  c_.i32_const(1), c_.op(Opc::Return);
}

void Emitter::pass_status() {
  if (callee_) return f32(0), c_.local_get(status_), c_.op(Opc::Return);
  c_.local_get(kScratch), c_.local_get(status_), c_.i64_store(0);
  c_.i32_const(1), c_.op(Opc::Return);
}

// One iteration per active lane; a lane past the budget ends the run with the loop's position.
// Where the program has callees the counts are in memory (scratch), one evaluation's for all of
// its functions, as the VM counts them.
void Emitter::tick(const Inst& in) {
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

void Emitter::branch(const Inst& in, const ir::Block& b) {
  Code& c = c_;
  truthy(in.args[0]);
  c.local_set(temp_);
  edge(b, *in.targets[0], [&] { c.local_get(temp_), c.local_get(mask_), c.simd(Simd::V128And); });
  edge(b, *in.targets[1], [&] { c.local_get(mask_), c.local_get(temp_), c.simd(Simd::V128AndNot); });
}

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

}  // namespace detail

namespace {

using namespace detail;

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
  p.next_index = static_cast<uint32_t>(out.imports.size() + jp.functions.size());
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
