// SSA to x86-64, four points per iteration, one value per xmm register. Within a block, registers
// are assigned while emitting: a free one if there is one, else the value whose next use in the
// block is farthest is spilled to a 16-byte stack slot (Belady's rule); spilled values and
// constants (rip-relative, from the pool) are read straight from memory. xmm0 and xmm1 are
// scratch (xmm0 is blendvps's implicit mask). Runtime calls (transcendentals, fmod, noise) go
// through runtime/math's batch functions on four lanes in stack slots, every live register saved.
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

#include "backends/sse/sse_arrays.h"
#include "backends/sse/sse_backend.h"
#include "backends/sse/x86.h"
#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "runtime/math/math.h"

namespace fscript::sse {
namespace {

constexpr int kFirstReg = 2, kNumRegs = 16;
constexpr int kFree = -1, kTemp = -2;  // held_[r] when r holds no value
constexpr int32_t kScratch = 0;  // call arguments at 0, 16, 32; result at 48
constexpr int32_t kActive = 64, kEdge0 = 80, kEdge1 = 96, kCounters = 112, kFixed = 128;

void mod_batch(const float* a, const float* b, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = math::mod(a[i], b[i]);
}
void noise_batch(const float* x, const float* y, const float* z, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = math::noise(x[i], y[i], z[i]);
}

// A source operand: a register or a memory location (spill or home slot, or constant).
struct Src {
  bool mem;
  Xmm x;
  Mem m;
};

#define FS_APPLY(method, d, s) ((s).mem ? a_.method(d, (s).m) : a_.method(d, (s).x))

class Codegen {
 public:
  Codegen(const ir::Function& fn, const backend::Budgets& budgets, uint32_t global_arrays)
      : fn_(fn), budget_(static_cast<int32_t>(std::min<uint64_t>(budgets.max_loop_iterations, INT32_MAX - 1))),
        global_arrays_(global_arrays) {}

  bool run(std::string& error) {
    if (!layout(error)) return false;
    prologue();
    Label top = a_.new_label(), done = a_.new_label();
    exit_ = a_.new_label();
    for (size_t b = 0; b <= order_.size(); ++b) block_label_.push_back(a_.new_label());
    a_.bind(top);
    a_.cmp(Gp::r13, Gp::r14);
    a_.jcc(Cond::AE, done);
    if (!straight_) start_group();
    for (size_t b = 0; b < order_.size(); ++b)
      if (!block(static_cast<int>(b), error)) return false;
    a_.bind(block_label_[order_.size()]);
    if (!straight_) finish_group();
    a_.add(Gp::r13, 16);
    a_.jmp(top);
    a_.bind(done);
    a_.mov_imm(Gp::rax, 0);
    a_.bind(exit_);
    epilogue();
    for (const auto& [label, code] : traps_) {  // runtime errors: the code names the kind and line
      a_.bind(label);
      a_.mov_imm(Gp::rax, code);
      a_.jmp(exit_);
    }
    for (const auto& sp : slow_) {  // the argument is in the first scratch slot
      a_.bind(sp.entry);
      for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(at(save_slot_ + 16 * r), static_cast<Xmm>(r));
      a_.lea(Gp::rdi, at(kScratch));
      a_.lea(Gp::rsi, at(kScratch + 48));
      a_.mov_imm(Gp::rdx, 4);
      a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(sp.fn));
      a_.call(Gp::rax);
      for (int r = kFirstReg; r < kNumRegs; ++r) a_.movaps(static_cast<Xmm>(r), at(save_slot_ + 16 * r));
      a_.movaps(sp.result, at(kScratch + 48));
      a_.jmp(sp.back);
    }
    return true;
  }

  void enable_listing() { a_.enable_listing(); }
  std::string listing() const {  // with the patched frame size in place of the placeholder
    std::string text = a_.listing(), from = "rsp, " + std::to_string(kPlaceholder), to = "rsp, " + std::to_string(frame_bytes());
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) text.replace(at, from.size(), to);
    return text;
  }
  std::vector<uint8_t> finish() {
    for (size_t at : frame_fields_) a_.patch32(at, static_cast<uint32_t>(frame_bytes()));
    return a_.finish();
  }

