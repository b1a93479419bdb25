// Promotes globals to SSA values inside each function (mem2reg for global slots), using the same
// SSA builder as the lowering. Memory is only kept where another function can observe it:
// before a call (store), after a call (reload), and at the return of a non-kernel function that
// wrote the global. In a kernel, globals start as NaN and are dead at its return.
#include <unordered_set>

#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "ir/ssa_builder.h"

namespace fscript::ir {
namespace {

class Promoter {
 public:
  Promoter(Module& m, Function& f)
      : n_(static_cast<int>(m.globals.size())), f_(f), ssa_(f, [this](int g) { return entry_value(g); }) {}

  bool run() {
    bool any = false;
    for (auto& b : f_.blocks)
      for (Inst* i : b->insts) {
        if (i->op == Op::GStore) written_.insert(i->aux);
        any |= i->op == Op::GLoad || i->op == Op::GStore;
      }
    if (!any) return false;
    std::vector<Block*> rpo = reverse_post_order(f_);
    for (Block* b : rpo) {
      if (ready(b)) ssa_.seal(b);
      rewrite(b);
      filled_.insert(b);
      for (Block* s : b->succs())
        if (!ssa_.is_sealed(s) && ready(s) && filled_.count(s)) ssa_.seal(s);
    }
    for (Block* b : rpo)
      if (!ssa_.is_sealed(b)) ssa_.seal(b);
    // Trivial phis first: one can stand for a program load's value (`g = g;` before a loop whose
    // body returns: the store at that return read the loop's phi), which the loads' replacement
    // must then still see (found by backend_diff: a dangling gstore operand, a crash in the JITs).
    ssa_.finish();
    std::vector<Inst*> rep(f_.next_value, nullptr);
    for (auto& [load, value] : replaced_) rep[load->id] = ssa_.resolve(value);
    replace_uses(f_, rep);
    return true;
  }

 private:
  bool ready(Block* b) const {
    for (Block* p : b->preds)
      if (!filled_.count(p)) return false;
    return true;
  }

  Inst* entry_value(int g) {
    if (f_.kernel || g < 0) {
      if (!nan_) nan_ = at_entry(Op::Const, 0);
      nan_->imm = __builtin_nanf("");
      return nan_;
    }
    auto it = entry_loads_.find(g);
    if (it != entry_loads_.end()) return it->second;
    Inst* load = at_entry(Op::GLoad, g);
    kept_loads_.insert(load);
    return entry_loads_[g] = load;
  }
  Inst* at_entry(Op op, int aux) {
    Block* e = f_.entry();
    Inst* i = f_.make(op);
    i->aux = aux;
    i->block = e;
    e->insts.insert(e->insts.begin(), i);
    return i;
  }
  Inst* make(Op op, Block* b, int aux, std::vector<Inst*> args) {
    Inst* i = f_.make(op);
    i->aux = aux;
    i->block = b;
    i->args = std::move(args);
    return i;
  }

  void rewrite(Block* b) {
    std::vector<Inst*> old = std::move(b->insts);
    b->insts.clear();
    for (Inst* i : old) {
      if (i->op == Op::GLoad && !is_entry_load(i)) {
        replaced_.push_back({i, ssa_.read(i->aux, b)});
      } else if (i->op == Op::GStore) {
        ssa_.write(i->aux, b, i->args[0]);
      } else if (i->op == Op::Call) {
        flush(b, f_.kernel);
        b->insts.push_back(i);
        for (int g = 0; g < n_; ++g) {
          Inst* l = make(Op::GLoad, b, g, {});
          b->insts.push_back(l);
          kept_loads_.insert(l);
          ssa_.write(g, b, l);
        }
      } else if (i->op == Op::Ret && !f_.kernel) {
        flush(b, false);
        b->insts.push_back(i);
      } else {
        b->insts.push_back(i);
      }
    }
  }

  // Stores the current value of every global (all of them, or those this function writes),
  // except where that value is a load of the same global that this pass keeps (at the entry or
  // after a call): memory already holds it. A load of the program's own is no such proof: it is
  // replaced by the value it would read, and the memory behind it may never have been written
  // (`acc = 0; acc = acc; f();` must store 0 before calling f).
  void flush(Block* b, bool all) {
    for (int g = 0; g < n_; ++g) {
      if (!all && !written_.count(g)) continue;
      Inst* v = ssa_.read(g, b);
      if (v->op == Op::GLoad && v->aux == g && kept_loads_.count(v)) continue;
      b->insts.push_back(make(Op::GStore, b, g, {v}));
    }
  }

  bool is_entry_load(Inst* i) const {
    auto it = entry_loads_.find(i->aux);
    return it != entry_loads_.end() && it->second == i;
  }

  int n_;
  Function& f_;
  SsaBuilder ssa_;
  std::unordered_set<int> written_;
  std::unordered_set<Block*> filled_;
  std::unordered_map<int, Inst*> entry_loads_;
  std::unordered_set<Inst*> kept_loads_;  // the loads this pass adds, which stay real loads
  std::vector<std::pair<Inst*, Inst*>> replaced_;
  Inst* nan_ = nullptr;
};

}  // namespace

bool run_promote_globals(Module& m) {
  bool changed = false;
  for (auto& f : m.functions) changed |= Promoter(m, *f).run();
  return changed;
}

}  // namespace fscript::ir
