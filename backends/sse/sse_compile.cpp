// SSA to x86-64 for straight-line kernels. Four points per iteration, one value per xmm register.
// Registers are assigned while emitting, in instruction order: a free register if there is one,
// else the value whose next use is farthest is spilled to its 16-byte stack slot (Belady's rule,
// optimal for one block); spilled values and constants (rip-relative, from the pool) are read
// straight from memory by the instructions that use them. xmm0 and xmm1 are scratch (xmm0 is
// blendvps's implicit mask). Runtime calls (transcendentals, fmod, noise) go through the batch
// functions of runtime/math on four lanes in stack slots; every live register is saved first.
#include <algorithm>
#include <cstring>
#include <map>

#include "backends/sse/sse_backend.h"
#include "backends/sse/x86.h"
#include "runtime/math/math.h"

namespace fscript::sse {
namespace {

constexpr int kFirstReg = 2, kNumRegs = 16;
constexpr int32_t kScratch = 0;  // call arguments at 0, 16, 32; result at 48
constexpr int32_t kSlots = 64;   // spill slots from here, 16 bytes each

void mod_batch(const float* a, const float* b, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = math::mod(a[i], b[i]);
}
void noise_batch(const float* x, const float* y, const float* z, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = math::noise(x[i], y[i], z[i]);
}

// A source operand: a register or a memory location (spill slot or constant).
struct Src {
  bool mem;
  Xmm x;
  Mem m;
};

#define FS_APPLY(method, d, s) ((s).mem ? a_.method(d, (s).m) : a_.method(d, (s).x))

class Codegen {
 public:
  Codegen(const ir::Function& fn, int frame_slots) : fn_(fn), frame_slots_(frame_slots) {}

  bool run(std::string& error) {
    const ir::Block& b = *fn_.entry();
    index_uses(b);
    prologue();
    Label top = a_.new_label(), done = a_.new_label();
    a_.bind(top);
    a_.cmp(Gp::r13, Gp::r14);
    a_.jcc(Cond::AE, done);
    for (size_t pos = 0; pos < b.insts.size(); ++pos) {
      if (!inst(*b.insts[pos], static_cast<int>(pos), error)) return false;
      release_dead(*b.insts[pos], static_cast<int>(pos));
    }
    a_.add(Gp::r13, 16);
    a_.jmp(top);
    a_.bind(done);
    epilogue();
    return true;
  }

  int slots_used() const { return next_slot_; }
  void enable_listing() { a_.enable_listing(); }
  std::string listing() const { return a_.listing(); }
  std::vector<uint8_t> finish() { return a_.finish(); }

 private:
  // ---- frame: rbx inputs, r12 outputs, r13 byte offset of the point, r14 end offset ----
  int32_t frame_bytes() const { return kSlots + 16 * frame_slots_ + 8; }  // + 8: realigns after six pushes
  void prologue() {
    for (Gp g : {Gp::rbx, Gp::rbp, Gp::r12, Gp::r13, Gp::r14, Gp::r15}) a_.push(g);
    a_.sub(Gp::rsp, frame_bytes());
    a_.mov(Gp::rbx, Gp::rdi);
    a_.mov(Gp::r12, Gp::rsi);
    a_.lea(Gp::r13, Mem::at(Gp::rdx, Gp::rdx, 2));  // 3 begin... then + begin: 4 begin
    a_.add(Gp::r13, Gp::rdx);
    a_.lea(Gp::r14, Mem::at(Gp::rcx, Gp::rcx, 2));
    a_.add(Gp::r14, Gp::rcx);
  }
  void epilogue() {
    a_.add(Gp::rsp, frame_bytes());
    for (Gp g : {Gp::r15, Gp::r14, Gp::r13, Gp::r12, Gp::rbp, Gp::rbx}) a_.pop(g);
    a_.ret();
  }

  // ---- uses and liveness ----
  void index_uses(const ir::Block& b) {
    uses_.assign(fn_.next_value, {});
    for (size_t pos = 0; pos < b.insts.size(); ++pos)
      for (const ir::Inst* arg : b.insts[pos]->args) uses_[arg->id].push_back(static_cast<int>(pos));
    reg_of_.assign(fn_.next_value, -1);
    slot_of_.assign(fn_.next_value, -1);
    held_.fill(-1);
  }
  int next_use(uint32_t v, int pos) const {  // first use after pos, or INT_MAX
    const auto& u = uses_[v];
    auto it = std::upper_bound(u.begin(), u.end(), pos);
    return it == u.end() ? INT32_MAX : *it;
  }
  void release_dead(const ir::Inst& in, int pos) {
    for (const ir::Inst* arg : in.args)
      if (next_use(arg->id, pos) == INT32_MAX && reg_of_[arg->id] >= 0) {
        held_[reg_of_[arg->id]] = -1;
        reg_of_[arg->id] = -1;
      }
    if (in.defines_value() && uses_[in.id].empty() && reg_of_[in.id] >= 0) {
      held_[reg_of_[in.id]] = -1;
      reg_of_[in.id] = -1;
    }
  }

