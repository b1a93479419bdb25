// SSA to x86-64, four points per iteration, one value per xmm register (eight per ymm register
// for a straight-line kernel where the CPU has AVX2: see try_wide). Within a block, registers
// are assigned while emitting: a free one if there is one, else the value whose next use in the
// block is farthest is spilled to a stack slot of the lanes' width (Belady's rule); spilled values and
// constants (rip-relative, from the pool) are read straight from memory. xmm0 and xmm1 are
// scratch (xmm0 is blendvps's implicit mask). Where the CPU has AVX, arithmetic, min/max and the
// sign operations take VEX's three-operand forms, which need no copy of a live first operand.
// Runtime calls (transcendentals, fmod, noise) go through runtime/math's batch functions on the
// code's lanes in stack slots, every live register saved.
//
// Control flow is masked, as in the VM: each block has a pending mask of the lanes waiting at it;
// blocks run in reverse post-order, each for its pending lanes (skipped when none), and a back
// edge that carried lanes jumps back to its target; the scan repeats until no lane waits. Values
// used outside their block, phis and globals live in 16-byte home slots written under the
// block's lane mask; phi moves are parallel copies on each edge under the edge's mask; loop
// budgets are per-lane counters. A straight-line kernel without globals or ticks needs none of
// this and runs as one pass.
#include <algorithm>
#include <climits>
#include <cstring>
#include <map>

#include "backends/jit_support.h"
#include "backends/sse/sse_compile_lanes.h"
#include "backends/sse/sse_backend.h"
#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "runtime/math/isa.h"
#include "runtime/math/math.h"
#include "runtime/support/cancel.h"

namespace fscript::sse {
namespace {

using namespace detail;

// The functions compiled into one piece of code: the kernel first (the code's start), then every
// function it calls, directly or not. Calls left after inlining are of recursive functions.
struct Program {
  const ir::Module& module;
  std::vector<Label> entries;  // by function index
  int num_globals = 0;         // global slots in the kernel's frame, for every function
  uint32_t max_call_depth = 0;
};

// The kernel loops over groups of four points. A called function (callee mode) runs once for
// the four lanes of its caller, under the caller's lane mask: rbx holds its arguments (16 bytes
// each), r12 where its result goes, rbp the kernel's call context. Recursion is thus packed: the
// lanes recurse together, each only as deep as its own path, as the VM's lane-by-lane calls do.
class Codegen : public detail::LaneCode {
 public:
  Codegen(const ir::Function& fn, Assembler& a, const backends::Budgets& budgets, uint32_t local_arrays,
          const Program& program, int index, bool callee)
      : LaneCode(fn, a, static_cast<int32_t>(std::min<uint64_t>(budgets.max_loop_iterations, kCarryAt)), local_arrays,
                 callee),
        program_(program), placeholder_(kPlaceholder + index), loop_budget_(budgets.max_loop_iterations) {}

  bool run(std::string& error) {
    if (!layout(error)) return false;
    if (!straight_) a_.refuse_wide("masked control flow");  // its masks and slots are four lanes
    exit_ = a_.new_label();
    prologue();
    Label top = a_.new_label(), done = a_.new_label();
    for (size_t b = 0; b <= order_.size(); ++b) block_label_.push_back(a_.new_label());
    if (!callee_) {
      a_.bind(top);
      a_.cmp(Gp::r13, Gp::r14);
      a_.jcc(Cond::AE, done);
    }
    if (!straight_) start_group();
    for (size_t b = 0; b < order_.size(); ++b)
      if (!block(static_cast<int>(b), error)) return false;
    a_.bind(block_label_[order_.size()]);
    if (!straight_) finish_group();
    if (!callee_) {
      a_.add(Gp::r13, slot_bytes_);  // byte offsets of 4-byte floats: one slot's width of points
      a_.jmp(top);
      a_.bind(done);
    }
    a_.mov_imm(Gp::rax, 0);
    a_.bind(exit_);
    epilogue();
    for (const auto& [label, code] : traps_) {  // runtime errors: the code names the kind and line
      a_.bind(label);
      a_.mov_imm(Gp::rax, code);
      a_.jmp(exit_);
    }
    for (const auto& c : carries_) carry(c);
    for (const auto& sp : slow_) {  // the argument is in the first scratch slot
      a_.bind(sp.entry);
      for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(at(save_slot_ + slot_bytes_ * r), static_cast<Xmm>(r));
      a_.lea(Gp::rdi, scratch(0));
      a_.lea(Gp::rsi, scratch(3));
      a_.mov_imm(Gp::rdx, static_cast<uint64_t>(lanes()));
      a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(sp.fn));
      call_out();
      a_.call(Gp::rax);
      if (sp.fn2) {  // the pair's second function of the same argument; the first's result to slot 2
        a_.movaps(Xmm::x0, scratch(3));
        a_.movaps(scratch(2), Xmm::x0);
        a_.lea(Gp::rdi, scratch(0));
        a_.lea(Gp::rsi, scratch(3));
        a_.mov_imm(Gp::rdx, static_cast<uint64_t>(lanes()));
        a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(sp.fn2));
        call_out();
        a_.call(Gp::rax);
      }
      for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(static_cast<Xmm>(r), at(save_slot_ + slot_bytes_ * r));
      if (sp.fn2) {
        a_.movaps(sp.result, scratch(2));
        a_.movaps(sp.result2, scratch(3));
      } else {
        a_.movaps(sp.result, scratch(3));
      }
      a_.jmp(sp.back);
    }
    return true;
  }