 private:
  // ---- layout: block order, positions, uses, homes ----
  bool layout(std::string& error) {
    for (const ir::Block* blk : ir::reverse_post_order(fn_)) order_.push_back(blk);
    block_index_.assign(fn_.next_block, -1);
    for (size_t b = 0; b < order_.size(); ++b) block_index_[order_[b]->id] = static_cast<int>(b);
    uses_.assign(fn_.next_value, {});
    def_block_.assign(fn_.next_value, -1);
    cross_.assign(fn_.next_value, false);
    int pos = 0;
    bool memory = false;
    for (size_t b = 0; b < order_.size(); ++b) {
      block_start_.push_back(pos);
      for (const ir::Inst* in : order_[b]->insts) {
        if (in->defines_value()) def_block_[in->id] = static_cast<int>(b);
        if (in->op == ir::Op::Phi) cross_[in->id] = true;
        else
          for (const ir::Inst* arg : in->args) uses_[arg->id].push_back(pos);
        memory |= in->op == ir::Op::GLoad || in->op == ir::Op::GStore || in->op == ir::Op::Tick;
        bool array = in->op == ir::Op::ANew || in->op == ir::Op::ALoad || in->op == ir::Op::AStore ||
                     in->op == ir::Op::ALen;
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
    straight_ = order_.size() == 1 && !memory;
    // Frame: fixed slots, outputs, pending masks, globals, homes, phi temporaries, spills.
    int32_t at = kFixed;
    out_slot_ = at, at += 16 * static_cast<int32_t>(fn_.num_results);
    pending_slot_ = at, at += 16 * static_cast<int32_t>(order_.size());
    int globals = 0;
    for (const ir::Block* blk : order_)
      for (const ir::Inst* in : blk->insts)
        if (in->op == ir::Op::GLoad || in->op == ir::Op::GStore) globals = std::max(globals, in->aux + 1);
    global_slot_ = at, at += 16 * globals;
    num_globals_ = globals;
    home_.assign(fn_.next_value, -1);
    for (uint32_t v = 0; v < fn_.next_value; ++v)
      if (cross_[v] && !straight_) home_[v] = at, at += 16;
    temp_slot_ = at, at += 16 * max_phis_;
    save_slot_ = at, at += 16 * kNumRegs;
    spill_base_ = at;
    (void)error;
    return true;
  }

  // The frame's size is known only once every spill slot is counted: the prologue and epilogue
  // take a 32-bit placeholder that finish() patches.
  int32_t frame_bytes() const { return spill_base_ + 16 * next_slot_ + 8; }  // + 8 realigns after six pushes
  static constexpr int32_t kPlaceholder = 0x10000;
  void prologue() {
    for (Gp g : {Gp::rbx, Gp::rbp, Gp::r12, Gp::r13, Gp::r14, Gp::r15}) a_.push(g);
    a_.sub(Gp::rsp, kPlaceholder);
    frame_fields_.push_back(a_.size() - 4);
    a_.mov(Gp::rbx, Gp::rdi);
    a_.mov(Gp::r12, Gp::rsi);
    a_.mov(Gp::r15, Gp::r8);  // the arrays' state
    a_.lea(Gp::r13, Mem::at(Gp::rdx, Gp::rdx, 2));  // byte offsets: 4 * point index
    a_.add(Gp::r13, Gp::rdx);
    a_.lea(Gp::r14, Mem::at(Gp::rcx, Gp::rcx, 2));
    a_.add(Gp::r14, Gp::rcx);
  }
  void epilogue() {
    a_.add(Gp::rsp, kPlaceholder);
    frame_fields_.push_back(a_.size() - 4);
    for (Gp g : {Gp::r15, Gp::r14, Gp::r13, Gp::r12, Gp::rbp, Gp::rbx}) a_.pop(g);
    a_.ret();
  }
  Mem at(int32_t offset) const { return Mem::at(Gp::rsp, offset); }
  Mem pending(int b) const { return at(pending_slot_ + 16 * b); }

  // Each group of four points: every lane waits at the entry; counters zero; globals NaN.
  void start_group() {
    if (arrays_) {
      a_.mov(Gp::rdi, Gp::r15);
      a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(&fs_sse_arrays_reset));
      a_.call(Gp::rax);
    }
    a_.pcmpeqd(Xmm::x0, Xmm::x0);
    a_.movaps(pending(0), Xmm::x0);
    a_.xorps(Xmm::x1, Xmm::x1);
    for (size_t b = 1; b < order_.size(); ++b) a_.movaps(pending(static_cast<int>(b)), Xmm::x1);
    a_.movaps(at(kCounters), Xmm::x1);
    for (uint32_t k = 0; k < fn_.num_results; ++k) a_.movaps(at(out_slot_ + 16 * static_cast<int32_t>(k)), Xmm::x1);
    if (num_globals_) a_.movaps(Xmm::x0, bits(0x7FC00000u));
    for (int g = 0; g < num_globals_; ++g) a_.movaps(at(global_slot_ + 16 * g), Xmm::x0);
  }
  // After the scan: lanes still waiting (sent back to an earlier block by a later one) rescan;
  // otherwise the outputs go out.
  void finish_group() {
    a_.xorps(Xmm::x0, Xmm::x0);
    for (size_t b = 0; b < order_.size(); ++b) a_.orps(Xmm::x0, pending(static_cast<int>(b)));
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, block_label_[0]);
    for (uint32_t k = 0; k < fn_.num_results; ++k) {
      a_.movaps(Xmm::x0, at(out_slot_ + 16 * static_cast<int32_t>(k)));
      a_.mov(Gp::rax, Mem::at(Gp::r12, 8 * static_cast<int32_t>(k)));
      a_.movups(Mem::at(Gp::rax, Gp::r13, 1), Xmm::x0);
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
        if (!inst(*in, pos, error)) return false;
        release_dead(*in, pos);
      }
      ++pos;
    }
    return true;
  }

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
      slot_of_[v] = spill_base_ + 16 * next_slot_++;
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

  // The result is in d; a value other blocks read also goes to its home, for this block's lanes.
  void define(const ir::Inst& in, Xmm d) {
    held_[static_cast<int>(d)] = static_cast<int>(in.id);
    reg_of_[in.id] = static_cast<int>(d);
    if (home_[in.id] >= 0) masked_store(at(home_[in.id]), {false, d, {}}, at(kActive));
  }
  // dst = mask ? value : dst, lane by lane (a plain store in the entry block: every lane is there).
  void masked_store(const Mem& dst, const Src& value, const Mem& mask) {
    if (cur_ == 0 && mask.disp == kActive) {
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
  Label trap(uint32_t kind, uint32_t line) {
    Label l = a_.new_label();
    traps_.push_back({l, (static_cast<uint64_t>(kind) << 32) | line});
    return l;
  }

  // ---- semantics (runtime/math/math.h, lane by lane) ----
  // min: b NaN ? NaN : (b < a ? b : a); max alike with >. minps(b, a) is (b < a ? b : a), which
  // is already a when a is NaN; a NaN b is caught by its unordered mask, OR-ed in (the result is a
  // NaN; NaN payloads are not part of the semantics). A constant b that is a number needs no mask.
  // d may be b's own register: b is read before d is written.
  void minmax(Xmm d, const Src& a, const Src& b, bool b_number, bool is_min) {
    if (!b_number) {
      load(Xmm::x0, b);
      a_.cmpps(Xmm::x0, Xmm::x0, Pred::Unord);
    }
    load(d, b);
    if (is_min) FS_APPLY(minps, d, a);
    else FS_APPLY(maxps, d, a);
    if (!b_number) a_.orps(d, Xmm::x0);
  }
  static bool number(const ir::Inst* v) { return v->op == ir::Op::Const && v->imm == v->imm; }
  // xmm0 = truthy(c): ordered and != 0.
  void truthy_mask(const Src& c) {
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
      a_.movaps(Mem::at(Gp::rsp, kScratch + 16 * static_cast<int32_t>(i)), Xmm::x0);
    }
    for (int r = kFirstReg; r < kNumRegs; ++r) {  // every xmm register is caller-saved
      if (held_[r] < 0) continue;
      if (next_use(static_cast<uint32_t>(held_[r]), pos) != INT32_MAX) spill(r);
      else reg_of_[held_[r]] = -1, held_[r] = -1;
    }
    Gp arg_regs[4] = {Gp::rdi, Gp::rsi, Gp::rdx, Gp::rcx};
    size_t n = in.args.size();
    for (size_t i = 0; i < n; ++i) a_.lea(arg_regs[i], Mem::at(Gp::rsp, kScratch + 16 * static_cast<int32_t>(i)));
    a_.lea(arg_regs[n], Mem::at(Gp::rsp, kScratch + 48));
    a_.mov_imm(n + 1 < 4 ? arg_regs[n + 1] : Gp::r8, 4);
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(fn));
    a_.call(Gp::rax);
    Xmm d = alloc(pos);
    a_.movaps(d, Mem::at(Gp::rsp, kScratch + 48));
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
  // NaN) takes the batch function itself, out of line.
  void trig(const ir::Inst& in, int pos, int offset) {
    constexpr float kLimit = 8.0e5f;
    Src a = src(in.args[0]);
    Xmm d = alloc(pos), t0 = temp(pos), t1 = temp(pos), t2 = temp(pos), t3 = temp(pos);
    load(Xmm::x1, a);
    a_.movaps(at(kScratch), Xmm::x1);
    a_.movaps(Xmm::x0, Xmm::x1);
    a_.andps(Xmm::x0, bits(0x7FFFFFFFu));
    a_.cmpps(Xmm::x0, k(kLimit), Pred::Le);
    a_.movmskps(Gp::rax, Xmm::x0);
    a_.cmp(Gp::rax, 15);
    SlowPath sp{a_.new_label(), a_.new_label(), d, offset ? reinterpret_cast<const void*>(&math::cos_batch)
                                                          : reinterpret_cast<const void*>(&math::sin_batch)};
    a_.jcc(Cond::NE, sp.entry);
    a_.cvtps2pd(t0, Xmm::x1);
    a_.movhlps(Xmm::x1, Xmm::x1);
    a_.cvtps2pd(t1, Xmm::x1);
    for (auto [h, j] : {std::pair{t0, t2}, std::pair{t1, t3}}) {  // each pair of lanes in double
      a_.movaps(j, h);
      a_.mulpd(j, dbl(0.63661977236758134308));
      a_.addpd(j, dbl(6755399441055744.0));
      a_.subpd(j, dbl(6755399441055744.0));
      a_.movaps(Xmm::x0, j);
      a_.mulpd(Xmm::x0, dbl(1.57079632673412561417e+00));
      a_.subpd(h, Xmm::x0);
      a_.movaps(Xmm::x0, j);
      a_.mulpd(Xmm::x0, dbl(6.07710050650619224932e-11));
      a_.subpd(h, Xmm::x0);
      a_.cvttpd2dq(j, j);
      a_.cvtpd2ps(h, h);
    }
    a_.movlhps(t0, t1);     // r, four lanes
    a_.punpcklqdq(t2, t3);  // q, four lanes
    if (offset) a_.paddd(t2, bits(1));
    a_.movaps(t1, t0);
    a_.mulps(t1, t0);  // z = r * r
    a_.movaps(t3, k(-1.9515295891e-4f));  // sin: ((c1 z + c2) z - c3) z r + r
    a_.mulps(t3, t1);
    a_.addps(t3, k(8.3321608736e-3f));
    a_.mulps(t3, t1);
    a_.subps(t3, k(1.6666654611e-1f));
    a_.mulps(t3, t1);
    a_.mulps(t3, t0);
    a_.addps(t3, t0);
    a_.movaps(d, k(2.443315711809948e-5f));  // cos: ((d1 z - d2) z + d3) z z - 0.5 z + 1
    a_.mulps(d, t1);
    a_.subps(d, k(1.388731625493765e-3f));
    a_.mulps(d, t1);
    a_.addps(d, k(4.166664568298827e-2f));
    a_.mulps(d, t1);
    a_.mulps(d, t1);
    a_.movaps(Xmm::x1, k(0.5f));
    a_.mulps(Xmm::x1, t1);
    a_.subps(d, Xmm::x1);
    a_.addps(d, k(1.0f));
    a_.movaps(Xmm::x0, t2);  // odd quadrant: the cosine polynomial
    a_.pand(Xmm::x0, bits(1));
    a_.pcmpeqd(Xmm::x0, bits(1));
    a_.blendvps(t3, d);
    a_.pand(t2, bits(2));  // quadrants 2 and 3: the sign flips
    a_.pslld(t2, 30);
    a_.xorps(t3, t2);
    a_.movaps(d, t3);
    a_.bind(sp.back);
    slow_.push_back(sp);
    for (Xmm t : {t0, t1, t2, t3}) release(t);
    define(in, d);
  }

  // An array operation: its operands to the scratch slots, every register saved, the helper called
  // with (state, slot, operands..., lane mask); a helper's 1 is a runtime error with its message.
  void array_op(const ir::Inst& in, int pos) {
    for (size_t i = 0; i < in.args.size(); ++i) {
      load(Xmm::x0, src(in.args[i]));
      a_.movaps(at(kScratch + 16 * static_cast<int32_t>(i)), Xmm::x0);
    }
    for (int r = kFirstReg; r < kNumRegs; ++r) {
      if (held_[r] < 0) continue;
      if (next_use(static_cast<uint32_t>(held_[r]), pos) != INT32_MAX) spill(r);
      else drop(static_cast<uint32_t>(held_[r]));
    }
    uint32_t slot = in.array_global ? static_cast<uint32_t>(in.aux) : global_arrays_ + static_cast<uint32_t>(in.aux);
    a_.mov(Gp::rdi, Gp::r15);
    a_.mov_imm(Gp::rsi, slot);
    const void* fn = nullptr;
    switch (in.op) {
      case ir::Op::ANew:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kActive));
        fn = reinterpret_cast<const void*>(&fs_sse_anew);
        break;
      case ir::Op::ALoad:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kScratch + 48));
        a_.lea(Gp::r8, at(kActive));
        fn = reinterpret_cast<const void*>(&fs_sse_aload);
        break;
      case ir::Op::AStore:
        a_.lea(Gp::rdx, at(kScratch));
        a_.lea(Gp::rcx, at(kScratch + 16));
        a_.lea(Gp::r8, at(kActive));
        fn = reinterpret_cast<const void*>(&fs_sse_astore);
        break;
      default:  // ALen
        a_.lea(Gp::rdx, at(kScratch + 48));
        a_.lea(Gp::rcx, at(kActive));
        fn = reinterpret_cast<const void*>(&fs_sse_alen);
        break;
    }
    a_.mov_imm(Gp::rax, reinterpret_cast<uint64_t>(fn));
    a_.call(Gp::rax);
    a_.test(Gp::rax, Gp::rax);
    a_.jcc(Cond::NE, trap(2, in.line));
    if (in.op == ir::Op::ALoad || in.op == ir::Op::ALen) {
      Xmm d = alloc(pos);
      a_.movaps(d, at(kScratch + 48));
      define(in, d);
    }
  }

  bool unsupported(const ir::Inst& in, std::string& error) {
    error = std::string("the sse backend does not compile '") + ir::mnemonic(in.op) +
            "' yet (calls of recursive functions); use --backend vm";
    return false;
  }

  bool inst(const ir::Inst& in, int pos, std::string& error) {
    using ir::Op;
    auto arg = [&](int i) { return src(in.args[i]); };
    // A simple destructive binary op may take over its first operand's register when it dies here.
    auto dest_binary = [&]() {
      const ir::Inst* a = in.args[0];
      if (a->op != Op::Const && reg_of_[a->id] >= 0 && next_use(a->id, pos) == INT32_MAX) {
        Xmm d = static_cast<Xmm>(reg_of_[a->id]);
        held_[reg_of_[a->id]] = -1, reg_of_[a->id] = -1;
        return d;
      }
      return alloc(pos);
    };
    switch (in.op) {
      case Op::Const: return true;  // read from the constant pool where used
      case Op::Param: {
        Xmm d = alloc(pos);
        a_.mov(Gp::rax, Mem::at(Gp::rbx, 8 * in.aux));
        a_.movups(d, Mem::at(Gp::rax, Gp::r13, 1));
        define(in, d);
        return true;
      }
      case Op::Add: case Op::Sub: case Op::Mul: case Op::Div: {
        Src b = arg(1);
        Src a = arg(0);
        Xmm d = dest_binary();
        load(d, a);
        if (in.op == Op::Add) FS_APPLY(addps, d, b);
        if (in.op == Op::Sub) FS_APPLY(subps, d, b);
        if (in.op == Op::Mul) FS_APPLY(mulps, d, b);
        if (in.op == Op::Div) FS_APPLY(divps, d, b);
        define(in, d);
        return true;
      }
      case Op::Neg: case Op::Abs: {
        Src a = arg(0);
        Xmm d = dest_binary();
        load(d, a);
        if (in.op == Op::Neg) a_.xorps(d, bits(0x80000000u));
        else a_.andps(d, bits(0x7FFFFFFFu));
        define(in, d);
        return true;
      }
      case Op::Sqrt: {
        Xmm d = alloc(pos);
        FS_APPLY(sqrtps, d, arg(0));
        define(in, d);
        return true;
      }
      case Op::Floor: case Op::Ceil: {
        Xmm d = alloc(pos);
        load(Xmm::x1, arg(0));
        a_.roundps(d, Xmm::x1, in.op == Op::Floor ? Rounding::Down : Rounding::Up);
        define(in, d);
        return true;
      }
      case Op::Round: {  // f = floor(a); a - f >= 0.5 ? f + 1 : f
        Xmm d = alloc(pos);
        load(Xmm::x1, arg(0));
        a_.roundps(d, Xmm::x1, Rounding::Down);
        a_.subps(Xmm::x1, d);
        a_.movaps(Xmm::x0, k(0.5f));
        a_.cmpps(Xmm::x0, Xmm::x1, Pred::Le);
        a_.movaps(Xmm::x1, d);
        a_.addps(Xmm::x1, k(1.0f));
        a_.blendvps(d, Xmm::x1);
        define(in, d);
        return true;
      }
      case Op::Sign: {  // a > 0 ? 1 : (a < 0 ? -1 : a)
        Xmm d = alloc(pos);
        Src a = arg(0);
        a_.movaps(Xmm::x1, k(0.0f));
        if (a.mem) a_.cmpps(Xmm::x1, a.m, Pred::Lt);
        else a_.cmpps(Xmm::x1, a.x, Pred::Lt);
        load(Xmm::x0, a);
        a_.cmpps(Xmm::x0, k(0.0f), Pred::Lt);
        load(d, a);
        a_.blendvps(d, k(-1.0f));
        a_.movaps(Xmm::x0, Xmm::x1);
        a_.blendvps(d, k(1.0f));
        define(in, d);
        return true;
      }
      case Op::Min: case Op::Max: {
        const ir::Inst* b = in.args[1];
        Src sa = arg(0), sb = arg(1);
        Xmm d;
        if (b->op != Op::Const && reg_of_[b->id] >= 0 && next_use(b->id, pos) == INT32_MAX) {
          d = static_cast<Xmm>(reg_of_[b->id]);  // b dies here: its register takes the result
          drop(b->id);
        } else {
          d = alloc(pos);
        }
        minmax(d, sa, sb, number(b), in.op == Op::Min);
        define(in, d);
        return true;
      }
      case Op::Clamp: {  // min(max(a, lo), hi)
        Xmm d = alloc(pos);
        minmax(Xmm::x1, arg(0), arg(1), number(in.args[1]), false);
        minmax(d, {false, Xmm::x1, {}}, arg(2), number(in.args[2]), true);
        define(in, d);
        return true;
      }
      case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: {
        Xmm d = alloc(pos);
        Src a = arg(0), b = arg(1);
        switch (in.op) {
          case Op::Eq: compare(d, a, b, Pred::Eq); break;
          case Op::Ne: compare(d, a, b, Pred::Neq); break;
          case Op::Lt: compare(d, a, b, Pred::Lt); break;
          case Op::Le: compare(d, a, b, Pred::Le); break;
          case Op::Gt: compare(d, b, a, Pred::Lt); break;
          default: compare(d, b, a, Pred::Le); break;  // Ge
        }
        define(in, d);
        return true;
      }
      case Op::Not: case Op::Truth: {
        Xmm d = alloc(pos);
        truthy_mask(arg(0));
        a_.movaps(d, Xmm::x0);
        if (in.op == Op::Not) a_.andnps(d, k(1.0f));
        else a_.andps(d, k(1.0f));
        define(in, d);
        return true;
      }
      case Op::Select: {
        Xmm d = alloc(pos);
        truthy_mask(arg(0));
        load(d, arg(2));
        FS_APPLY(blendvps, d, arg(1));
        define(in, d);
        return true;
      }
      case Op::Mod: return call(in, pos, reinterpret_cast<const void*>(&mod_batch));
      case Op::Pow: return call(in, pos, reinterpret_cast<const void*>(&math::pow_batch));
      case Op::Exp: return call(in, pos, reinterpret_cast<const void*>(&math::exp_batch));
      case Op::Log: return call(in, pos, reinterpret_cast<const void*>(&math::log_batch));
      case Op::Log10: return call(in, pos, reinterpret_cast<const void*>(&math::log10_batch));
      case Op::Sin: return trig(in, pos, 0), true;
      case Op::Cos: return trig(in, pos, 1), true;
      case Op::Tan: return call(in, pos, reinterpret_cast<const void*>(&math::tan_batch));
      case Op::Asin: return call(in, pos, reinterpret_cast<const void*>(&math::asin_batch));
      case Op::Acos: return call(in, pos, reinterpret_cast<const void*>(&math::acos_batch));
      case Op::Atan: return call(in, pos, reinterpret_cast<const void*>(&math::atan_batch));
      case Op::Atan2: return call(in, pos, reinterpret_cast<const void*>(&math::atan2_batch));
      case Op::Sinh: return call(in, pos, reinterpret_cast<const void*>(&math::sinh_batch));
      case Op::Cosh: return call(in, pos, reinterpret_cast<const void*>(&math::cosh_batch));
      case Op::Tanh: return call(in, pos, reinterpret_cast<const void*>(&math::tanh_batch));
      case Op::Noise: return call(in, pos, reinterpret_cast<const void*>(&noise_batch));
      case Op::Ret:
        for (size_t o = 0; o < in.args.size(); ++o) {
          Src s = src(in.args[o]);
          if (!straight_) {  // lanes return at different times: collect under the block's mask
            masked_store(at(out_slot_ + 16 * static_cast<int32_t>(o)), s, at(kActive));
            continue;
          }
          if (s.mem) a_.movaps(Xmm::x0, s.m), s = {false, Xmm::x0, {}};
          a_.mov(Gp::rax, Mem::at(Gp::r12, 8 * static_cast<int32_t>(o)));
          a_.movups(Mem::at(Gp::rax, Gp::r13, 1), s.x);
        }
        return true;
      case Op::Jump:
        a_.movaps(Xmm::x0, at(kActive));
        a_.movaps(at(kEdge0), Xmm::x0);
        edge(in.targets[0], at(kEdge0));
        back_edge(in.targets[0], at(kEdge0));
        return true;
      case Op::Branch: {  // lanes where the condition is truthy take targets[0]
        truthy_mask(arg(0));
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
        return true;
      }
      case Op::Tick: {  // per-lane iteration counters (int32): counter - mask adds one per active lane
        a_.movaps(Xmm::x0, at(kCounters));
        a_.psubd(Xmm::x0, at(kActive));
        a_.movaps(at(kCounters), Xmm::x0);
        a_.pcmpgtd(Xmm::x0, bits(static_cast<uint32_t>(budget_)));
        a_.movmskps(Gp::rax, Xmm::x0);
        a_.test(Gp::rax, Gp::rax);
        a_.jcc(Cond::NE, trap(1, in.line));
        return true;
      }
      case Op::GLoad: {
        Xmm d = alloc(pos);
        a_.movaps(d, at(global_slot_ + 16 * in.aux));
        define(in, d);
        return true;
      }
      case Op::GStore:
        masked_store(at(global_slot_ + 16 * in.aux), arg(0), at(kActive));
        return true;
      case Op::Phi: return true;  // its home is written on the incoming edges
      case Op::ANew: case Op::ALoad: case Op::AStore: case Op::ALen:
        array_op(in, pos);
        return true;
      case Op::Call:
        return unsupported(in, error);
    }
    return unsupported(in, error);
  }

  const ir::Function& fn_;
  int32_t budget_;
  std::vector<size_t> frame_fields_;
  Assembler a_;
  Label exit_;
  std::vector<Label> block_label_;  // one per block in order, then the end of the scan
  std::vector<std::pair<Label, uint64_t>> traps_;
  std::vector<const ir::Block*> order_;
  std::vector<int> block_index_, block_start_, block_end_, def_block_;
  std::vector<bool> cross_;
  std::vector<std::vector<int>> uses_;
  std::vector<int> reg_of_, slot_of_, home_;
  std::array<int, kNumRegs> held_{};
  bool straight_ = true, arrays_ = false;
  uint32_t global_arrays_ = 0;  // array slots: the module's global arrays first, then the kernel's
  int cur_ = 0, next_slot_ = 0, max_phis_ = 0, phis_here_ = 0, num_globals_ = 0;
  int32_t out_slot_ = 0, pending_slot_ = 0, global_slot_ = 0, temp_slot_ = 0, save_slot_ = 0, spill_base_ = 0;
  struct SlowPath {  // a call of a batch function out of line: every register saved around it
    Label entry, back;
    Xmm result;
    const void* fn;
  };
  std::vector<SlowPath> slow_;
};