  // ---- registers ----
  Mem slot_mem(int slot) const { return Mem::at(Gp::rsp, kSlots + 16 * slot); }
  void spill(int reg) {
    uint32_t v = static_cast<uint32_t>(held_[reg]);
    if (slot_of_[v] < 0) {
      slot_of_[v] = next_slot_++;
      a_.movaps(slot_mem(slot_of_[v]), static_cast<Xmm>(reg));
    }
    reg_of_[v] = -1;
    held_[reg] = -1;
  }
  // A free register for the result of the instruction at pos; operands of that instruction stay.
  Xmm alloc(int pos) {
    int best = -1, best_use = -1;
    for (int r = kFirstReg; r < kNumRegs; ++r) {
      if (held_[r] < 0) return static_cast<Xmm>(r);
      int u = next_use(static_cast<uint32_t>(held_[r]), pos - 1);
      if (u != pos && u > best_use) best = r, best_use = u;
    }
    spill(best);
    return static_cast<Xmm>(best);
  }
  void define(const ir::Inst& in, Xmm d) {
    held_[static_cast<int>(d)] = static_cast<int>(in.id);
    reg_of_[in.id] = static_cast<int>(d);
  }
  Src src(const ir::Inst* v) {
    if (v->op == ir::Op::Const) return {true, Xmm::x0, Mem::rip(a_.constant_ps(v->imm))};
    if (reg_of_[v->id] >= 0) return {false, static_cast<Xmm>(reg_of_[v->id]), {}};
    return {true, Xmm::x0, slot_mem(slot_of_[v->id])};
  }
  Mem k(float v) { return Mem::rip(a_.constant_ps(v)); }
  Mem bits(uint32_t b) { return Mem::rip(a_.constant({b, b, b, b})); }
  void load(Xmm d, const Src& s) {
    if (s.mem || s.x != d) FS_APPLY(movaps, d, s);
  }

  // ---- semantics (runtime/math/math.h, lane by lane) ----
  // min: b NaN ? b : (b < a ? b : a); max alike with >. minps/maxps return their second operand
  // when either is NaN, hence b first.
  void minmax(Xmm d, const Src& a, const Src& b, bool is_min) {
    load(Xmm::x1, b);
    if (is_min) FS_APPLY(minps, Xmm::x1, a);
    else FS_APPLY(maxps, Xmm::x1, a);
    load(Xmm::x0, b);
    a_.cmpps(Xmm::x0, Xmm::x0, Pred::Unord);
    a_.movaps(d, Xmm::x1);
    FS_APPLY(blendvps, d, b);
  }
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

  bool unsupported(const ir::Inst& in, std::string& error) {
    error = std::string("the sse backend does not compile '") + ir::mnemonic(in.op) +
            "' yet (it compiles straight-line kernels: no loops, arrays, global memory or recursion); use --backend vm";
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
        Xmm d = alloc(pos);
        minmax(d, arg(0), arg(1), in.op == Op::Min);
        define(in, d);
        return true;
      }
      case Op::Clamp: {  // min(max(a, lo), hi)
        Xmm d = alloc(pos);
        minmax(d, arg(0), arg(1), false);
        minmax(d, {false, d, {}}, arg(2), true);
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
      case Op::Sin: return call(in, pos, reinterpret_cast<const void*>(&math::sin_batch));
      case Op::Cos: return call(in, pos, reinterpret_cast<const void*>(&math::cos_batch));
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
          if (s.mem) a_.movaps(Xmm::x0, s.m), s = {false, Xmm::x0, {}};
          a_.mov(Gp::rax, Mem::at(Gp::r12, 8 * static_cast<int32_t>(o)));
          a_.movups(Mem::at(Gp::rax, Gp::r13, 1), s.x);
        }
        return true;
      case Op::Phi: case Op::GLoad: case Op::GStore: case Op::ANew: case Op::ALoad: case Op::AStore:
      case Op::ALen: case Op::Call: case Op::Tick: case Op::Jump: case Op::Branch:
        return unsupported(in, error);
    }
    return unsupported(in, error);
  }

  const ir::Function& fn_;
  int frame_slots_;
  Assembler a_;
  std::vector<std::vector<int>> uses_;
  std::vector<int> reg_of_, slot_of_;
  std::array<int, kNumRegs> held_{};
  int next_slot_ = 0;
};

#undef FS_APPLY

}  // namespace

std::vector<uint8_t> generate(const ir::Module& m, std::string& error, std::string* listing) {
  const ir::Function* fn = nullptr;
  for (const auto& f : m.functions)
    if (f->kernel) fn = f.get();
  if (!fn) {
    error = "the module has no kernel function";
    return {};
  }
  if (fn->blocks.size() != 1) {
    error = "the sse backend compiles straight-line kernels only so far; this one keeps " +
            std::to_string(fn->blocks.size()) + " blocks (a loop or a branch); use --backend vm";
    return {};
  }
  // Twice: the first pass counts the spill slots the frame must hold.
  Codegen sizing(*fn, 0);
  if (!sizing.run(error)) return {};
  Codegen final_pass(*fn, sizing.slots_used());
  if (listing) final_pass.enable_listing();
  if (!final_pass.run(error)) return {};
  std::vector<uint8_t> code = final_pass.finish();
  if (listing) *listing = final_pass.listing();
  return code;
}

}  // namespace fscript::sse