  void set_ranges(std::vector<ir::Range> r) { ranges_ = std::move(r); }
  void set_uniform() { uniform_ = true; }
  void set_wide() { slot_bytes_ = 32; }
  // The listing with this function's frame size in place of its placeholder.
  void fix_listing(std::string& text) const {
    std::string from = "rsp, " + std::to_string(placeholder_), to = "rsp, " + std::to_string(frame_bytes());
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  void patch_frame() {
    for (size_t at : frame_fields_) a_.patch32(at, static_cast<uint32_t>(frame_bytes()));
  }

 private:
  // ---- layout: block order, positions, uses, homes ----
  bool layout(std::string& error) {
    for (const ir::Block* blk : ir::reverse_post_order(fn_)) order_.push_back(blk);
    block_index_.assign(fn_.next_block, -1);
    for (size_t b = 0; b < order_.size(); ++b) block_index_[order_[b]->id] = static_cast<int>(b);
    uses_.assign(fn_.next_value, {});
    early_.assign(fn_.next_value, false);
    def_block_.assign(fn_.next_value, -1);
    cross_.assign(fn_.next_value, false);
    int pos = 0;
    bool memory = false;
    for (size_t b = 0; b < order_.size(); ++b) {
      block_start_.push_back(pos);
      for (const ir::Inst* in : order_[b]->insts) {
        inst_at_.push_back(in);
        if (in->defines_value()) def_block_[in->id] = static_cast<int>(b);
        if (in->op == ir::Op::Phi) cross_[in->id] = true;
        else
          for (const ir::Inst* arg : in->args) uses_[arg->id].push_back(pos);
        memory |= in->op == ir::Op::GLoad || in->op == ir::Op::GStore || in->op == ir::Op::Tick;
        if (in->op == ir::Op::Call) {  // the callee needs the lane mask, and the call context
          memory = calls_ = true;
          max_args_ = std::max(max_args_, static_cast<int>(in->args.size()));
        }
        bool array =
            in->op == ir::Op::ANew || in->op == ir::Op::ALoad || in->op == ir::Op::AStore || in->op == ir::Op::ALen;
        memory |= array;
        arrays_ |= array;
        max_phis_ = std::max(max_phis_, in->op == ir::Op::Phi ? ++phis_here_ : (phis_here_ = 0));
        ++pos;
      }
      phis_here_ = 0;
      block_end_.push_back(pos);
    }
    // A phi's operand is used on its edge, at the end of the predecessor.
    for (const ir::Block* blk : order_)
      for (const ir::Inst* in : blk->insts) {
        if (in->op != ir::Op::Phi) continue;
        for (size_t k = 0; k < in->args.size(); ++k) {
          int pred = block_index_[in->targets[k]->id];
          uses_[in->args[k]->id].push_back(block_end_[pred] - 1);
          cross_[in->args[k]->id] = true;
        }
      }
    for (auto& u : uses_) std::sort(u.begin(), u.end());
    for (uint32_t v = 0; v < fn_.next_value; ++v)
      for (int u : uses_[v])
        if (def_block_[v] >= 0 && (u < block_start_[def_block_[v]] || u >= block_end_[def_block_[v]])) cross_[v] = true;
    straight_ = order_.size() == 1 && !memory && !callee_;
    // Frame: fixed slots, outputs, pending masks, globals, homes, phi temporaries, spills.
    int32_t at = kFixed;
    out_slot_ = at, at += 16 * static_cast<int32_t>(fn_.num_results);
    pending_slot_ = at, at += 16 * static_cast<int32_t>(order_.size());
    int globals = callee_ ? 0 : program_.num_globals;  // a callee's globals are the kernel's
    global_slot_ = at, at += 16 * globals;
    num_globals_ = globals;
    call_slot_ = at, at += 16 * max_args_;
    array_save_ = at, at += callee_ ? 64 * static_cast<int32_t>(fn_.arrays.size()) : 0;
    home_.assign(fn_.next_value, -1);
    for (uint32_t v = 0; v < fn_.next_value; ++v)
      if (cross_[v] && !straight_) home_[v] = at, at += 16;
    temp_slot_ = at, at += 16 * max_phis_;
    auto aligned = [&](int32_t v) { return (v + slot_bytes_ - 1) / slot_bytes_ * slot_bytes_; };
    save_slot_ = aligned(at), at = save_slot_ + slot_bytes_ * kNumRegs;
    spill_base_ = aligned(at);
    (void)error;
    return true;
  }

  // The frame's size is known only once every spill slot is counted: the prologue and epilogue
  // take a 32-bit placeholder that finish() patches.
  int32_t frame_bytes() const { return spill_base_ + slot_bytes_ * next_slot_ + 8; }  // + 8 realigns after six pushes
  static constexpr int32_t kPlaceholder = 0x10000;
  // Eight lanes: the frame is aligned to 32 bytes below the pushes, rbp keeps where they end (a
  // straight-line kernel has no call context in rbp).
  void prologue() {
    for (Gp g : {Gp::rbx, Gp::rbp, Gp::r12, Gp::r13, Gp::r14, Gp::r15}) a_.push(g);
    if (a_.wide()) a_.mov(Gp::rbp, Gp::rsp);
    a_.sub(Gp::rsp, placeholder_);
    frame_fields_.push_back(a_.size() - 4);
    if (a_.wide()) a_.and_(Gp::rsp, -32);
    if (callee_) return callee_prologue();
    if (calls_) kernel_context();
    a_.mov(Gp::rbx, Gp::rdi);
    a_.mov(Gp::r12, Gp::rsi);
    a_.mov(Gp::r15, Gp::r8);  // the arrays' state
    a_.lea(Gp::r13, Mem::at(Gp::rdx, Gp::rdx, 2));  // byte offsets: 4 * point index
    a_.add(Gp::r13, Gp::rdx);
    a_.lea(Gp::r14, Mem::at(Gp::rcx, Gp::rcx, 2));
    a_.add(Gp::r14, Gp::rcx);
  }
  // (args, result, mask, context): the stack is checked once the frame is reserved, before any
  // of it is written; the caller's lane mask is where the lanes start.
  void callee_prologue() {
    a_.mov(Gp::rbx, Gp::rdi);
    a_.mov(Gp::r12, Gp::rsi);
    a_.mov(Gp::rbp, Gp::rcx);
    a_.mov(Gp::r15, Mem::at(Gp::rbp, kCtxArrays));
    a_.mov(Gp::rax, Mem::at(Gp::rbp, kCtxStackLimit));
    a_.cmp(Gp::rsp, Gp::rax);
    a_.jcc(Cond::B, trap(4, backends::first_located(fn_)));
    a_.movups(Xmm::x0, Mem::at(Gp::rdx));
    a_.movaps(pending(0), Xmm::x0);
  }
  // The kernel's call context: its globals, counters, arrays, depth 0 and the stack limit (r9).
  void kernel_context() {
    a_.lea(Gp::rax, at(global_slot_));
    a_.mov(at(kCtx + kCtxGlobals), Gp::rax);
    a_.lea(Gp::rax, at(kCounters));
    a_.mov(at(kCtx + kCtxCounters), Gp::rax);
    a_.mov(at(kCtx + kCtxArrays), Gp::r8);
    a_.mov_imm(Gp::rax, 0);
    a_.mov(at(kCtx + kCtxDepth), Gp::rax);
    a_.mov(at(kCtx + kCtxStackLimit), Gp::r9);
    a_.lea(Gp::rbp, at(kCtx));
  }
  void epilogue() {
    if (a_.wide()) {
      a_.mov(Gp::rsp, Gp::rbp);
    } else {
      a_.add(Gp::rsp, placeholder_);
      frame_fields_.push_back(a_.size() - 4);
    }
    for (Gp g : {Gp::r15, Gp::r14, Gp::r13, Gp::r12, Gp::rbp, Gp::rbx}) a_.pop(g);
    if (a_.wide()) a_.vzeroupper();  // no dirty upper halves for the SSE code after us
    a_.ret();
  }

  // Each group of four points: every lane waits at the entry; counters zero; globals NaN. A callee
  // starts with its caller's lanes, and its local arrays are its own.
  void start_group() {
    if (callee_) return start_call();
    if (arrays_) {
      a_.mov(Gp::rdi, Gp::r15);
      a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(&backends::fs_lanes_reset));
      a_.call(Gp::rax);
    }
    a_.pcmpeqd(Xmm::x0, Xmm::x0);
    a_.movaps(pending(0), Xmm::x0);
    a_.xorps(Xmm::x1, Xmm::x1);
    for (size_t b = 1; b < order_.size(); ++b) a_.movaps(pending(static_cast<int>(b)), Xmm::x1);
    a_.movaps(at(kCounters), Xmm::x1);
    a_.movaps(at(kTotals), Xmm::x1);
    a_.movaps(at(kTotals + 16), Xmm::x1);
    for (uint32_t k = 0; k < fn_.num_results; ++k) a_.movaps(at(out_slot_ + 16 * static_cast<int32_t>(k)), Xmm::x1);
    if (num_globals_) a_.movaps(Xmm::x0, bits(0x7FC00000u));
    for (int g = 0; g < num_globals_; ++g) a_.movaps(at(global_slot_ + 16 * g), Xmm::x0);
  }
  void start_call() {
    a_.xorps(Xmm::x1, Xmm::x1);
    for (size_t b = 1; b < order_.size(); ++b) a_.movaps(pending(static_cast<int>(b)), Xmm::x1);
    a_.movaps(at(out_slot_), Xmm::x1);
    if (!fn_.arrays.empty()) local_arrays(reinterpret_cast<const void*>(&backends::fs_lanes_enter));
  }
  void local_arrays(const void* helper) {
    a_.mov(Gp::rdi, Gp::r15);
    a_.mov_imm(Gp::rsi, global_arrays_);
    a_.mov_imm(Gp::rdx, fn_.arrays.size());
    a_.lea(Gp::rcx, at(array_save_));
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(helper));
    a_.call(Gp::rax);
  }
  // After the scan: lanes still waiting (sent back to an earlier block by a later one) rescan;
  // otherwise the outputs go out.
  void finish_group() {
    a_.xorps(Xmm::x0, Xmm::x0);
    for (size_t b = 0; b < order_.size(); ++b) a_.orps(Xmm::x0, pending(static_cast<int>(b)));
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, block_label_[0]);
    if (callee_) {
      a_.movaps(Xmm::x0, at(out_slot_));
      a_.movaps(Mem::at(Gp::r12), Xmm::x0);
      if (!fn_.arrays.empty()) local_arrays(reinterpret_cast<const void*>(&backends::fs_lanes_leave));
      return;
    }
    for (uint32_t k = 0; k < fn_.num_results; ++k) {
      a_.movaps(Xmm::x0, at(out_slot_ + 16 * static_cast<int32_t>(k)));
      store_output(k, Xmm::x0);
    }
  }

  bool block(int b, std::string& error) {
    a_.bind(block_label_[b]);
    cur_ = b;
    held_.fill(kFree);
    reg_of_.assign(fn_.next_value, -1);
    slot_of_ = home_;
    if (!straight_) {  // run for the waiting lanes, or skip
      a_.movaps(Xmm::x0, pending(b));
      a_.movmskps(Gp::rax, Xmm::x0);
      a_.test(Gp::rax, Gp::rax);
      a_.jcc(Cond::E, block_label_[b + 1]);
      a_.movaps(at(kActive), Xmm::x0);
      a_.xorps(Xmm::x1, Xmm::x1);
      a_.movaps(pending(b), Xmm::x1);
    }
    int pos = block_start_[b];
    for (const ir::Inst* in : order_[b]->insts) {
      if (in->op != ir::Op::Phi) {
        if (!early_[in->id] && !inst(*in, pos, error)) return false;
        release_dead(*in, pos);
      }
      ++pos;
    }
    return true;
  }

  bool unsupported(const ir::Inst& in, std::string& error) {
    error = std::string("the sse backend does not compile '") + ir::mnemonic(in.op) + "'; use --backend vm";
    return false;
  }

  // One IR instruction: a dispatch by family; every op is named here (no default), so a new op
  // fails the build until it has its instructions.
  bool inst(const ir::Inst& in, int pos, std::string& error) {
    using ir::Op;
    switch (in.op) {
      case Op::Const: return true;  // read from the constant pool where used
      case Op::Phi: return true;  // its home is written on the incoming edges
      case Op::Param: return param(in, pos), true;
      case Op::Add:
      case Op::Sub:
      case Op::Mul:
      case Op::Div: return arithmetic(in, pos), true;
      case Op::Neg:
      case Op::Abs: return sign_bit(in, pos), true;
      case Op::Sqrt:
      case Op::Floor:
      case Op::Ceil:
      case Op::Round:
      case Op::Sign: return rounding(in, pos), true;
      case Op::Min:
      case Op::Max:
      case Op::Clamp: return min_max(in, pos), true;
      case Op::Eq:
      case Op::Ne:
      case Op::Lt:
      case Op::Le:
      case Op::Gt:
      case Op::Ge: return comparison(in, pos), true;
      case Op::Not:
      case Op::Truth:
      case Op::Select: return logic(in, pos), true;
      case Op::Mod:
        return call(in, pos, reinterpret_cast<const void*>(&backends::mod_batch));
        // Batch rows of ir/math_ops.def call runtime/math's batch function; Trig rows inline it
        // (sse_compile_lanes.h); Lane rows have their own cases above.
#define FS_SSE_Lane(N, FN)
#define FS_SSE_Batch(N, FN) \
  case Op::N: return call(in, pos, reinterpret_cast<const void*>(&math::FN##_batch));
#define FS_SSE_Trig(N, FN) \
  case Op::N: return trig(in, pos, in.op == Op::Cos), true;
#define FS_MATH(N, FN, A, HOW) FS_SSE_##HOW(N, FN)
#include "ir/math_ops.def"
#undef FS_SSE_Lane
#undef FS_SSE_Batch
#undef FS_SSE_Trig
      case Op::Ret: return ret(in), true;
      case Op::Jump:
      case Op::Branch: return jump(in), true;
      case Op::Tick: return tick(in), true;
      case Op::GLoad:
      case Op::GStore: return global(in, pos), true;
      case Op::ANew:
      case Op::ALoad:
      case Op::AStore:
      case Op::ALen: return array_op(in, pos), true;
      case Op::Call: return call_function(in, pos), true;
    }
    return unsupported(in, error);
  }

  Src arg(const ir::Inst& in, size_t i) { return src(in.args[i]); }

  bool dies_here(const ir::Inst* v, int pos) const {
    return v->op != ir::Op::Const && reg_of_[v->id] >= 0 && next_use(v->id, pos) == INT32_MAX;
  }

  // A simple destructive op may take over its first operand's register when it dies here.
  Xmm dest_first(const ir::Inst& in, int pos) {
    const ir::Inst* a = in.args[0];
    if (!dies_here(a, pos)) return alloc(pos);
    Xmm d = static_cast<Xmm>(reg_of_[a->id]);
    held_[reg_of_[a->id]] = -1, reg_of_[a->id] = -1;
    return d;
  }

  void param(const ir::Inst& in, int pos) {
    Xmm d = alloc(pos);
    if (callee_) {
      a_.movaps(d, Mem::at(Gp::rbx, 16 * in.aux));
    } else if (uniform_) {  // the one-point code: rbx is the point's array of inputs
      a_.movss(d, Mem::at(Gp::rbx, 4 * in.aux));
      a_.shufps(d, d, 0);
    } else if (fn_.row_params_from && static_cast<uint32_t>(in.aux) >= fn_.row_params_from) {
      a_.mov(Gp::rax, Mem::at(Gp::rbx, 8 * in.aux));  // a row parameter: one value for the call
      if (a_.wide()) {
        a_.vbroadcastss(d, Mem::at(Gp::rax, 0));
      } else {
        a_.movss(d, Mem::at(Gp::rax, 0));
        a_.shufps(d, d, 0);
      }
    } else {
      a_.mov(Gp::rax, Mem::at(Gp::rbx, 8 * in.aux));
      a_.movups(d, Mem::at(Gp::rax, Gp::r13, 1));
    }
    define(in, d);
  }

  // With VEX, the result's register: a dying operand's, else a free one; no copy either way.
  Xmm vex_dest(const ir::Inst* a, const ir::Inst* b, int pos) {
    for (const ir::Inst* v : {a, b}) {
      if (!dies_here(v, pos)) continue;
      Xmm d = static_cast<Xmm>(reg_of_[v->id]);
      drop(v->id);
      return d;
    }
    return alloc(pos);
  }

  void arithmetic(const ir::Inst& in, int pos) {
    using ir::Op;
    Src b = arg(in, 1);
    Src a = arg(in, 0);
    // a + b and a * b are b + a and b * a, bit for bit: when only b dies here, its register
    // takes the result and no copy is needed.
    const ir::Inst *ia = in.args[0], *ib = in.args[1];
    if (a_.vex()) {  // three operands: only a first operand in memory needs a load
      if (a.mem && !b.mem && (in.op == Op::Add || in.op == Op::Mul)) std::swap(a, b), std::swap(ia, ib);
      if (!a.mem) {
        Xmm d = vex_dest(ia, ib, pos);
        if (in.op == Op::Add) FS_APPLY3(vaddps, d, a.x, b);
        if (in.op == Op::Sub) FS_APPLY3(vsubps, d, a.x, b);
        if (in.op == Op::Mul) FS_APPLY3(vmulps, d, a.x, b);
        if (in.op == Op::Div) FS_APPLY3(vdivps, d, a.x, b);
        define(in, d);
        return;
      }
    }
    if ((in.op == Op::Add || in.op == Op::Mul) && !dies_here(ia, pos) && dies_here(ib, pos) && ia != ib) {
      Xmm d = static_cast<Xmm>(reg_of_[ib->id]);
      drop(ib->id);
      if (in.op == Op::Add) FS_APPLY(addps, d, a);
      else FS_APPLY(mulps, d, a);
      define(in, d);
      return;
    }
    Xmm d = dest_first(in, pos);
    load(d, a);
    if (in.op == Op::Add) FS_APPLY(addps, d, b);
    if (in.op == Op::Sub) FS_APPLY(subps, d, b);
    if (in.op == Op::Mul) FS_APPLY(mulps, d, b);
    if (in.op == Op::Div) FS_APPLY(divps, d, b);
    define(in, d);
  }

  void sign_bit(const ir::Inst& in, int pos) {  // neg flips it, abs clears it
    Src a = arg(in, 0);
    if (a_.vex() && !a.mem) {
      Xmm d = vex_dest(in.args[0], in.args[0], pos);
      if (in.op == ir::Op::Neg) a_.vxorps(d, a.x, bits(0x80000000u));
      else a_.vandps(d, a.x, bits(0x7FFFFFFFu));
      define(in, d);
      return;
    }
    Xmm d = dest_first(in, pos);
    load(d, a);
    if (in.op == ir::Op::Neg) a_.xorps(d, bits(0x80000000u));
    else a_.andps(d, bits(0x7FFFFFFFu));
    define(in, d);
  }

  void rounding(const ir::Inst& in, int pos) {
    using ir::Op;
    Xmm d = alloc(pos);
    if (in.op == Op::Sqrt) {
      FS_APPLY(sqrtps, d, arg(in, 0));
    } else if (in.op == Op::Floor || in.op == Op::Ceil) {
      load(Xmm::x1, arg(in, 0));
      a_.roundps(d, Xmm::x1, in.op == Op::Floor ? Rounding::Down : Rounding::Up);
    } else if (in.op == Op::Round) {  // f = floor(a); a - f >= 0.5 ? f + 1 : f, with a's sign
      load(Xmm::x1, arg(in, 0));
      a_.roundps(d, Xmm::x1, Rounding::Down);
      a_.subps(Xmm::x1, d);
      a_.movaps(Xmm::x0, k(0.5f));
      a_.cmpps(Xmm::x0, Xmm::x1, Pred::Le);
      a_.movaps(Xmm::x1, d);
      a_.addps(Xmm::x1, k(1.0f));
      a_.blendvps(d, Xmm::x1);
      load(Xmm::x0, arg(in, 0));  // only +0 can differ from a's sign (a in [-0.5, 0)): or it in
      a_.andps(Xmm::x0, bits(0x80000000u));
      a_.orps(d, Xmm::x0);
    } else {  // Sign: a > 0 ? 1 : (a < 0 ? -1 : a)
      Src a = arg(in, 0);
      a_.movaps(Xmm::x1, k(0.0f));
      if (a.mem) a_.cmpps(Xmm::x1, a.m, Pred::Lt);
      else a_.cmpps(Xmm::x1, a.x, Pred::Lt);
      load(Xmm::x0, a);
      a_.cmpps(Xmm::x0, k(0.0f), Pred::Lt);
      load(d, a);
      a_.blendvps(d, k(-1.0f));
      a_.movaps(Xmm::x0, Xmm::x1);
      a_.blendvps(d, k(1.0f));
    }
    define(in, d);
  }

  void min_max(const ir::Inst& in, int pos) {
    if (in.op == ir::Op::Clamp) {  // min(max(a, lo), hi)
      Xmm d = alloc(pos);
      minmax(Xmm::x1, arg(in, 0), arg(in, 1), !may_nan(in.args[1]), false);
      minmax(d, {false, Xmm::x1, {}}, arg(in, 2), !may_nan(in.args[2]), true);
      define(in, d);
      return;
    }
    const ir::Inst* b = in.args[1];
    Src sa = arg(in, 0), sb = arg(in, 1);
    Xmm d;
    if (dies_here(b, pos)) {
      d = static_cast<Xmm>(reg_of_[b->id]);  // b dies here: its register takes the result
      drop(b->id);
    } else if (a_.vex() && !sb.mem) {
      d = vex_dest(in.args[0], b, pos);
    } else {
      d = alloc(pos);
    }
    minmax(d, sa, sb, !may_nan(b), in.op == ir::Op::Min);
    define(in, d);
  }

  void comparison(const ir::Inst& in, int pos) {
    using ir::Op;
    Xmm d = alloc(pos);
    Src a = arg(in, 0), b = arg(in, 1);
    if (in.op == Op::Eq) compare(d, a, b, Pred::Eq);
    if (in.op == Op::Ne) compare(d, a, b, Pred::Neq);
    if (in.op == Op::Lt) compare(d, a, b, Pred::Lt);
    if (in.op == Op::Le) compare(d, a, b, Pred::Le);
    if (in.op == Op::Gt) compare(d, b, a, Pred::Lt);
    if (in.op == Op::Ge) compare(d, b, a, Pred::Le);
    define(in, d);
  }

  void logic(const ir::Inst& in, int pos) {  // not, truth (0 or 1), select
    Xmm d = alloc(pos);
    truthy_mask(arg(in, 0), may_nan(in.args[0]));
    if (in.op == ir::Op::Select) {
      load(d, arg(in, 2));
      FS_APPLY(blendvps, d, arg(in, 1));
    } else {
      a_.movaps(d, Xmm::x0);
      if (in.op == ir::Op::Not) a_.andnps(d, k(1.0f));
      else a_.andps(d, k(1.0f));
    }
    define(in, d);
  }

  void ret(const ir::Inst& in) {
    for (size_t o = 0; o < in.args.size(); ++o) {
      Src s = src(in.args[o]);
      if (!straight_) {  // lanes return at different times: collect under the block's mask
        masked_store(at(out_slot_ + 16 * static_cast<int32_t>(o)), s, at(kActive));
        continue;
      }
      if (s.mem) a_.movaps(Xmm::x0, s.m), s = {false, Xmm::x0, {}};
      store_output(static_cast<uint32_t>(o), s.x);
    }
  }
  // The one-point code writes the first lane to the point's array of outputs (r12).
  void store_output(uint32_t k, Xmm x) {
    if (uniform_) return a_.movss(Mem::at(Gp::r12, 4 * static_cast<int32_t>(k)), x);
    a_.mov(Gp::rax, Mem::at(Gp::r12, 8 * static_cast<int32_t>(k)));
    a_.movups(Mem::at(Gp::rax, Gp::r13, 1), x);
  }

  void jump(const ir::Inst& in) {
    if (in.op == ir::Op::Jump) {
      a_.movaps(Xmm::x0, at(kActive));
      a_.movaps(at(kEdge0), Xmm::x0);
      edge(in.targets[0], at(kEdge0));
      back_edge(in.targets[0], at(kEdge0));
      return;
    }
    // Branch: lanes where the condition is truthy take targets[0].
    truthy_mask(arg(in, 0), may_nan(in.args[0]));
    a_.movaps(Xmm::x1, at(kActive));
    a_.andps(Xmm::x1, Xmm::x0);
    a_.movaps(at(kEdge0), Xmm::x1);
    a_.andnps(Xmm::x0, at(kActive));
    a_.movaps(at(kEdge1), Xmm::x0);
    edge(in.targets[0], at(kEdge0));
    edge(in.targets[1], at(kEdge1));
    bool first_back = block_index_[in.targets[0]->id] <= block_index_[in.targets[1]->id];
    back_edge(in.targets[first_back ? 0 : 1], at(first_back ? kEdge0 : kEdge1));
    back_edge(in.targets[first_back ? 1 : 0], at(first_back ? kEdge1 : kEdge0));
  }

  void tick(const ir::Inst& in) {  // per-lane iteration counters (int32): counter - mask adds one per active lane
    Mem counters = counters_mem();
    a_.movaps(Xmm::x0, counters);
    a_.psubd(Xmm::x0, at(kActive));
    a_.movaps(counters, Xmm::x0);
    a_.pcmpgtd(Xmm::x0, bits(static_cast<uint32_t>(budget_)));
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.test(Gp::rax, Gp::rax);
    if (loop_budget_ <= kCarryAt) {
      a_.jcc(Cond::NE, trap(1, &in));
    } else {
      // A budget beyond int32: at 2^30 the counts move into 64-bit totals, checked there.
      carries_.push_back({a_.new_label(), a_.new_label(), trap(1, &in)});
      a_.jcc(Cond::NE, carries_.back().entry);
      a_.bind(carries_.back().back);
    }
    cancel_check(in);
  }

  // A run cancelled from another thread (support/cancel.h) ends the loop or the recursion: the
  // slot holds the current flag's address.
  void cancel_check(const ir::Inst& in) {
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(support::cancel_slot()));
    a_.mov(Gp::rax, Mem::at(Gp::rax));
    a_.cmp8(Mem::at(Gp::rax), 0);
    a_.jcc(Cond::NE, trap(5, &in));
  }

  void global(const ir::Inst& in, int pos) {
    if (in.op == ir::Op::GStore) {
      masked_store(global_mem(in.aux), arg(in, 0), at(kActive));
      return;
    }
    Xmm d = alloc(pos);
    a_.movaps(d, global_mem(in.aux));
    define(in, d);
  }

  // The callee runs for this block's lanes: arguments to the call slots, live registers saved,
  // the depth budget (recursive callees only, as in the VM) checked around it; an error it
  // returns (rax != 0) ends this function too.
  void call_function(const ir::Inst& in, int pos) {
    a_.refuse_wide("a function call");
    for (size_t i = 0; i < in.args.size(); ++i) {
      load(Xmm::x0, src(in.args[i]));
      a_.movaps(at(call_slot_ + 16 * static_cast<int32_t>(i)), Xmm::x0);
    }
    flush_registers(pos);
    bool counted = program_.module.functions[in.aux]->recursive;
    Mem depth = Mem::at(Gp::rbp, kCtxDepth);
    if (counted) {
      a_.cmp(depth, static_cast<int32_t>(program_.max_call_depth));
      a_.jcc(Cond::AE, trap(3, &in));
      cancel_check(in);
      a_.add(depth, 1);
    }
    a_.lea(Gp::rdi, at(call_slot_));
    a_.lea(Gp::rsi, at(kScratch + 48));
    a_.lea(Gp::rdx, at(kActive));
    a_.mov(Gp::rcx, Gp::rbp);
    a_.lea(Gp::rax, Mem::rip(program_.entries[in.aux]));
    a_.call(Gp::rax);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, exit_);
    if (counted) a_.sub(depth, 1);
    Xmm d = alloc(pos);
    a_.movaps(d, at(kScratch + 48));
    define(in, d);
  }

  static constexpr uint64_t kCarryAt = INT32_MAX - 1;  // budgets up to here count in int32 alone
  struct Carry {  // out of line: fold the int32 counters into the totals, every register saved
    Label entry, back, trap;
  };
  void carry(const Carry& c) {
    a_.bind(c.entry);
    for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(at(save_slot_ + 16 * r), static_cast<Xmm>(r));
    if (callee_) a_.mov(Gp::rdi, Mem::at(Gp::rbp, kCtxCounters));
    else a_.lea(Gp::rdi, at(kCounters));
    a_.mov_imm(Gp::rsi, loop_budget_);
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(&backends::fs_ticks_carry));
    a_.call(Gp::rax);
    for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(static_cast<Xmm>(r), at(save_slot_ + 16 * r));
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, c.trap);
    a_.jmp(c.back);
  }
  const Program& program_;
  int32_t placeholder_;
  uint64_t loop_budget_;
  std::vector<Carry> carries_;
  bool calls_ = false;
  int max_args_ = 0;
  int32_t call_slot_ = 0, array_save_ = 0;
};

