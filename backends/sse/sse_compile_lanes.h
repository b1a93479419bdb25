#pragma once
// The lane machinery of the SSE code generator (sse_compile.cpp builds on it): the frame's fixed
// slots, register assignment inside a block (Belady's rule, spills to 16-byte slots, operands
// read from memory where they live), stores under lane masks, phi moves on edges, runtime calls,
// and the lowering of the operations that need more than one instruction (min/max with the NaN
// rule, truthiness, comparisons, sin/cos inline, arrays). Internal to backends/sse.
#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/sse/x86.h"
#include "ir/ir.h"
#include "ir/ranges.h"
#include "runtime/math/math.h"
#include "runtime/math/trig_constants.h"

namespace fscript::sse::detail {

constexpr int kFirstReg = 2, kNumRegs = 16;
constexpr int kFree = -1, kTemp = -2;  // held_[r] when r holds no value
constexpr int32_t kScratch = 0;  // call arguments at 0, 16, 32; result at 48
constexpr int32_t kActive = 64, kEdge0 = 80, kEdge1 = 96, kCounters = 112, kTotals = 128, kCtx = 160, kFixed = 208;
// Loop counters: int32 per lane at kCounters; a budget beyond int32 also keeps 64-bit totals per
// lane right after them (kTotals = kCounters + 16, see fs_ticks_carry in jit_support.h).
static_assert(kTotals == kCounters + 16);
// The call context a kernel keeps at kCtx and hands (in rbp) to the functions it calls, which
// share its lanes' globals, loop counters, arrays and call depth.
constexpr int32_t kCtxGlobals = 0, kCtxCounters = 8, kCtxArrays = 16, kCtxDepth = 24, kCtxStackLimit = 32;

// A source operand: a register or a memory location (spill or home slot, or constant).
struct Src {
  bool mem;
  Xmm x;
  Mem m;
};

#define FS_APPLY(method, d, s) ((s).mem ? a_.method(d, (s).m) : a_.method(d, (s).x))
#define FS_APPLY3(method, d, s1, s) ((s).mem ? a_.method(d, s1, (s).m) : a_.method(d, s1, (s).x))

class LaneCode {
 protected:
  LaneCode(const ir::Function& fn, Assembler& a, int32_t budget, uint32_t global_arrays, bool callee)
      : fn_(fn), budget_(budget), a_(a), global_arrays_(global_arrays), callee_(callee) {}

  Mem at(int32_t offset) const { return Mem::at(Gp::rsp, offset); }
  // Scratch slot k of a runtime call: arguments 0 to 2, the result 3 (slots of the lanes' width).
  Mem scratch(int k) const { return at(kScratch + slot_bytes_ * k); }
  int lanes() const { return slot_bytes_ / 4; }
  Mem pending(int b) const { return at(pending_slot_ + 16 * b); }

  // ---- uses and liveness (within the current block) ----
  int next_use(uint32_t v, int pos) const {  // first use after pos in this block, or INT_MAX
    const auto& u = uses_[v];
    auto it = std::upper_bound(u.begin(), u.end(), pos);
    return it == u.end() || *it >= block_end_[cur_] ? INT32_MAX : *it;
  }
  void drop(uint32_t v) {
    if (reg_of_[v] < 0) return;
    held_[reg_of_[v]] = kFree;
    reg_of_[v] = -1;
  }
  void release_dead(const ir::Inst& in, int pos) {
    for (const ir::Inst* arg : in.args)
      if (next_use(arg->id, pos) == INT32_MAX) drop(arg->id);
    if (in.defines_value() && next_use(in.id, pos) == INT32_MAX) drop(in.id);
  }

