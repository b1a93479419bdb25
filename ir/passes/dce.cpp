// Dead code elimination: marks from the roots (effects, traps, terminators) through operands and
// deletes every unmarked instruction. Pure values, phis and global loads are removable.
#include <vector>

#include "ir/passes/passes.h"

namespace fscript::ir {

static bool removable(const Inst* i) { return has_flag(i->op, Pure) || i->op == Op::Phi || i->op == Op::GLoad; }

bool run_dce(Function& fn) {
  std::vector<bool> live(fn.next_value, false);
  std::vector<Inst*> work;
  for (auto& b : fn.blocks)
    for (Inst* i : b->insts)
      if (!removable(i)) {
        live[i->id] = true;
        work.push_back(i);
      }
  while (!work.empty()) {
    Inst* i = work.back();
    work.pop_back();
    for (Inst* a : i->args)
      if (!live[a->id]) {
        live[a->id] = true;
        work.push_back(a);
      }
  }
  bool changed = false;
  for (auto& b : fn.blocks) {
    size_t before = b->insts.size();
    std::erase_if(b->insts, [&](Inst* i) { return !live[i->id]; });
    changed |= b->insts.size() != before;
  }
  return changed;
}

}  // namespace fscript::ir
