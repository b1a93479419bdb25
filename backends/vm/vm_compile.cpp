// IR -> VM bytecode: register assignment by linear scan, constants as immediates of binary ops
// (or registers filled once per run), phis as parallel copies on the edges, and in straight-line
// functions pairs of lane ops fused (bytecode.h).
#include <algorithm>
#include <unordered_map>

#include "backends/regalloc.h"
#include "backends/vm/bytecode.h"
#include "ir/text.h"

namespace fscript::vm {
namespace {

using ir::Inst;
using ir::Op;

class FunctionCompiler {
 public:
  FunctionCompiler(const ir::Function& fn, VmFunction& out) : fn_(fn), out_(out) {}

  void run() {
    out_.name = fn_.name;
    out_.num_params = fn_.num_params;
    out_.num_results = fn_.num_results;
    out_.recursive = fn_.recursive;
    out_.num_arrays = static_cast<uint32_t>(fn_.arrays.size());
    out_.array_names = fn_.arrays;
    lo_ = backends::compute_intervals(fn_);
    // The executor fills parameter registers before the first instruction, wherever the Param sits
    // (a row split's body places them at their first use).
    for (const auto& b : fn_.blocks)
      for (const Inst* i : b->insts)
        if (i->op == Op::Param) lo_.interval[i->id].start = 0;
    reg_ = backends::linear_scan(fn_, lo_, [&](const Inst* i) { return i->op == Op::Const; }, out_.num_regs);
    out_.param_regs.assign(fn_.num_params, kNoReg);
    for (size_t k = 0; k < lo_.blocks.size(); ++k) block_index_[lo_.blocks[k]] = static_cast<uint32_t>(k);
    count_uses();
    for (ir::Block* b : lo_.blocks) emit_block(b);
  }

 private:
  uint32_t const_reg(const Inst* c) {
    auto it = const_regs_.find(c);
    if (it != const_regs_.end()) return it->second;
    uint32_t r = out_.num_regs++;
    out_.consts.push_back({r, c->imm});
    return const_regs_[c] = r;
  }

  uint32_t r(const Inst* v) { return v->op == Op::Const ? const_reg(v) : reg_[v->id]; }

  // The block's sin and cos of one value, paired (bytecode.h): each pair's extra register, by its
  // two instructions.
  void pair_trig(const ir::Block* b) {
    trig_.clear();
    std::unordered_map<const Inst*, const Inst*> open[2];  // by operand: an unpaired sin, cos
    for (const Inst* i : b->insts) {
      if (i->op != Op::Sin && i->op != Op::Cos) continue;
      int kind = i->op == Op::Cos, other = 1 - kind;
      auto it = open[other].find(i->args[0]);
      if (it == open[other].end()) {
        open[kind].emplace(i->args[0], i);
        continue;
      }
      uint32_t extra = out_.num_regs++;
      trig_[it->second] = {kTrigFirst, extra}, trig_[i] = {kTrigSecond, extra};
      open[other].erase(it);
    }
  }

  void count_uses() {
    uses_.assign(fn_.next_value, 0);
    for (const auto& b : fn_.blocks)
      for (const Inst* i : b->insts)
        for (const Inst* a : i->args) ++uses_[a->id];
  }

