// Liveness by backward dataflow over blocks, then live intervals over the reverse post-order.
#include "backends/regalloc.h"

#include <unordered_map>

#include "ir/analysis.h"

namespace fscript::backends {

LinearOrder compute_intervals(const ir::Function& fn) {
  LinearOrder lo;
  lo.blocks = ir::reverse_post_order(fn);
  size_t nb = lo.blocks.size();
  std::unordered_map<const ir::Block*, size_t> index;
  for (size_t k = 0; k < nb; ++k) index[lo.blocks[k]] = k;
  lo.interval.assign(fn.next_value, {});
  lo.has_value.assign(fn.next_value, false);
  uint32_t pos = 0;
  lo.block_start.resize(nb);
  lo.block_end.resize(nb);
  for (size_t k = 0; k < nb; ++k) {
    lo.block_start[k] = pos;
    for (const ir::Inst* i : lo.blocks[k]->insts) {
      if (i->defines_value()) {
        lo.has_value[i->id] = true;
        lo.interval[i->id] = {pos, pos};
      }
      ++pos;
    }
    lo.block_end[k] = pos - 1;
  }
  // live_in per block as sets of value ids, iterated to a fixed point (backward).
  std::vector<std::vector<bool>> live_in(nb, std::vector<bool>(fn.next_value, false));
  auto live_out_of = [&](size_t k) {
    std::vector<bool> out(fn.next_value, false);
    const ir::Block* b = lo.blocks[k];
    for (ir::Block* s : b->succs()) {
      const auto& in = live_in[index[s]];
      for (size_t v = 0; v < in.size(); ++v)
        if (in[v]) out[v] = true;
      for (const ir::Inst* p : s->insts) {
        if (p->op != ir::Op::Phi) break;
        for (size_t a = 0; a < p->args.size(); ++a)
          if (p->targets[a] == b) out[p->args[a]->id] = true;
      }
    }
    return out;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = nb; k-- > 0;) {
      std::vector<bool> live = live_out_of(k);
      const ir::Block* b = lo.blocks[k];
      for (auto it = b->insts.rbegin(); it != b->insts.rend(); ++it) {
        const ir::Inst* i = *it;
        if (i->defines_value()) live[i->id] = false;
        if (i->op == ir::Op::Phi) continue;
        for (const ir::Inst* a : i->args) live[a->id] = true;
      }
      if (live != live_in[k]) {
        live_in[k] = std::move(live);
        changed = true;
      }
    }
  }
  // Stretch intervals: uses, and whole blocks where a value is live in or out.
  for (size_t k = 0; k < nb; ++k) {
    std::vector<bool> out = live_out_of(k);
    for (size_t v = 0; v < out.size(); ++v) {
      if (out[v]) lo.interval[v].end = std::max(lo.interval[v].end, lo.block_end[k]);
      if (live_in[k][v]) lo.interval[v].end = std::max(lo.interval[v].end, lo.block_start[k]);
    }
    uint32_t p = lo.block_start[k];
    for (const ir::Inst* i : lo.blocks[k]->insts) {
      if (i->op != ir::Op::Phi)
        for (const ir::Inst* a : i->args) lo.interval[a->id].end = std::max(lo.interval[a->id].end, p);
      ++p;
    }
  }
  return lo;
}

}  // namespace fscript::backends
