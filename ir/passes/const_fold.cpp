// Constant folding through runtime/math (so a folded value equals the run-time one bit for bit),
// plus identities exact in IEEE arithmetic, the sign of zero included: x*1, x/1, x+(-0), x-(+0),
// --x, select on a constant or on equal arms. Not x+0: -0 + 0 is +0, and a zero's sign shows
// through a division (1 / (y + 0) at y = -0 is inf; folded, it was -inf).
#include <algorithm>
#include <cmath>
#include <vector>

#include "ir/eval.h"
#include "ir/passes/passes.h"
#include "runtime/math/math.h"

namespace fscript::ir {
namespace {

bool is_const(const Inst* i, float v) { return i->op == Op::Const && i->imm == v; }
// The constant zero of the given sign.
bool is_zero(const Inst* i, bool negative) {
  return i->op == Op::Const && i->imm == 0.0f && std::signbit(i->imm) == negative;
}

// A replacement for `i` (an existing value), or nullptr.
Inst* identity(Inst* i) {
  auto& a = i->args;
  switch (i->op) {
    case Op::Mul:
      if (is_const(a[1], 1.0f)) return a[0];
      if (is_const(a[0], 1.0f)) return a[1];
      return nullptr;
    case Op::Div: return is_const(a[1], 1.0f) ? a[0] : nullptr;
    case Op::Add:
      if (is_zero(a[1], true)) return a[0];
      if (is_zero(a[0], true)) return a[1];
      return nullptr;
    case Op::Sub: return is_zero(a[1], false) ? a[0] : nullptr;
    case Op::Pow: return is_const(a[1], 1.0f) ? a[0] : nullptr;
    case Op::Neg: return a[0]->op == Op::Neg ? a[0]->args[0] : nullptr;
    case Op::Select:
      if (a[1] == a[2]) return a[1];
      if (a[0]->op == Op::Const) return math::truthy(a[0]->imm) ? a[1] : a[2];
      return nullptr;
    case Op::Truth:
      // truth(v) is v when v is already 0 or 1 (a comparison or logic result).
      switch (a[0]->op) {
        case Op::Eq:
        case Op::Ne:
        case Op::Lt:
        case Op::Le:
        case Op::Gt:
        case Op::Ge:
        case Op::Not:
        case Op::Truth: return a[0];
        default: return nullptr;
      }
    case Op::Phi: {
      Inst* same = nullptr;
      for (Inst* v : a) {
        if (v == i || v == same) continue;
        if (same) return nullptr;
        same = v;
      }
      return same;
    }
    default: return nullptr;
  }
}

// x^k for a small constant integer k becomes multiplications (x^2 = x*x exactly: one rounding, as
// the correctly rounded pow; x^3 and x^4 round twice, within the transcendental ulp bound), x^1 is
// x, x^0 is 1 (also for NaN, as Math.pow), x^-1 is 1/x (exact). Rewrites `i` in place.
bool reduce_pow(Function& fn, Inst* i) {
  if (i->op != Op::Pow || i->args[1]->op != Op::Const) return false;
  float k = i->args[1]->imm;
  Inst* x = i->args[0];
  auto square = [&] {
    Inst* s = fn.make(Op::Mul);
    s->args = {x, x};
    s->block = i->block;
    auto& v = i->block->insts;
    v.insert(std::find(v.begin(), v.end(), i), s);
    return s;
  };
  if (k == 2) {
    i->op = Op::Mul;
    i->args = {x, x};
  } else if (k == 3) {
    i->op = Op::Mul;
    i->args = {square(), x};
  } else if (k == 4) {
    Inst* s = square();
    i->op = Op::Mul;
    i->args = {s, s};
  } else if (k == 0) {
    i->op = Op::Const;
    i->imm = 1;
    i->args.clear();
  } else if (k == -1) {
    Inst* one = fn.make(Op::Const);
    one->imm = 1;
    one->block = i->block;
    auto& v = i->block->insts;
    v.insert(std::find(v.begin(), v.end(), i), one);
    i->op = Op::Div;
    i->args = {one, x};
  } else {
    return false;
  }
  return true;
}

// cbr on a constant becomes br; the untaken successor loses this predecessor.
bool fold_branch(Block* b) {
  Inst* t = b->terminator();
  if (t->op != Op::Branch || t->args[0]->op != Op::Const) return false;
  Block* taken = math::truthy(t->args[0]->imm) ? t->targets[0] : t->targets[1];
  Block* dropped = taken == t->targets[0] ? t->targets[1] : t->targets[0];
  remove_pred(dropped, b);
  t->op = Op::Jump;
  t->args.clear();
  t->targets = {taken};
  return true;
}

}  // namespace

bool run_const_fold(Function& fn) {
  std::vector<Inst*> rep(fn.next_value, nullptr);
  bool changed = false;
  for (auto& b : fn.blocks) {
    for (size_t n = 0; n < b->insts.size(); ++n) {
      Inst* i = b->insts[n];
      for (auto& a : i->args)
        while (rep[a->id]) a = rep[a->id];
      if (reduce_pow(fn, i)) {
        rep.resize(fn.next_value, nullptr);
        changed = true;
        n = static_cast<size_t>(std::find(b->insts.begin(), b->insts.end(), i) - b->insts.begin());
      }
      if (Inst* r = identity(i); r && r != i) {
        rep[i->id] = r;
        changed = true;
        continue;
      }
      if (!has_flag(i->op, Pure) || i->op == Op::Const || i->op == Op::Param || i->args.empty()) continue;
      float vals[3];
      bool all_const = i->args.size() <= 3;
      for (size_t k = 0; all_const && k < i->args.size(); ++k) {
        all_const = i->args[k]->op == Op::Const;
        if (all_const) vals[k] = i->args[k]->imm;
      }
      float out;
      if (all_const && eval_pure(i->op, vals, out)) {
        i->op = Op::Const;
        i->imm = out;
        i->args.clear();
        changed = true;
      }
    }
    changed |= fold_branch(b.get());
  }
  if (changed) {
    replace_uses(fn, rep);
    for (auto& b : fn.blocks) std::erase_if(b->insts, [&](Inst* i) { return rep[i->id] != nullptr; });
    fn.remove_unreachable_blocks();
  }
  return changed;
}

}  // namespace fscript::ir