  // i's value, read by j alone and once, where both ops fuse (straight-line functions only: a
  // fused instruction runs every lane).
  bool fuses(const Inst* i, const Inst* j) const {
    if (fn_.blocks.size() != 1 || fuse_first_index(i->op) < 0 || fuse_second_index(j->op) < 0) return false;
    if (uses_[i->id] != 1 || std::count(j->args.begin(), j->args.end(), i) != 1) return false;
    // a must be a register: a constant first operand only of + and * (exact either way round).
    return i->args[0]->op != Op::Const || (i->args.size() > 1 && i->args[1]->op != Op::Const && commutative(i->op));
  }
  // i then s = i * i, where i's value is read by s alone (squared pairs: fuses(s, next) as well).
  bool squares(const Inst* i, const Inst* s) const {
    if (fn_.blocks.size() != 1 || fuse_squared_index(i->op) < 0 || s->op != Op::Mul) return false;
    if (uses_[i->id] != 2 || s->args[0] != i || s->args[1] != i) return false;
    return i->args[0]->op != Op::Const || (i->args[1]->op != Op::Const && commutative(i->op));
  }
  static bool commutative(Op op) { return op == Op::Add || op == Op::Mul; }
  // i and its one reader j; with `square`, i's value squared (s) is what j reads.
  void emit_fused(const Inst& i, const Inst& j, const Inst* square = nullptr) {
    const Inst* t = square ? square : &i;
    VInst v;
    v.squared = square != nullptr;
    v.op = i.op, v.op2 = j.op;
    v.line = j.line, v.col = j.col;
    v.dst = reg_[j.id];
    const Inst* a = i.args[0];
    const Inst* b = i.args.size() > 1 ? i.args[1] : nullptr;
    if (a->op == Op::Const) std::swap(a, b);  // fuses() allows it for + and * only
    v.a = r(a);
    if (b && b->op == Op::Const) v.kinds |= 2, v.imm_b = b->imm;
    else if (b) v.b = r(b);
    v.fused = j.args[0] == t ? kFuseCLast : kFuseCFirst;
    if (j.args.size() > 1) {
      const Inst* c = j.args[j.args[0] == t ? 1 : 0];
      if (c->op == Op::Const) v.kinds |= 4, v.imm_c = c->imm;
      else v.c = r(c);
    }
    out_.code.push_back(v);
  }

  void emit_block(ir::Block* b) {
    VBlock vb;
    vb.begin = static_cast<uint32_t>(out_.code.size());
    pair_trig(b);
    std::vector<const Inst*> seq;
    for (const Inst* i : b->insts) {
      if (i->op == Op::Phi || i->op == Op::Const) continue;
      if (ir::has_flag(i->op, ir::Terminator)) break;
      seq.push_back(i);
    }
    for (size_t k = 0; k < seq.size(); ++k) {
      if (k + 2 < seq.size() && squares(seq[k], seq[k + 1]) && fuses(seq[k + 1], seq[k + 2])) {
        emit_fused(*seq[k], *seq[k + 2], seq[k + 1]);
        k += 2;
        continue;
      }
      if (k + 1 < seq.size() && fuses(seq[k], seq[k + 1])) {
        emit_fused(*seq[k], *seq[k + 1]);
        ++k;
        continue;
      }
      emit(*seq[k]);
    }
    vb.end = static_cast<uint32_t>(out_.code.size());
    const Inst* t = b->terminator();
    vb.term = t->op;
    switch (t->op) {
      case Op::Jump: vb.edges[0] = edge(b, t->targets[0]); break;
      case Op::Branch:
        vb.cond = r(t->args[0]);
        vb.edges[0] = edge(b, t->targets[0]);
        vb.edges[1] = edge(b, t->targets[1]);
        break;
      case Op::Ret:
        for (const Inst* a : t->args) vb.results.push_back(r(a));
        break;
      default: break;
    }
    out_.blocks.push_back(std::move(vb));
  }

  Edge edge(ir::Block* from, ir::Block* to) {
    Edge e;
    e.block = block_index_.at(to);
    for (const Inst* p : to->insts) {
      if (p->op != Op::Phi) break;
      if (reg_[p->id] == kNoReg) continue;
      for (size_t k = 0; k < p->args.size(); ++k)
        if (p->targets[k] == from) e.moves.push_back({reg_[p->id], r(p->args[k])});
    }
    return e;
  }

  void emit(const Inst& i) {
    VInst v;
    v.op = i.op;
    v.aux = i.aux;
    v.array_global = i.array_global;
    v.line = i.line;
    v.col = i.col;
    if (i.defines_value()) v.dst = reg_[i.id];
    if (i.op == Op::Param) out_.param_regs[i.aux] = v.dst;
    if (i.op == Op::Call) {
      std::vector<uint32_t> args;
      for (const Inst* a : i.args) args.push_back(r(a));
      v.aux = static_cast<int32_t>(out_.lists.size());
      out_.lists.push_back(std::move(args));
      v.c = static_cast<uint32_t>(i.aux);  // callee
      out_.code.push_back(v);
      return;
    }
    uint32_t* slots[3] = {&v.a, &v.b, &v.c};
    for (size_t k = 0; k < i.args.size() && k < 3; ++k) {
      const Inst* a = i.args[k];
      if (a->op == Op::Const && takes_immediates(i.op)) {
        v.kinds |= static_cast<uint8_t>(1u << k);
        (k == 0 ? v.imm_a : v.imm_b) = a->imm;
      } else {
        *slots[k] = r(a);
      }
    }
    if (auto t = trig_.find(&i); t != trig_.end()) v.aux = t->second.first, v.c = t->second.second;
    out_.code.push_back(v);
  }

