// IR verifier: terminators, phis, pred lists, arities, slots, and def-dominates-use.
#include "ir/verifier.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "ir/analysis.h"

namespace fscript::ir {
namespace {

class Verifier {
 public:
  Verifier(const Module& m, const Function& f) : m_(m), f_(f) {}

  std::string run() {
    if (f_.blocks.empty()) return fail("function has no blocks");
    if (!f_.entry()->preds.empty()) return fail("entry block has predecessors");
    for (auto& b : f_.blocks)
      for (Inst* i : b->insts) {
        if (i->block != b.get()) return fail("instruction v" + std::to_string(i->id) + " has a wrong block link");
        if (i->defines_value() && !ids_.insert(i->id).second)
          return fail("value id v" + std::to_string(i->id) + " defined twice");
        where_[i] = b.get();
      }
    // Every block's predecessors as the terminators say, in one pass (per block over all blocks
    // was quadratic: 10 KB of `||` chains spent most of a compile in the verifier).
    for (auto& p : f_.blocks)
      for (Block* s : p->succs()) preds_seen_[s].push_back(p.get());
    for (auto& b : f_.blocks)
      if (std::string e = block(*b); !e.empty()) return e;
    DomTree dom(f_);
    for (auto& b : f_.blocks)
      if (std::string e = dominance(dom, *b); !e.empty()) return e;
    return "";
  }

 private:
  std::string fail(const std::string& what) const { return "in @" + f_.name + ": " + what; }

  std::string block(const Block& b) {
    std::string at = " in b" + std::to_string(b.id);
    if (b.insts.empty() || !has_flag(b.insts.back()->op, Terminator))
      return fail("block does not end in a terminator" + at);
    std::vector<Block*>& preds_seen = preds_seen_[&b];
    std::vector<Block*> listed = b.preds;
    std::sort(preds_seen.begin(), preds_seen.end());
    std::sort(listed.begin(), listed.end());
    if (preds_seen != listed) return fail("predecessor list out of sync" + at);
    if (std::adjacent_find(listed.begin(), listed.end()) != listed.end()) return fail("duplicate CFG edge" + at);
    bool phis_done = false;
    for (size_t k = 0; k < b.insts.size(); ++k) {
      const Inst& i = *b.insts[k];
      if (has_flag(i.op, Terminator) && k + 1 != b.insts.size()) return fail("terminator in the middle" + at);
      if (i.op == Op::Phi) {
        if (phis_done) return fail("phi after a non-phi" + at);
        std::vector<Block*> ts = i.targets;
        std::sort(ts.begin(), ts.end());
        if (ts != listed || i.args.size() != i.targets.size())
          return fail("phi v" + std::to_string(i.id) + " does not match the predecessors" + at);
      } else {
        phis_done = true;
      }
      if (std::string e = operands(i); !e.empty()) return fail(e + at);
    }
    return "";
  }

  std::string operands(const Inst& i) {
    int arity = op_info(i.op).arity;
    std::string name = std::string(mnemonic(i.op));
    if (arity >= 0 && static_cast<int>(i.args.size()) != arity) return "wrong operand count for " + name;
    for (Inst* a : i.args)
      if (!where_.count(a) || !a->defines_value()) return "operand of " + name + " is not a value of this function";
    switch (i.op) {
      case Op::GLoad:
      case Op::GStore:
        if (i.aux < 0 || i.aux >= static_cast<int>(m_.globals.size())) return "bad global slot";
        break;
      case Op::ANew:
      case Op::ALoad:
      case Op::AStore:
      case Op::ALen: {
        size_t n = i.array_global ? m_.arrays.size() : f_.arrays.size();
        if (i.aux < 0 || i.aux >= static_cast<int>(n)) return "bad array slot";
        break;
      }
      case Op::Call:
        if (i.aux < 0 || i.aux >= static_cast<int>(m_.functions.size())) return "bad callee";
        if (m_.functions[i.aux]->num_params != i.args.size()) return "call arity mismatch";
        break;
      case Op::Jump:
        if (i.targets.size() != 1) return "br needs one target";
        break;
      case Op::Branch:
        if (i.targets.size() != 2 || i.targets[0] == i.targets[1]) return "cbr needs two distinct targets";
        break;
      case Op::Ret:
        if (i.args.size() != f_.num_results) return "ret has the wrong number of values";
        break;
      case Op::Param:
        if (i.aux < 0 || i.aux >= static_cast<int>(f_.num_params)) return "bad parameter index";
        break;
      default: break;
    }
    return "";
  }

  std::string dominance(const DomTree& dom, const Block& b) {
    if (!dom.reachable(&b)) return "";
    std::unordered_map<const Inst*, size_t> pos;
    for (size_t k = 0; k < b.insts.size(); ++k) pos[b.insts[k]] = k;
    for (size_t k = 0; k < b.insts.size(); ++k) {
      const Inst& i = *b.insts[k];
      for (size_t a = 0; a < i.args.size(); ++a) {
        Inst* d = i.args[a];
        Block* db = where_[d];
        bool ok;
        if (i.op == Op::Phi) ok = !dom.reachable(i.targets[a]) || dom.dominates(db, i.targets[a]);
        else if (db == &b) ok = pos.count(d) && pos[d] < k;
        else ok = dom.dominates(db, const_cast<Block*>(&b));
        if (!ok) return fail("v" + std::to_string(d->id) + " does not dominate its use in b" + std::to_string(b.id));
      }
    }
    return "";
  }

  const Module& m_;
  const Function& f_;
  std::unordered_set<uint32_t> ids_;
  std::unordered_map<const Inst*, Block*> where_;
  std::unordered_map<const Block*, std::vector<Block*>> preds_seen_;
};

}  // namespace

std::string verify(const Module& m) {
  for (auto& f : m.functions) {
    if (f->row_params_from && (!f->kernel || f->row_params_from >= f->num_params))
      return "@" + f->name + ": row parameters on a function that is not a kernel, or past its parameters";
    if (!f->row_param_ranges.empty() &&
        (!f->row_params_from ||
         f->row_param_ranges.size() != kNumParamBounds * (f->num_params - std::min(f->row_params_from, f->num_params))))
      return "@" + f->name + ": row parameter ranges for " + std::to_string(f->row_param_ranges.size()) +
          " values, not one per row parameter and bound";
    if (std::string e = Verifier(m, *f).run(); !e.empty()) return e;
  }
  return "";
}

}  // namespace fscript::ir
