#pragma once
// On-the-fly SSA construction (Braun, Buchwald, Hack, Leissa, Mallon, Zwinkau, CC 2013), shared by
// the AST lowering (variables = local symbols) and the promote_globals pass (variables = global
// slots). Blocks are sealed once all their predecessors are known; trivial phis are removed.
#include <functional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "ir/ir.h"

namespace fscript::ir {

class SsaBuilder {
 public:
  // `undefined(var, block)` supplies the value of a variable read where no definition reaches
  // (the entry block): NaN for a local, a gload for a global in a called function.
  using UndefinedFn = std::function<Inst*(int var)>;

  SsaBuilder(Function& fn, UndefinedFn undefined) : fn_(fn), undefined_(std::move(undefined)) {}

  void write(int var, Block* b, Inst* v) { defs_[b][var] = v; }
  Inst* read(int var, Block* b);
  void seal(Block* b);
  bool is_sealed(Block* b) const { return sealed_.count(b) != 0; }
  // Rewrites every operand that names a removed phi; call once when construction is done.
  void finish();
  Inst* resolve(Inst* v) const;

 private:
  Inst* read_recursive(int var, Block* b);
  Inst* add_phi_operands(int var, Inst* phi);
  Inst* remove_trivial_phi(int var, Inst* phi);
  Inst* new_phi(Block* b);

  Function& fn_;
  UndefinedFn undefined_;
  std::unordered_map<Block*, std::unordered_map<int, Inst*>> defs_;
  std::unordered_set<Block*> sealed_;
  std::unordered_map<Block*, std::vector<std::pair<int, Inst*>>> incomplete_;
  std::vector<Inst*> rep_;  // by value id: what a removed trivial phi became
};

}  // namespace fscript::ir
