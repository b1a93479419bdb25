// Reverse post-order (iterative DFS) and the Cooper-Harvey-Kennedy dominator algorithm.
#include "ir/analysis.h"

#include <algorithm>
#include <cmath>

#include "runtime/math/math.h"

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

std::vector<KnownOutOfRange> known_out_of_range(const Module& m) {
  // Each array (a global slot, or a function's own) and the one constant length all its `new`s
  // give; -1 where some length is not a constant or two differ.
  using Key = std::pair<int, int32_t>;  // (function index, or -1 for globals; slot)
  std::map<Key, long> length;
  auto key = [](const Inst& i, int fn) { return Key{i.array_global ? -1 : fn, i.aux}; };
  for (size_t f = 0; f < m.functions.size(); ++f)
    for (const auto& b : m.functions[f]->blocks)
      for (const Inst* i : b->insts) {
        if (i->op != Op::ANew) continue;
        long n = i->args[0]->op == Op::Const && std::isfinite(i->args[0]->imm) && i->args[0]->imm >= 0
            ? std::lround(i->args[0]->imm)
            : -1;
        auto [it, fresh] = length.emplace(key(*i, static_cast<int>(f)), n);
        if (!fresh && it->second != n) it->second = -1;
      }
  std::vector<KnownOutOfRange> out;
  for (size_t f = 0; f < m.functions.size(); ++f)
    for (const auto& b : m.functions[f]->blocks)
      for (const Inst* i : b->insts) {
        if ((i->op != Op::ALoad && i->op != Op::AStore) || i->args[0]->op != Op::Const) continue;
        auto it = length.find(key(*i, static_cast<int>(f)));
        if (it == length.end() || it->second < 0) continue;
        float index = i->args[0]->imm;
        if (math::array_index(index, it->second) < 0) {  // the backends' own rule (rounding, NaN)
          const auto& names = i->array_global ? m.arrays : m.functions[f]->arrays;
          std::string name =
              i->aux >= 0 && static_cast<size_t>(i->aux) < names.size() ? names[static_cast<size_t>(i->aux)] : "?";
          // The name as written: inlining and renaming made it "caller.name.N".
          size_t end = name.size();
          while (end > 0) {
            size_t dot = name.rfind('.', end - 1);
            std::string seg =
                name.substr(dot == std::string::npos ? 0 : dot + 1, end - (dot == std::string::npos ? 0 : dot + 1));
            if (!seg.empty() && seg.find_first_not_of("0123456789") != std::string::npos) {
              name = seg;
              break;
            }
            if (dot == std::string::npos) break;
            end = dot;
          }
          out.push_back({i->line, i->col, name, index, static_cast<uint32_t>(it->second)});
        }
      }
  return out;
}

}  // namespace fscript::ir
