// If-conversion: a branch whose arms are small blocks of pure code that meet again becomes
// straight-line code with `select`s, so SIMD lanes never diverge there. Handles the diamond
// (h -> t, f -> j) and both triangles (h -> t -> j, h -> j). Arms are speculated, so only pure
// ops qualify, and only up to a cost budget (a runtime call counts as 8).
#include <algorithm>
#include <vector>

#include "ir/passes/passes.h"

namespace fscript::ir {
namespace {

constexpr int kMaxArmCost = 48;

// An arm can be hoisted when it has h as its only predecessor, jumps to j, and is pure and small.
bool hoistable(Block* arm, Block* h, Block* j) {
  if (arm->preds.size() != 1 || arm->preds[0] != h) return false;
  Inst* t = arm->terminator();
  if (t->op != Op::Jump || t->targets[0] != j) return false;
  int cost = 0;
  for (size_t k = 0; k + 1 < arm->insts.size(); ++k) {
    Inst* i = arm->insts[k];
    if (!has_flag(i->op, Pure)) return false;
    cost += has_flag(i->op, CallsRuntime) ? 8 : 1;
  }
  return cost <= kMaxArmCost;
}

void hoist(Block* arm, Block* h) {
  auto pos = h->insts.end() - 1;  // before h's terminator
  for (size_t k = 0; k + 1 < arm->insts.size(); ++k) {
    Inst* i = arm->insts[k];
    i->block = h;
    pos = h->insts.insert(pos, i) + 1;
  }
  arm->insts.erase(arm->insts.begin(), arm->insts.end() - 1);
}

// Value of phi `p` arriving from block `from`.
Inst* incoming(Inst* p, Block* from) {
  auto it = std::find(p->targets.begin(), p->targets.end(), from);
  return p->args[it - p->targets.begin()];
}

// Converts at h; the phis it replaces go into `rep` (applied once for the whole pass, with the
// unreachable arms removed then too: per conversion, both walked the whole function, quadratic on
// a long chain of `||`).
bool convert(Function& fn, Block* h, std::vector<Inst*>& rep) {
  Inst* br = h->terminator();
  if (br->op != Op::Branch) return false;
  Block* t = br->targets[0];
  Block* f = br->targets[1];
  Block* j = nullptr;
  Block* from_t = t;
  Block* from_f = f;
  if (t->succs().size() == 1 && hoistable(t, h, t->succs()[0]) && f == t->succs()[0]) {
    j = f;  // triangle: h -> t -> j, h -> j
    from_f = h;
  } else if (f->succs().size() == 1 && hoistable(f, h, f->succs()[0]) && t == f->succs()[0]) {
    j = t;  // mirrored triangle
    from_t = h;
  } else if (t->succs().size() == 1 && f->succs().size() == 1 && t->succs()[0] == f->succs()[0] &&
             hoistable(t, h, t->succs()[0]) && hoistable(f, h, f->succs()[0])) {
    j = t->succs()[0];  // diamond
  }
  if (!j || j->preds.size() != 2) return false;
  Inst* cond = br->args[0];
  if (from_t != h) hoist(t, h);
  if (from_f != h) hoist(f, h);
  // Each phi of j becomes a select at the end of h.
  size_t nphi = j->first_non_phi();
  for (size_t k = 0; k < nphi; ++k) {
    Inst* p = j->insts[k];
    Inst* sel = fn.make(Op::Select);
    sel->args = {cond, incoming(p, from_t), incoming(p, from_f)};
    sel->block = h;
    h->insts.insert(h->insts.end() - 1, sel);
    rep.resize(fn.next_value, nullptr);
    rep[p->id] = sel;
  }
  j->insts.erase(j->insts.begin(), j->insts.begin() + static_cast<long>(nphi));
  // h now jumps straight to j; the emptied arms become unreachable.
  for (Block* arm : {t, f})
    if (arm != j) remove_pred(arm, h);
  j->preds.clear();
  j->preds.push_back(h);
  br->op = Op::Jump;
  br->args.clear();
  br->targets = {j};
  return true;
}

}  // namespace

bool run_if_convert(Function& fn) {
  bool changed = false;
  std::vector<Inst*> rep;
  for (size_t k = 0; k < fn.blocks.size(); ++k) changed |= convert(fn, fn.blocks[k].get(), rep);
  if (changed) {
    replace_uses(fn, rep);  // resolves chains: a select made from a phi replaced earlier
    fn.remove_unreachable_blocks();
  }
  return changed;
}

}  // namespace fscript::ir