#undef FS_APPLY
#undef FS_APPLY3

// Bounded-input code only where a bound removes NaN tests (then the kernel needs its guard).
double choose_bound(const ir::Function& fn, Codegen& gen) {
  double best = ir::best_param_bound(fn);
  if (best > 0) gen.set_ranges(ir::value_ranges(fn, best));
  return best;
}

// Eight lanes where the kernel is straight-line code: the one function of its program, one block,
// no globals, arrays or loop counters (those run four lanes: the code generator refuses wide
// mode for them and the kernel is generated again on four).
bool try_wide(const backends::JitProgram& jp, bool uniform_lanes) {
  if (uniform_lanes || math::active_isa() == math::Isa::Base || jp.functions.size() != 1) return false;
  return jp.module->functions[static_cast<size_t>(jp.kernel)]->blocks.size() == 1;
}

std::vector<uint8_t> emit_program(const backends::JitProgram& jp, const backends::Budgets& budgets, bool wide,
                                  std::string& error, std::string* listing, std::vector<std::string>* array_names,
                                  double* param_bound, bool uniform_lanes, bool& refused) {
  const ir::Module& m = *jp.module;
  int kernel = jp.kernel;
  Assembler a;
  if (listing) a.enable_listing();
  // AVX's three-operand forms where the CPU has them (FSCRIPT_ISA=base keeps the SSE encoding).
  if (math::active_isa() != math::Isa::Base) a.enable_vex();
  if (wide) a.enable_wide();
  const std::vector<int>& fns = jp.functions;
  Program program{m, {}, jp.num_globals, budgets.max_call_depth};
  for (size_t f = 0; f < m.functions.size(); ++f) program.entries.push_back(a.new_label());
  std::vector<std::string> names = m.arrays;
  std::vector<std::unique_ptr<Codegen>> gens;
  for (int f : fns) {
    const ir::Function& fn = *m.functions[static_cast<size_t>(f)];
    gens.push_back(std::make_unique<Codegen>(fn, a, budgets, static_cast<uint32_t>(names.size()), program,
                                             static_cast<int>(gens.size()), f != kernel));
    names.insert(names.end(), fn.arrays.begin(), fn.arrays.end());
    if (uniform_lanes) gens.back()->set_uniform();
    if (wide) gens.back()->set_wide();
    if (f == kernel && param_bound) *param_bound = choose_bound(fn, *gens.back());
    a.bind(program.entries[static_cast<size_t>(f)]);
    if (!gens.back()->run(error)) return {};
  }
  refused = !a.wide_refused().empty();
  if (refused) return {};
  if (array_names) *array_names = names;
  for (const auto& g : gens) g->patch_frame();
  std::vector<uint8_t> code = a.finish();
  if (listing) {
    *listing = a.listing();
    for (const auto& g : gens) g->fix_listing(*listing);
  }
  return code;
}

}  // namespace

std::vector<uint8_t> generate(const ir::Module& module, const backends::Budgets& budgets, std::string& error,
                              std::string* listing, std::vector<std::string>* array_names, double* param_bound,
                              bool uniform_lanes, uint32_t* lanes) {
  backends::JitProgram jp;
  if (!backends::prepare_program(module, jp, error)) return {};
  bool refused = false;
  if (try_wide(jp, uniform_lanes)) {
    std::vector<uint8_t> code =
        emit_program(jp, budgets, true, error, listing, array_names, param_bound, false, refused);
    if (!refused) {
      if (lanes) *lanes = 8;
      return code;
    }
  }
  if (lanes) *lanes = 4;
  return emit_program(jp, budgets, false, error, listing, array_names, param_bound, uniform_lanes, refused);
}

}  // namespace fscript::sse