  // ---- registers ----
  void spill(int reg) {
    uint32_t v = static_cast<uint32_t>(held_[reg]);
    if (slot_of_[v] < 0) {
      slot_of_[v] = spill_base_ + slot_bytes_ * next_slot_++;
      a_.movaps(at(slot_of_[v]), static_cast<Xmm>(reg));
    }
    drop(v);
  }
  // A free register for the result of the instruction at pos; operands of that instruction stay.
  Xmm alloc(int pos) {
    int best = -1, best_use = -1;
    for (int r = kFirstReg; r < kNumRegs; ++r) {
      if (held_[r] == kFree) return static_cast<Xmm>(r);
      if (held_[r] == kTemp) continue;
      int u = next_use(static_cast<uint32_t>(held_[r]), pos - 1);
      if (u != pos && u > best_use) best = r, best_use = u;
    }
    spill(best);
    return static_cast<Xmm>(best);
  }
  // A scratch register for the length of one instruction's code.
  Xmm temp(int pos) {
    Xmm t = alloc(pos);
    held_[static_cast<int>(t)] = kTemp;
    return t;
  }
  void release(Xmm t) { held_[static_cast<int>(t)] = kFree; }
  // Before a call: every xmm register is caller-saved, so values used later go to their slots.
  void flush_registers(int pos) {
    for (int r = kFirstReg; r < kNumRegs; ++r) {
      if (held_[r] < 0) continue;
      if (next_use(static_cast<uint32_t>(held_[r]), pos) != INT32_MAX) spill(r);
      else drop(static_cast<uint32_t>(held_[r]));
    }
  }
  // The lanes' globals and loop counters: in the kernel's frame, reached through the call
  // context from a called function (rax holds its pointer).
  Mem global_mem(int g) {
    if (!callee_) return at(global_slot_ + 16 * g);
    a_.mov(Gp::rax, Mem::at(Gp::rbp, kCtxGlobals));
    return Mem::at(Gp::rax, 16 * g);
  }
  Mem counters_mem() {
    if (!callee_) return at(kCounters);
    a_.mov(Gp::rax, Mem::at(Gp::rbp, kCtxCounters));
    return Mem::at(Gp::rax, 0);
  }

  // The result is in d; a value other blocks read also goes to its home, for this block's lanes.
  void define(const ir::Inst& in, Xmm d) {
    held_[static_cast<int>(d)] = static_cast<int>(in.id);
    reg_of_[in.id] = static_cast<int>(d);
    if (home_[in.id] >= 0) masked_store(at(home_[in.id]), {false, d, {}}, at(kActive));
  }
  // dst = mask ? value : dst, lane by lane (a plain store in the entry block: every lane is there).
  void masked_store(const Mem& dst, const Src& value, const Mem& mask) {
    if (cur_ == 0 && mask.disp == kActive && !callee_) {
      if (value.mem) a_.movaps(Xmm::x1, value.m), a_.movaps(dst, Xmm::x1);
      else a_.movaps(dst, value.x);
      return;
    }
    a_.movaps(Xmm::x0, mask);
    a_.movaps(Xmm::x1, dst);
    FS_APPLY(blendvps, Xmm::x1, value);
    a_.movaps(dst, Xmm::x1);
  }
  Src src(const ir::Inst* v) {
    if (v->op == ir::Op::Const) return {true, Xmm::x0, Mem::rip(a_.constant_ps(v->imm))};
    if (reg_of_[v->id] >= 0) return {false, static_cast<Xmm>(reg_of_[v->id]), {}};
    return {true, Xmm::x0, at(slot_of_[v->id])};
  }
  Mem k(float v) { return Mem::rip(a_.constant_ps(v)); }
  // Before a call out of wide code (every live register is in memory by then): clean upper halves,
  // so callee code in the legacy SSE encoding pays no AVX transition on the CPUs that charge one.
  void call_out() {
    if (a_.wide()) a_.vzeroupper();
  }
  Mem bits(uint32_t b) { return Mem::rip(a_.constant({b, b, b, b})); }
  void load(Xmm d, const Src& s) {
    if (s.mem || s.x != d) FS_APPLY(movaps, d, s);
  }

