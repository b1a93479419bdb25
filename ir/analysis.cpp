// Reverse post-order (iterative DFS) and the Cooper-Harvey-Kennedy dominator algorithm.
#include "ir/analysis.h"

#include <algorithm>

namespace fscript::ir {

std::vector<Block*> reverse_post_order(const Function& fn) {
  std::vector<Block*> post;
  std::unordered_map<Block*, bool> seen;
  // Explicit stack of (block, next successor index) so deep CFGs never recurse.
  std::vector<std::pair<Block*, size_t>> stack;
  Block* e = fn.entry();
  seen[e] = true;
  stack.push_back({e, 0});
  while (!stack.empty()) {
    auto& [b, k] = stack.back();
    std::vector<Block*> succ = b->succs();
    if (k < succ.size()) {
      Block* s = succ[succ.size() - 1 - k];  // false target first
      ++k;
      if (!seen[s]) {
        seen[s] = true;
        stack.push_back({s, 0});
      }
    } else {
      post.push_back(b);
      stack.pop_back();
    }
  }
  std::reverse(post.begin(), post.end());
  return post;
}

DomTree::DomTree(const Function& fn) : rpo_(reverse_post_order(fn)) {
  for (size_t i = 0; i < rpo_.size(); ++i) index_[rpo_[i]] = i;
  Block* entry = rpo_.front();
  idom_[entry] = entry;
  auto intersect = [&](Block* a, Block* b) {
    while (a != b) {
      while (index_[a] > index_[b]) a = idom_[a];
      while (index_[b] > index_[a]) b = idom_[b];
    }
    return a;
  };
  bool changed = true;
  while (changed) {
    changed = false;
    for (size_t i = 1; i < rpo_.size(); ++i) {
      Block* b = rpo_[i];
      Block* nd = nullptr;
      for (Block* p : b->preds) {
        if (!idom_.count(p) || !index_.count(p)) continue;
        nd = nd ? intersect(p, nd) : p;
      }
      if (nd && idom_[b] != nd) {
        idom_[b] = nd;
        changed = true;
      }
    }
  }
  for (Block* b : rpo_)
    if (b != entry) kids_[idom_[b]].push_back(b);
}

bool DomTree::dominates(Block* a, Block* b) const {
  if (!index_.count(b) || !index_.count(a)) return false;
  while (true) {
    if (a == b) return true;
    Block* up = idom_.at(b);
    if (up == b) return false;
    b = up;
  }
}

const std::vector<Block*>& DomTree::children(Block* b) const {
  static const std::vector<Block*> kNone;
  auto it = kids_.find(b);
  return it == kids_.end() ? kNone : it->second;
}

}  // namespace fscript::ir
