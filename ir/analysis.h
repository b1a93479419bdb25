#pragma once
// CFG analyses shared by passes and backends: reverse post-order and dominators; and arrays
// indexed out of range by constants.
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "ir/ir.h"

namespace fscript::ir {

// Reverse post-order from the entry. A branch's second (false) target is visited first, so a
// loop's exit block comes after the whole loop body: the SIMD VM schedules blocks in this order.
std::vector<Block*> reverse_post_order(const Function& fn);

// Immediate dominators (Cooper, Harvey, Kennedy), for reachable blocks.
class DomTree {
 public:
  explicit DomTree(const Function& fn);
  bool dominates(Block* a, Block* b) const;  // reflexive
  const std::vector<Block*>& rpo() const { return rpo_; }
  const std::vector<Block*>& children(Block* b) const;
  bool reachable(const Block* b) const { return index_.count(const_cast<Block*>(b)) != 0; }

 private:
  std::vector<Block*> rpo_;
  std::unordered_map<Block*, size_t> index_;
  std::unordered_map<Block*, Block*> idom_;
  std::unordered_map<Block*, std::vector<Block*>> kids_;
};

// An array read or write whose index is a constant outside the array's length, where every
// `new Array(n)` of that array makes the same constant n: it fails whenever it runs, so `fscript
// check` warns at it (after optimisation, which makes `var i = 5; a[i]` such a constant).
struct KnownOutOfRange {
  uint32_t line = 0, col = 0;
  std::string array;
  float index = 0;
  uint32_t length = 0;
};
std::vector<KnownOutOfRange> known_out_of_range(const Module& m);

}  // namespace fscript::ir