  // ---- edges: phi moves as a parallel copy under the edge's mask, then the lanes wait at s ----
  void edge(const ir::Block* to, const Mem& mask) {
    const ir::Block* from = order_[cur_];
    std::vector<const ir::Inst*> phis;
    for (const ir::Inst* in : to->insts)
      if (in->op == ir::Op::Phi) phis.push_back(in);
    for (size_t k = 0; k < phis.size(); ++k)
      for (size_t j = 0; j < phis[k]->args.size(); ++j)
        if (phis[k]->targets[j] == from) {
          Src s = src(phis[k]->args[j]);
          if (s.mem) a_.movaps(Xmm::x1, s.m), s = {false, Xmm::x1, {}};
          a_.movaps(at(temp_slot_ + 16 * static_cast<int32_t>(k)), s.x);
        }
    for (size_t k = 0; k < phis.size(); ++k)
      masked_store(at(home_[phis[k]->id]), {true, Xmm::x0, at(temp_slot_ + 16 * static_cast<int32_t>(k))}, mask);
    int t = block_index_[to->id];
    a_.movaps(Xmm::x1, pending(t));
    a_.orps(Xmm::x1, mask);
    a_.movaps(pending(t), Xmm::x1);
  }
  // After both edges: a back edge that carried lanes jumps to its target.
  void back_edge(const ir::Block* to, const Mem& mask) {
    int t = block_index_[to->id];
    if (t > cur_) return;  // forward: the scan gets there
    a_.movaps(Xmm::x0, mask);
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, block_label_[t]);
  }
  Label trap(uint32_t kind, const ir::Inst* at) {
    Label l = a_.new_label();
    traps_.push_back({l, backends::trap_code(kind, at)});
    return l;
  }

  // ---- semantics (runtime/math/math.h, lane by lane) ----
  // min: b NaN ? NaN : (b < a ? b : a); max alike with >. minps(b, a) is (b < a ? b : a), which
  // is already a when a is NaN; a NaN b is caught by its unordered mask, OR-ed in (the result is a
  // NaN; NaN payloads are not part of the semantics). A constant b that is a number needs no mask.
  // d may be b's own register: b is read before d is written.
  // With VEX, d may be a's register too: both are read before d is written.
  void minmax(Xmm d, const Src& a, const Src& b, bool b_number, bool is_min) {
    if (!b_number) {
      load(Xmm::x0, b);
      a_.cmpps(Xmm::x0, Xmm::x0, Pred::Unord);
    }
    if (a_.vex() && !b.mem) {
      if (is_min) FS_APPLY3(vminps, d, b.x, a);
      else FS_APPLY3(vmaxps, d, b.x, a);
    } else {
      load(d, b);
      if (is_min) FS_APPLY(minps, d, a);
      else FS_APPLY(maxps, d, a);
    }
    if (!b_number) a_.orps(d, Xmm::x0);
  }
  // Without value ranges only a constant is known not to be NaN.
  bool may_nan(const ir::Inst* v) const { return ir::may_be_nan(v, ranges_); }
  // xmm0 = truthy(c): ordered and != 0.
  void truthy_mask(const Src& c, bool maybe_nan = true) {
    if (!maybe_nan) {
      load(Xmm::x0, c);
      a_.cmpps(Xmm::x0, k(0.0f), Pred::Neq);
      return;
    }
    load(Xmm::x0, c);
    if (c.mem) a_.cmpps(Xmm::x0, c.m, Pred::Ord);
    else a_.cmpps(Xmm::x0, c.x, Pred::Ord);
    load(Xmm::x1, c);
    a_.cmpps(Xmm::x1, k(0.0f), Pred::Neq);
    a_.andps(Xmm::x0, Xmm::x1);
  }
  void compare(Xmm d, const Src& first, const Src& second, Pred p) {
    load(d, first);
    if (second.mem) a_.cmpps(d, second.m, p);
    else a_.cmpps(d, second.x, p);
    a_.andps(d, k(1.0f));
  }

