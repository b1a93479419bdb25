// Global value numbering: a pure instruction equal to one that dominates it (same op, immediate,
// slot and operands; operands sorted for commutative ops) is replaced by the dominating one.
// Scoped hash table over a pre-order walk of the dominator tree.
#include <algorithm>
#include <bit>
#include <map>
#include <tuple>
#include <vector>

#include "ir/analysis.h"
#include "ir/passes/passes.h"

namespace fscript::ir {
namespace {

using Key = std::tuple<Op, uint32_t, int32_t, std::vector<uint32_t>>;

Key key_of(const Inst* i) {
  std::vector<uint32_t> args;
  for (const Inst* a : i->args) args.push_back(a->id);
  if (has_flag(i->op, Commutative)) std::sort(args.begin(), args.end());
  return {i->op, std::bit_cast<uint32_t>(i->imm), i->aux, std::move(args)};
}

}  // namespace

bool run_gvn(Function& fn) {
  DomTree dom(fn);
  std::map<Key, Inst*> table;
  std::vector<Inst*> rep(fn.next_value, nullptr);
  bool changed = false;
  // An explicit stack instead of recursion over a deep dominator tree; `added` is the undo log.
  struct Frame {
    Block* b;
    size_t child = 0;
    bool visited = false;
    std::vector<Key> added;
  };
  std::vector<Frame> stack;
  stack.push_back({fn.entry(), 0, false, {}});
  while (!stack.empty()) {
    Frame& f = stack.back();
    if (!f.visited) {
      f.visited = true;
      for (Inst* i : f.b->insts) {
        for (auto& a : i->args)
          while (rep[a->id]) a = rep[a->id];
        if (!has_flag(i->op, Pure) || i->op == Op::Param) continue;
        Key k = key_of(i);
        auto it = table.find(k);
        if (it != table.end()) {
          rep[i->id] = it->second;
          changed = true;
        } else {
          table.emplace(k, i);
          f.added.push_back(std::move(k));
        }
      }
    }
    const auto& kids = dom.children(f.b);
    if (f.child < kids.size()) {
      Block* next = kids[f.child++];
      stack.push_back({next, 0, false, {}});
      continue;
    }
    for (auto& k : f.added) table.erase(k);
    stack.pop_back();
  }
  if (!changed) return false;
  replace_uses(fn, rep);
  for (auto& b : fn.blocks) std::erase_if(b->insts, [&](Inst* i) { return rep[i->id] != nullptr; });
  return true;
}

}  // namespace fscript::ir