  const ir::Function& fn_;
  VmFunction& out_;
  backends::LinearOrder lo_;
  std::vector<uint32_t> reg_;
  std::unordered_map<const Inst*, uint32_t> const_regs_;
  std::unordered_map<const ir::Block*, uint32_t> block_index_;
  std::unordered_map<const Inst*, std::pair<int32_t, uint32_t>> trig_;  // pair_trig's, for this block
  std::vector<uint32_t> uses_;  // by value id: how many operands read it
};

// Straight-line code reordered for fusion: a value whose one reader would fuse with it
// (FunctionCompiler::fuses, ::squares) moves down to just before that reader, with the values it
// pulls in turn. Sources write `dx = x - a; dy = y - b; dz = z - c; sqrt(dx * dx + dy * dy +
// dz * dz)`, which leaves each subtraction apart from its square. Only such chains move (moving
// whole expression trees to their roots made prospero's live values 127 -> 959 registers), each
// reader pulls at most one operand (one can sit next to it), and every op is pure, so the values
// do not change.
class FusionOrder {
 public:
  // The block's instructions in fusion order (the block itself untouched).
  static std::vector<Inst*> of(const ir::Block& b) {
    for (const Inst* i : b.insts)
      if (i->op != Op::Ret && !ir::has_flag(i->op, ir::Pure)) return b.insts;
    uint32_t ids = b.fn->next_value;
    std::vector<uint32_t> readers(ids, 0), at(ids, 0);
    std::vector<const Inst*> last_reader(ids, nullptr);
    for (const Inst* i : b.insts)
      for (const Inst* a : i->args)
        if (last_reader[a->id] != i) last_reader[a->id] = i, ++readers[a->id];
    for (size_t k = 0; k < b.insts.size(); ++k) at[b.insts[k]->id] = static_cast<uint32_t>(k);
    std::vector<Inst*> pulled(ids, nullptr);  // by reader id: the operand it pulls next to itself
    std::vector<char> moved(ids, 0);
    for (Inst* j : b.insts) {
      Inst* best = nullptr;
      for (Inst* a : j->args)
        if (readers[a->id] == 1 && wants_next(*a, *j) && (!best || at[a->id] > at[best->id])) best = a;
      if (best) pulled[j->id] = best, moved[best->id] = 1;
    }
    std::vector<Inst*> order, chain;
    for (Inst* x : b.insts) {
      if (moved[x->id]) continue;
      for (Inst* c = x; c; c = pulled[c->id]) chain.push_back(c);
      order.insert(order.end(), chain.rbegin(), chain.rend());
      chain.clear();
    }
    return order;
  }

