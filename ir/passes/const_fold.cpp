// Constant folding through runtime/math (so a folded value equals the run-time one bit for bit),
// plus identities that are exact in IEEE arithmetic up to the sign of zero, which the language
// leaves unspecified: x*1, x/1, x+0, x-0, --x, select on a constant or on equal arms.
#include <vector>

#include "ir/eval.h"
#include "ir/passes/passes.h"
#include "runtime/math/math.h"

namespace fscript::ir {
namespace {

bool is_const(const Inst* i, float v) { return i->op == Op::Const && i->imm == v; }

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
      if (is_const(a[1], 0.0f)) return a[0];
      if (is_const(a[0], 0.0f)) return a[1];
      return nullptr;
    case Op::Sub: return is_const(a[1], 0.0f) ? a[0] : nullptr;
    case Op::Neg: return a[0]->op == Op::Neg ? a[0]->args[0] : nullptr;
    case Op::Select:
      if (a[1] == a[2]) return a[1];
      if (a[0]->op == Op::Const) return math::truthy(a[0]->imm) ? a[1] : a[2];
      return nullptr;
    case Op::Truth:
      // truth(v) is v when v is already 0 or 1 (a comparison or logic result).
      switch (a[0]->op) {
        case Op::Eq: case Op::Ne: case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::Not: case Op::Truth:
          return a[0];
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
    for (Inst* i : b->insts) {
      for (auto& a : i->args)
        while (rep[a->id]) a = rep[a->id];
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
    for (auto& b : fn.blocks)
      std::erase_if(b->insts, [&](Inst* i) { return rep[i->id] != nullptr; });
    fn.remove_unreachable_blocks();
  }
  return changed;
}

}  // namespace fscript::ir
