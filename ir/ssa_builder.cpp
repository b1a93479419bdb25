// Braun et al.'s SSA construction: read/write per block, incomplete phis in unsealed blocks.
#include "ir/ssa_builder.h"

namespace fscript::ir {

Inst* SsaBuilder::resolve(Inst* v) const {
  while (v->id < rep_.size() && rep_[v->id]) v = rep_[v->id];
  return v;
}

Inst* SsaBuilder::read(int var, Block* b) {
  auto& m = defs_[b];
  auto it = m.find(var);
  if (it != m.end()) return resolve(it->second);
  return read_recursive(var, b);
}

Inst* SsaBuilder::new_phi(Block* b) {
  Inst* p = fn_.make(Op::Phi);
  p->block = b;
  b->insts.insert(b->insts.begin() + static_cast<long>(b->first_non_phi()), p);
  return p;
}

Inst* SsaBuilder::read_recursive(int var, Block* b) {
  Inst* v;
  if (!sealed_.count(b)) {
    v = new_phi(b);
    incomplete_[b].push_back({var, v});
  } else if (b->preds.size() == 1) {
    v = read(var, b->preds[0]);
  } else if (b->preds.empty()) {
    v = undefined_(var);
  } else {
    v = new_phi(b);
    write(var, b, v);
    v = add_phi_operands(var, v);
  }
  write(var, b, v);
  return v;
}

Inst* SsaBuilder::add_phi_operands(int var, Inst* phi) {
  for (Block* p : phi->block->preds) {
    phi->args.push_back(read(var, p));
    phi->targets.push_back(p);
  }
  return remove_trivial_phi(var, phi);
}

Inst* SsaBuilder::remove_trivial_phi(int var, Inst* phi) {
  Inst* same = nullptr;
  for (Inst*& a : phi->args) {
    a = resolve(a);
    if (a == same || a == phi) continue;
    if (same) return phi;
    same = a;
  }
  if (!same) same = undefined_(var);  // a phi only of itself: unreachable or never assigned
  if (rep_.size() <= phi->id) rep_.resize(phi->id + 1, nullptr);
  rep_[phi->id] = same;
  erase(phi);
  return same;
}

void SsaBuilder::seal(Block* b) {
  auto pending = std::move(incomplete_[b]);
  incomplete_.erase(b);
  sealed_.insert(b);
  for (auto& [var, phi] : pending) add_phi_operands(var, phi);
}

void SsaBuilder::finish() { replace_uses(fn_, rep_); }

}  // namespace fscript::ir