#undef FS_APPLY

}  // namespace

std::vector<uint8_t> generate(const ir::Module& module, const backend::Budgets& budgets, std::string& error,
                              std::string* listing, std::vector<std::string>* array_names) {
  // Masked lanes have no call stack: calls of non-recursive functions are inlined first (an
  // unoptimised module still has them); calls of recursive ones are refused below.
  std::unique_ptr<ir::Module> inlined;
  const ir::Module* mp = &module;
  for (const auto& f : module.functions)
    for (const auto& blk : f->blocks)
      for (const ir::Inst* in : blk->insts)
        if (in->op == ir::Op::Call && !inlined) {
          inlined = module.clone();
          error = ir::run_passes(*inlined, "inline");
          if (!error.empty()) return {};
          mp = inlined.get();
        }
  const ir::Module& m = *mp;
  const ir::Function* fn = nullptr;
  for (const auto& f : m.functions)
    if (f->kernel) fn = f.get();
  if (!fn) {
    error = "the module has no kernel function";
    return {};
  }
  if (array_names) {
    *array_names = m.arrays;
    array_names->insert(array_names->end(), fn->arrays.begin(), fn->arrays.end());
  }
  Codegen gen(*fn, budgets, static_cast<uint32_t>(m.arrays.size()));
  if (listing) gen.enable_listing();
  if (!gen.run(error)) return {};
  std::vector<uint8_t> code = gen.finish();
  if (listing) *listing = gen.listing();
  return code;
}

}  // namespace fscript::sse
