// IR data structures: op table expansion, instruction and block bookkeeping.
#include "ir/ir.h"

#include <algorithm>
#include <unordered_map>

namespace fscript::ir {

const OpInfo kOpInfo[] = {
#define FS_OP(N, M, A, F, FN, HOW) {M, A, (F) | how_flags(MathHow::HOW)},
#include "ir/opcodes.def"
};

bool Inst::defines_value() const { return !has_flag(op, static_cast<OpFlag>(NoValue | Terminator)); }

std::vector<Block*> Block::succs() const {
  Inst* t = terminator();
  if (!t || (t->op != Op::Jump && t->op != Op::Branch)) return {};
  return t->targets;
}

size_t Block::first_non_phi() const {
  size_t i = 0;
  while (i < insts.size() && insts[i]->op == Op::Phi) ++i;
  return i;
}

Inst* Function::make(Op op) {
  pool.push_back(std::make_unique<Inst>());
  Inst* i = pool.back().get();
  i->op = op;
  i->id = next_value++;
  return i;
}

Block* Function::add_block() {
  blocks.push_back(std::make_unique<Block>());
  Block* b = blocks.back().get();
  b->id = next_block++;
  b->fn = this;
  return b;
}

void Function::remove_unreachable_blocks() {
  std::vector<Block*> stack{entry()};
  std::unordered_map<Block*, bool> seen{{entry(), true}};
  while (!stack.empty()) {
    Block* b = stack.back();
    stack.pop_back();
    for (Block* s : b->succs())
      if (!seen[s]) {
        seen[s] = true;
        stack.push_back(s);
      }
  }
  for (auto& b : blocks) {
    if (seen[b.get()]) continue;
    for (Block* s : b->succs())
      if (seen[s]) remove_pred(s, b.get());
  }
  std::erase_if(blocks, [&](const std::unique_ptr<Block>& b) { return !seen[b.get()]; });
}

void Function::renumber() {
  uint32_t v = 0, bid = 0;
  for (auto& b : blocks) {
    b->id = bid++;
    for (Inst* i : b->insts) i->id = v++;
  }
  next_value = v;
  next_block = bid;
}

const Function& Module::kernel_function() const {
  for (const auto& f : functions)
    if (f->kernel) return *f;
  return *functions.front();
}

int Module::find_function(const std::string& name) const {
  for (size_t i = 0; i < functions.size(); ++i)
    if (functions[i]->name == name) return static_cast<int>(i);
  return -1;
}

size_t Module::instruction_count() const {
  size_t n = 0;
  for (const auto& f : functions)
    for (const auto& b : f->blocks) n += b->insts.size();
  return n;
}

int Module::global_slot(const std::string& name) {
  for (size_t i = 0; i < globals.size(); ++i)
    if (globals[i] == name) return static_cast<int>(i);
  globals.push_back(name);
  return static_cast<int>(globals.size()) - 1;
}

std::unique_ptr<Function> shell_of(const Function& src) {
  auto fn = std::make_unique<Function>();
  fn->name = src.name;
  fn->num_params = src.num_params;
  fn->num_results = src.num_results;
  fn->recursive = src.recursive;
  fn->kernel = src.kernel;
  fn->row_params_from = src.row_params_from;
  fn->row_param_ranges = src.row_param_ranges;
  fn->arrays = src.arrays;
  return fn;
}

static std::unique_ptr<Function> clone_function(const Function& src) {
  auto fn = shell_of(src);
  std::unordered_map<const Block*, Block*> bmap;
  std::unordered_map<const Inst*, Inst*> imap;
  for (auto& b : src.blocks) bmap[b.get()] = fn->add_block();
  for (auto& b : src.blocks)
    for (Inst* i : b->insts) {
      Inst* n = fn->make(i->op);
      *n = *i;
      imap[i] = n;
    }
  for (auto& b : src.blocks) {
    Block* nb = bmap[b.get()];
    nb->id = b->id;
    for (Block* p : b->preds) nb->preds.push_back(bmap[p]);
    for (Inst* i : b->insts) {
      Inst* n = imap[i];
      n->block = nb;
      for (auto& a : n->args) a = imap[a];
      for (auto& t : n->targets) t = bmap[t];
      nb->insts.push_back(n);
    }
  }
  fn->next_value = src.next_value;
  fn->next_block = src.next_block;
  return fn;
}

std::unique_ptr<Module> Module::clone() const {
  auto m = std::make_unique<Module>();
  m->globals = globals;
  m->arrays = arrays;
  for (auto& f : functions) m->functions.push_back(clone_function(*f));
  return m;
}

void replace_uses(Function& fn, std::vector<Inst*>& rep) {
  auto resolve = [&](Inst* v) {
    while (v->id < rep.size() && rep[v->id] && rep[v->id] != v) v = rep[v->id];
    return v;
  };
  for (auto& b : fn.blocks)
    for (Inst* i : b->insts)
      for (auto& a : i->args) a = resolve(a);
}

void erase(Inst* inst) {
  auto& v = inst->block->insts;
  v.erase(std::find(v.begin(), v.end(), inst));
}

void retarget(Block* pred, Block* old_succ, Block* new_succ) {
  Inst* t = pred->terminator();
  for (auto& s : t->targets)
    if (s == old_succ) s = new_succ;
  auto& ps = old_succ->preds;
  ps.erase(std::find(ps.begin(), ps.end(), pred));
  new_succ->preds.push_back(pred);
}

void remove_pred(Block* b, Block* pred) {
  for (Inst* i : b->insts) {
    if (i->op != Op::Phi) break;
    for (size_t k = 0; k < i->targets.size(); ++k)
      if (i->targets[k] == pred) {
        i->targets.erase(i->targets.begin() + k);
        i->args.erase(i->args.begin() + k);
        break;
      }
  }
  auto it = std::find(b->preds.begin(), b->preds.end(), pred);
  if (it != b->preds.end()) b->preds.erase(it);
}

}  // namespace fscript::ir