  bool call(const ir::Inst& in, int pos, const void* fn) {
    for (size_t i = 0; i < in.args.size(); ++i) {  // arguments to the scratch slots
      load(Xmm::x0, src(in.args[i]));
      a_.movaps(scratch(static_cast<int>(i)), Xmm::x0);
    }
    flush_registers(pos);
    Gp arg_regs[4] = {Gp::rdi, Gp::rsi, Gp::rdx, Gp::rcx};
    size_t n = in.args.size();
    for (size_t i = 0; i < n; ++i) a_.lea(arg_regs[i], scratch(static_cast<int>(i)));
    a_.lea(arg_regs[n], scratch(3));
    a_.mov_imm(n + 1 < 4 ? arg_regs[n + 1] : Gp::r8, static_cast<uint64_t>(lanes()));
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(fn));
    call_out();
    a_.call(Gp::rax);
    Xmm d = alloc(pos);
    a_.movaps(d, scratch(3));
    define(in, d);
    return true;
  }

  Mem dbl(double v) {
    uint64_t b;
    std::memcpy(&b, &v, 8);
    uint32_t lo = static_cast<uint32_t>(b), hi = static_cast<uint32_t>(b >> 32);
    return Mem::rip(a_.constant({lo, hi, lo, hi}));
  }

  // sin (offset 0) and cos (offset 1) inline: runtime/math/batch.cpp's trig_lane step for step
  // (the argument reduced in double, Cephes polynomials, quadrant by bit tricks), so the result is
  // the batch function's, bit for bit. A group with a lane outside the fast range (huge, inf,
  // NaN) takes the batch function itself, out of line. Both polynomials are computed whatever the
  // quadrant, so a later sin or cos of the same value in the block (the gyroid's pairs) is made
  // here too, from the same reduction, and skipped when its turn comes.
  // Eight lanes (wide mode): the same steps on four doubles per ymm register, the halves split
  // with vextractf128 and joined with vinsertf128.
  void trig(const ir::Inst& in, int pos, int offset) {
    using namespace math::trig;
    const ir::Inst* partner = trig_partner(in, pos, offset);
    Src a = src(in.args[0]);
    Xmm t0 = temp(pos), t1 = temp(pos), t2 = temp(pos), t3 = temp(pos), cp = temp(pos);
    bool wide = a_.wide();
    load(Xmm::x1, a);
    a_.movaps(scratch(0), Xmm::x1);
    a_.movaps(Xmm::x0, Xmm::x1);
    a_.andps(Xmm::x0, bits(0x7FFFFFFFu));
    a_.cmpps(Xmm::x0, k(kFastLimit), Pred::Le);
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.cmp(Gp::rax, (1 << lanes()) - 1);
    SlowPath sp{a_.new_label(), a_.new_label(), t0, batch_trig(offset), t1, partner ? batch_trig(1 - offset) : nullptr};
    a_.jcc(Cond::NE, sp.entry);
    a_.cvtps2pd(t0, Xmm::x1);
    if (wide) {
      a_.vextractf128(Xmm::x1, Xmm::x1, 1);
      a_.cvtps2pd(t1, Xmm::x1);
    } else if (!uniform_) {
      a_.movhlps(Xmm::x1, Xmm::x1);
      a_.cvtps2pd(t1, Xmm::x1);
    }
    auto reduce = [&](Xmm h, Xmm j) {  // a pair of lanes in double
      a_.movaps(j, h);
      a_.mulpd(j, dbl(kTwoOverPi));
      a_.addpd(j, dbl(kRoundMagic));
      a_.subpd(j, dbl(kRoundMagic));
      a_.movaps(Xmm::x0, j);
      a_.mulpd(Xmm::x0, dbl(kPio2Hi));
      a_.subpd(h, Xmm::x0);
      a_.movaps(Xmm::x0, j);
      a_.mulpd(Xmm::x0, dbl(kPio2Lo));
      a_.subpd(h, Xmm::x0);
      a_.cvttpd2dq(j, j);
      a_.cvtpd2ps(h, h);
    };
    reduce(t0, t2);
    if (!uniform_) reduce(t1, t3);
    if (wide) {
      a_.vinsertf128(t0, t0, t1, 1);  // r, eight lanes
      a_.vinsertf128(t2, t2, t3, 1);  // q, eight lanes
    } else {
      a_.movlhps(t0, uniform_ ? t0 : t1);     // r, four lanes
      a_.punpcklqdq(t2, uniform_ ? t2 : t3);  // q, four lanes
    }
    a_.movaps(t1, t0);
    a_.mulps(t1, t0);  // z = r * r
    a_.movaps(t3, k(kSin1));  // sin: ((kSin1 z + kSin2) z - kSin3) z r + r
    a_.mulps(t3, t1);
    a_.addps(t3, k(kSin2));
    a_.mulps(t3, t1);
    a_.subps(t3, k(kSin3));
    a_.mulps(t3, t1);
    a_.mulps(t3, t0);
    a_.addps(t3, t0);
    a_.movaps(Xmm::x1, t0);  // with r's sign: the sum is +0 at r = -0, where sin(-0) is -0
    a_.andps(Xmm::x1, bits(0x80000000u));
    a_.orps(t3, Xmm::x1);
    a_.movaps(cp, k(kCos1));  // cos: ((kCos1 z - kCos2) z + kCos3) z z - 0.5 z + 1
    a_.mulps(cp, t1);
    a_.subps(cp, k(kCos2));
    a_.mulps(cp, t1);
    a_.addps(cp, k(kCos3));
    a_.mulps(cp, t1);
    a_.mulps(cp, t1);
    a_.movaps(Xmm::x1, k(0.5f));
    a_.mulps(Xmm::x1, t1);
    a_.subps(cp, Xmm::x1);
    a_.addps(cp, k(1.0f));
    quadrant_pick(t0, t3, cp, t2, offset);  // r and z are done with: their registers take the results
    if (partner) quadrant_pick(t1, t3, cp, t2, 1 - offset);
    a_.bind(sp.back);
    slow_.push_back(sp);
    for (Xmm t : {t2, t3, cp}) release(t);
    define(in, t0);
    if (!partner) return release(t1);
    define(*partner, t1);
    early_[partner->id] = true;
  }
  // out = (quadrant q + offset odd ? cos polynomial : sin polynomial), negated in quadrants 2, 3.
  void quadrant_pick(Xmm out, Xmm sin_poly, Xmm cos_poly, Xmm q, int offset) {
    a_.movaps(Xmm::x1, q);
    if (offset) a_.paddd(Xmm::x1, bits(1));
    a_.movaps(Xmm::x0, Xmm::x1);
    a_.pand(Xmm::x0, bits(1));
    a_.pcmpeqd(Xmm::x0, bits(1));
    a_.movaps(out, sin_poly);
    a_.blendvps(out, cos_poly);
    a_.pand(Xmm::x1, bits(2));
    a_.pslld(Xmm::x1, 30);
    a_.xorps(out, Xmm::x1);
  }
  static const void* batch_trig(int offset) {
    return offset ? reinterpret_cast<const void*>(&math::cos_batch) : reinterpret_cast<const void*>(&math::sin_batch);
  }
  // The first later cos (sin) of the same value in this block, not yet made, for a sin (cos).
  const ir::Inst* trig_partner(const ir::Inst& in, int pos, int offset) const {
    ir::Op want = offset ? ir::Op::Sin : ir::Op::Cos;
    for (int u : uses_[in.args[0]->id]) {
      if (u <= pos || u >= block_end_[cur_]) continue;
      const ir::Inst* p = inst_at_[u];
      if (p->op == want && p->args[0] == in.args[0] && !early_[p->id]) return p;
    }
    return nullptr;
  }

  // An array operation: its operands to the scratch slots, every register saved, the helper called
  // with (state, slot, operands..., lane mask); a helper's 1 is a runtime error with its message.
  void array_op(const ir::Inst& in, int pos) {
    a_.refuse_wide("an array operation");
    for (size_t i = 0; i < in.args.size(); ++i) {
      load(Xmm::x0, src(in.args[i]));
      a_.movaps(at(kScratch + 16 * static_cast<int32_t>(i)), Xmm::x0);
    }
    flush_registers(pos);
    uint32_t slot = in.array_global ? static_cast<uint32_t>(in.aux) : global_arrays_ + static_cast<uint32_t>(in.aux);
    a_.mov(Gp::rdi, Gp::r15);
    a_.mov_imm(Gp::rsi, slot);
    const void* fn = nullptr;
    switch (in.op) {
      case ir::Op::ANew:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kActive));
        fn = reinterpret_cast<const void*>(&backends::fs_lanes_anew);
        break;
      case ir::Op::ALoad:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kScratch + 48));
        a_.lea(Gp::r8, at(kActive));
        fn = reinterpret_cast<const void*>(&backends::fs_lanes_aload);
        break;
      case ir::Op::AStore:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kScratch + 16));
        a_.lea(Gp::r8, at(kActive));
        fn = reinterpret_cast<const void*>(&backends::fs_lanes_astore);
        break;
      default:  // ALen
        a_.lea(Gp::rdx, at(kScratch + 48));
        a_.lea(Gp::rcx, at(kActive));
        fn = reinterpret_cast<const void*>(&backends::fs_lanes_alen);
        break;
    }
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(fn));
    a_.call(Gp::rax);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, trap(2, &in));
    if (in.op == ir::Op::ALoad || in.op == ir::Op::ALen) {
      Xmm d = alloc(pos);
      a_.movaps(d, at(kScratch + 48));
      define(in, d);
    }
  }

  const ir::Function& fn_;
  std::vector<ir::Range> ranges_;  // empty: no assumption about the parameters
  // Every lane holds the same point (the one-point code): what is computed per pair of lanes in
  // double is computed for the first pair and copied to the second.
  bool uniform_ = false;
  // Eight lanes (Assembler::enable_wide): spill slots of 32 bytes in a frame aligned to 32.
  int32_t slot_bytes_ = 16;
  int32_t budget_;
  std::vector<size_t> frame_fields_;
  Assembler& a_;  // shared by the kernel and the functions it calls
  Label exit_;
  std::vector<Label> block_label_;  // one per block in order, then the end of the scan
  std::vector<std::pair<Label, uint64_t>> traps_;
  std::vector<const ir::Block*> order_;
  std::vector<int> block_index_, block_start_, block_end_, def_block_;
  std::vector<bool> cross_;
  std::vector<std::vector<int>> uses_;
  std::vector<const ir::Inst*> inst_at_;  // by position
  std::vector<bool> early_;               // by value id: made with an earlier instruction (trig pairs)
  std::vector<int> reg_of_, slot_of_, home_;
  std::array<int, kNumRegs> held_{};
  bool straight_ = true, arrays_ = false;
  uint32_t global_arrays_ = 0;  // array slots: the module's global arrays first, then each function's
  bool callee_ = false;         // a called function: lanes come in under a mask, state through rbp
  int cur_ = 0, next_slot_ = 0, max_phis_ = 0, phis_here_ = 0, num_globals_ = 0;
  int32_t out_slot_ = 0, pending_slot_ = 0, global_slot_ = 0, temp_slot_ = 0, save_slot_ = 0, spill_base_ = 0;
  struct SlowPath {  // a call of a batch function out of line: every register saved around it
    Label entry, back;
    Xmm result;
    const void* fn;
    Xmm result2 = Xmm::x0;     // a paired sin/cos: the second function's result
    const void* fn2 = nullptr;
  };
  std::vector<SlowPath> slow_;
};

}  // namespace fscript::sse::detail
