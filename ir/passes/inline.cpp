// Inlining: every call of a non-recursive function is replaced by a copy of its body (the call's
// block is split; returns jump to the continuation, whose phi is the call's value). Functions no
// longer called from a kernel are then dropped. A size cap stops exponential blow-up; calls left
// over still work, through the backends' call path.
#include <algorithm>
#include <unordered_map>

#include "ir/passes/passes.h"

namespace fscript::ir {
namespace {

constexpr size_t kMaxFunctionSize = 2'000'000;  // instructions

size_t size_of(const Function& f) {
  size_t n = 0;
  for (auto& b : f.blocks) n += b->insts.size();
  return n;
}

// Moves the blocks added since `first_new` to just after `after` in the layout.
void place_after(Function& f, Block* after, size_t first_new) {
  auto pos = std::find_if(f.blocks.begin(), f.blocks.end(), [&](auto& b) { return b.get() == after; });
  size_t at = static_cast<size_t>(pos - f.blocks.begin()) + 1;
  std::rotate(f.blocks.begin() + static_cast<long>(at), f.blocks.begin() + static_cast<long>(first_new),
              f.blocks.end());
}

// Splits `b` after `call`: the instructions after it move to a new block, returned.
Block* split_after(Function& f, Block* b, Inst* call) {
  Block* post = f.add_block();
  auto it = std::find(b->insts.begin(), b->insts.end(), call);
  for (auto k = it + 1; k != b->insts.end(); ++k) {
    (*k)->block = post;
    post->insts.push_back(*k);
  }
  b->insts.erase(it, b->insts.end());
  for (Block* s : post->succs()) {
    std::replace(s->preds.begin(), s->preds.end(), b, post);
    for (Inst* p : s->insts) {
      if (p->op != Op::Phi) break;
      std::replace(p->targets.begin(), p->targets.end(), b, post);
    }
  }
  return post;
}

void inline_call(Function& f, const Function& g, Inst* call) {
  Block* b = call->block;
  size_t first_new = f.blocks.size();
  Block* post = split_after(f, b, call);
  uint32_t array_base = static_cast<uint32_t>(f.arrays.size());
  for (const auto& a : g.arrays) f.arrays.push_back(g.name + "." + a);
  std::unordered_map<const Block*, Block*> bmap;
  std::unordered_map<const Inst*, Inst*> imap;
  for (auto& gb : g.blocks) bmap[gb.get()] = f.add_block();
  std::vector<std::pair<Inst*, Block*>> returns;
  for (auto& gb : g.blocks) {
    Block* nb = bmap[gb.get()];
    for (Block* p : gb->preds) nb->preds.push_back(bmap[p]);
    for (Inst* i : gb->insts) {
      if (i->op == Op::Param) {
        imap[i] = call->args[i->aux];
        continue;
      }
      Inst* n = f.make(i->op);
      uint32_t id = n->id;
      *n = *i;
      n->id = id;
      n->block = nb;
      if ((i->op == Op::ANew || i->op == Op::ALoad || i->op == Op::AStore || i->op == Op::ALen) && !i->array_global)
        n->aux += static_cast<int32_t>(array_base);
      for (auto& t : n->targets) t = bmap[t];
      imap[i] = n;
      nb->insts.push_back(n);
      if (i->op == Op::Ret) returns.push_back({n, nb});
    }
  }
  for (auto& [gb, nb] : bmap)
    for (Inst* n : nb->insts)
      for (auto& a : n->args) a = imap.at(a);
  // The call's block jumps into the copy; each return jumps to the continuation.
  Block* entry = bmap[g.entry()];
  Inst* j = f.make(Op::Jump);
  j->block = b;
  j->targets = {entry};
  b->insts.push_back(j);
  entry->preds.push_back(b);
  Inst* result = nullptr;
  if (returns.size() > 1) {
    result = f.make(Op::Phi);
    result->block = post;
    post->insts.insert(post->insts.begin(), result);
  }
  for (auto& [ret, rb] : returns) {
    Inst* v = ret->args[0];
    if (result) {
      result->args.push_back(v);
      result->targets.push_back(rb);
    } else {
      result = v;
    }
    ret->op = Op::Jump;
    ret->args.clear();
    ret->targets = {post};
    post->preds.push_back(rb);
  }
  if (!result) {  // the callee never returns (it loops until the budget stops it)
    result = f.make(Op::Const);
    result->imm = 0;
    result->block = post;
    post->insts.insert(post->insts.begin(), result);
  }
  std::vector<Inst*> rep(f.next_value, nullptr);
  rep[call->id] = result;
  replace_uses(f, rep);
  place_after(f, b, first_new);
}

Inst* next_inlinable_call(const Module& m, Function& f) {
  for (auto& b : f.blocks)
    for (Inst* i : b->insts)
      if (i->op == Op::Call && !m.functions[i->aux]->recursive && m.functions[i->aux].get() != &f) return i;
  return nullptr;
}

// Drops functions that no kernel can reach, renumbering call targets.
bool drop_dead_functions(Module& m) {
  std::vector<bool> live(m.functions.size(), false);
  std::vector<size_t> work;
  for (size_t i = 0; i < m.functions.size(); ++i)
    if (m.functions[i]->kernel) {
      live[i] = true;
      work.push_back(i);
    }
  if (work.empty()) return false;
  while (!work.empty()) {
    size_t k = work.back();
    work.pop_back();
    for (auto& b : m.functions[k]->blocks)
      for (Inst* i : b->insts)
        if (i->op == Op::Call && !live[i->aux]) {
          live[i->aux] = true;
          work.push_back(static_cast<size_t>(i->aux));
        }
  }
  if (std::all_of(live.begin(), live.end(), [](bool v) { return v; })) return false;
  std::vector<int> new_index(m.functions.size(), -1);
  std::vector<std::unique_ptr<Function>> kept;
  for (size_t i = 0; i < m.functions.size(); ++i)
    if (live[i]) {
      new_index[i] = static_cast<int>(kept.size());
      kept.push_back(std::move(m.functions[i]));
    }
  m.functions = std::move(kept);
  for (auto& f : m.functions)
    for (auto& b : f->blocks)
      for (Inst* i : b->insts)
        if (i->op == Op::Call) i->aux = new_index[i->aux];
  return true;
}

}  // namespace

bool run_inline(Module& m) {
  bool changed = false;
  for (auto& f : m.functions) {
    while (Inst* call = next_inlinable_call(m, *f)) {
      const Function& g = *m.functions[call->aux];
      if (size_of(*f) + size_of(g) > kMaxFunctionSize) break;
      inline_call(*f, g, call);
      changed = true;
    }
  }
  changed |= drop_dead_functions(m);
  return changed;
}

}  // namespace fscript::ir