 private:
  // j, i's only reader, would take i fused: as a pair's second op, or as i's square.
  static bool wants_next(const Inst& i, const Inst& j) {
    if (!i.defines_value() || i.op == Op::Param || i.op == Op::Const) return false;
    bool square_of_i = j.op == Op::Mul && j.args[0] == &i && j.args[1] == &i;
    if (square_of_i) return fuse_squared_index(i.op) >= 0;
    return fuse_first_index(i.op) >= 0 && fuse_second_index(j.op) >= 0;
  }
};

// A one-block function seen with its block in fusion order: a shell whose block lists the
// original's instructions (owned by the original; the caller's module may be compiled by another
// thread at the same time, so it is not reordered in place, and a copy cost 2 ms on prospero).
std::unique_ptr<ir::Function> fusion_view(const ir::Function& fn) {
  auto v = ir::shell_of(fn);
  ir::Block* b = v->add_block();
  b->id = fn.entry()->id;
  b->insts = FusionOrder::of(*fn.entry());
  v->next_value = fn.next_value;
  v->next_block = fn.next_block;
  return v;
}

}  // namespace

bool compile_program(const ir::Module& m, VmProgram& out, std::string& error) {
  out.functions.clear();
  out.num_globals = static_cast<uint32_t>(m.globals.size());
  out.num_global_arrays = static_cast<uint32_t>(m.arrays.size());
  out.global_names = m.globals;
  out.global_array_names = m.arrays;
  bool found = false;
  for (size_t k = 0; k < m.functions.size(); ++k) {
    out.functions.emplace_back();
    const ir::Function& fn = *m.functions[k];
    std::unique_ptr<ir::Function> view = fn.blocks.size() == 1 ? fusion_view(fn) : nullptr;
    FunctionCompiler(view ? *view : fn, out.functions.back()).run();
    if (m.functions[k]->kernel) {
      out.kernel = static_cast<uint32_t>(k);
      out.row_params_from = m.functions[k]->row_params_from;
      found = true;
    }
  }
  for (const auto& f : out.functions)
    for (const auto& v : f.code) switch (v.op) {
        case Op::Tick:
        case Op::Call:
        case Op::GLoad:
        case Op::GStore:
        case Op::ANew:
        case Op::ALoad:
        case Op::AStore:
        case Op::ALen: out.needs_lane_state = true; break;
        default: break;
      }
  if (!found) error = "the module has no kernel function";
  return found;
}

std::string disassemble(const VmProgram& p) {
  std::string s;
  for (const auto& f : p.functions) {
    s += "function " + f.name + " (" + std::to_string(f.num_regs) + " registers)\n";
    for (auto [r, v] : f.consts) s += "  r" + std::to_string(r) + " := " + ir::format_float(v) + "\n";
    for (size_t b = 0; b < f.blocks.size(); ++b) {
      const VBlock& vb = f.blocks[b];
      s += "B" + std::to_string(b) + ":\n";
      for (uint32_t k = vb.begin; k < vb.end; ++k) {
        const VInst& v = f.code[k];
        s += "  ";
        if (v.dst != kNoReg) s += "r" + std::to_string(v.dst) + " = ";
        auto operand = [&](int idx, uint32_t reg, float imm) {
          if (v.kinds & (1u << idx)) s += " #" + ir::format_float(imm);
          else if (reg != kNoReg) s += " r" + std::to_string(reg);
        };
        // e.g. r5 = fmul r1 r1 -> fadd r3 _ (the first op's value in the place of _), or
        // r5 = fsub r1 #0.5 -> square -> fadd r3 _
        if (v.fused) {
          s += ir::mnemonic(v.op);
          operand(0, v.a, 0);
          operand(1, v.b, v.imm_b);
          if (v.squared) s += " -> square";
          s += std::string(" -> ") + ir::mnemonic(v.op2);
          std::string c = v.kinds & 4 ? "#" + ir::format_float(v.imm_c)
              : v.c != kNoReg         ? "r" + std::to_string(v.c)
                                      : "";
          if (!c.empty()) s += v.fused == kFuseCFirst ? " " + c + " _" : " _ " + c;
          s += "\n";
          continue;
        }
        s += ir::mnemonic(v.op);
        operand(0, v.a, v.imm_a);
        operand(1, v.b, v.imm_b);
        if ((v.op == ir::Op::Sin || v.op == ir::Op::Cos) && v.c != kNoReg)  // a pair (bytecode.h)
          s += v.aux == kTrigFirst ? std::string(" (and its ") + (v.op == ir::Op::Sin ? "cos" : "sin") + " into r" +
                  std::to_string(v.c) + ")"
                                   : " (computed with its pair, from r" + std::to_string(v.c) + ")";
        else operand(2, v.c, 0);
        s += "\n";
      }
      s += "  " + std::string(ir::mnemonic(vb.term));
      if (vb.term == ir::Op::Branch) s += " r" + std::to_string(vb.cond);
      for (int e = 0; e < (vb.term == ir::Op::Branch ? 2 : vb.term == ir::Op::Jump ? 1 : 0); ++e) {
        s += " B" + std::to_string(vb.edges[e].block);
        for (auto mv : vb.edges[e].moves) s += " [r" + std::to_string(mv.dst) + "<-r" + std::to_string(mv.src) + "]";
      }
      for (uint32_t r : vb.results) s += " r" + std::to_string(r);
      s += "\n";
    }
  }
  return s;
}

}  // namespace fscript::vm
