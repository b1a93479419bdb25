#pragma once
// linear_scan: the template body (included by regalloc.h).
#include <algorithm>
#include <queue>

namespace fscript::backends {

template <typename Skip>
std::vector<uint32_t> linear_scan(const ir::Function& fn, const LinearOrder& lo, Skip skip, uint32_t& num_regs) {
  std::vector<uint32_t> reg(fn.next_value, UINT32_MAX);
  std::vector<const ir::Inst*> order;
  for (ir::Block* b : lo.blocks)
    for (const ir::Inst* i : b->insts)
      if (lo.has_value[i->id] && !skip(i)) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](const ir::Inst* a, const ir::Inst* b) {
    return lo.interval[a->id].start < lo.interval[b->id].start;
  });
  using Active = std::pair<uint32_t, uint32_t>;  // (end, register), earliest end on top
  std::priority_queue<Active, std::vector<Active>, std::greater<>> active;
  std::vector<uint32_t> free_regs;
  num_regs = 0;
  for (const ir::Inst* i : order) {
    const Interval& iv = lo.interval[i->id];
    while (!active.empty() && active.top().first < iv.start) {
      free_regs.push_back(active.top().second);
      active.pop();
    }
    uint32_t r;
    if (!free_regs.empty()) {
      r = free_regs.back();
      free_regs.pop_back();
    } else {
      r = num_regs++;
    }
    reg[i->id] = r;
    active.push({iv.end, r});
  }
  return reg;
}

}  // namespace fscript::backends
