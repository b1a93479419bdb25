// CFG simplification: drop unreachable blocks, thread jumps through empty blocks, merge a block
// into its only predecessor, drop the phis of single-predecessor blocks. Repeats to a fixed point.
#include <algorithm>

#include "ir/passes/passes.h"

namespace fscript::ir {
namespace {

// Phis of a block with a single predecessor are copies: replace them by their operand.
bool drop_single_pred_phis(Function& fn, Block* b) {
  if (b->preds.size() != 1 || b->first_non_phi() == 0) return false;
  std::vector<Inst*> rep(fn.next_value, nullptr);
  for (size_t k = 0; k < b->first_non_phi(); ++k) rep[b->insts[k]->id] = b->insts[k]->args[0];
  replace_uses(fn, rep);
  b->insts.erase(b->insts.begin(), b->insts.begin() + static_cast<long>(b->first_non_phi()));
  return true;
}

// b ends in `br s`, s has b as its only predecessor: append s to b.
bool merge_into_pred(Function& fn, Block* b) {
  Inst* t = b->terminator();
  if (t->op != Op::Jump) return false;
  Block* s = t->targets[0];
  if (s == b || s->preds.size() != 1 || s == fn.entry()) return false;
  drop_single_pred_phis(fn, s);
  b->insts.pop_back();
  for (Inst* i : s->insts) {
    i->block = b;
    b->insts.push_back(i);
  }
  s->insts.clear();
  for (Block* succ : b->succs()) {
    std::replace(succ->preds.begin(), succ->preds.end(), s, b);
    for (Inst* p : succ->insts) {
      if (p->op != Op::Phi) break;
      std::replace(p->targets.begin(), p->targets.end(), s, b);
    }
  }
  s->preds.clear();
  return true;
}

// e holds only `br t` and t has no phis: its predecessors jump straight to t.
bool thread_empty(Function& fn, Block* e) {
  if (e == fn.entry() || e->insts.size() != 1 || e->terminator()->op != Op::Jump) return false;
  Block* t = e->terminator()->targets[0];
  if (t == e) return false;
  bool t_has_phis = t->first_non_phi() > 0;
  bool changed = false;
  for (Block* p : std::vector<Block*>(e->preds)) {
    bool already = std::find(t->preds.begin(), t->preds.end(), p) != t->preds.end();
    if (already) continue;
    if (t_has_phis) {
      // The phi operand that came through e now comes from p directly.
      for (Inst* phi : t->insts) {
        if (phi->op != Op::Phi) break;
        auto it = std::find(phi->targets.begin(), phi->targets.end(), e);
        phi->args.push_back(phi->args[it - phi->targets.begin()]);
        phi->targets.push_back(p);
      }
    }
    retarget(p, e, t);
    changed = true;
  }
  if (changed && e->preds.empty()) remove_pred(t, e);
  return changed;
}

}  // namespace

bool run_simplify_cfg(Function& fn) {
  bool any = false;
  for (bool changed = true; changed;) {
    changed = false;
    size_t before = fn.blocks.size();
    fn.remove_unreachable_blocks();
    changed |= fn.blocks.size() != before;
    for (auto& b : fn.blocks) {
      if (b->insts.empty()) continue;  // merged away this round
      changed |= drop_single_pred_phis(fn, b.get());
      changed |= merge_into_pred(fn, b.get());
      changed |= thread_empty(fn, b.get());
    }
    std::erase_if(fn.blocks, [](const std::unique_ptr<Block>& b) { return b->insts.empty(); });
    any |= changed;
  }
  return any;
}

}  // namespace fscript::ir
