// Tape simplification: collapse decided choices, keep what the outputs still reach, copy it out.
#include "ir/tape.h"

namespace fscript::ir {

size_t tape_length(const Function& fn) {
  size_t n = 0;
  for (const auto& b : fn.blocks)
    for (const Inst* in : b->insts) n += in->defines_value();
  return n;
}

SimplifiedTape simplify_tape(const Function& fn, const IntervalEval& ev) {
  SimplifiedTape out;
  const auto& insts = fn.entry()->insts;
  // What each value stands for in the region: itself, or the side a decided choice takes.
  std::vector<const Inst*> stands(fn.next_value, nullptr);
  for (const Inst* in : insts) {
    if (!in->defines_value()) continue;
    const Inst* s = in;
    Choice c = ev.choices[in->id];
    if (c != Choice::Both && (in->op == Op::Min || in->op == Op::Max))
      s = stands[in->args[c == Choice::Left ? 0 : 1]->id];
    if (c != Choice::Both && in->op == Op::Select) s = stands[in->args[c == Choice::Left ? 1 : 2]->id];
    out.choices_collapsed += s != in;
    stands[in->id] = s;
  }
  // Live: what the outputs reach through the collapsed choices.
  const Inst* ret = fn.entry()->terminator();
  std::vector<char> live(fn.next_value, 0);
  for (const Inst* a : ret->args) live[stands[a->id]->id] = 1;
  for (auto it = insts.rbegin(); it != insts.rend(); ++it) {
    const Inst* in = *it;
    if (in->op == Op::Ret || !live[in->id]) continue;
    for (const Inst* a : in->args) live[stands[a->id]->id] = 1;
  }
  // The copy, in the original order.
  out.module = std::make_unique<Module>();
  auto f = std::make_unique<Function>();
  f->name = fn.name;
  f->num_params = fn.num_params;
  f->num_results = fn.num_results;
  f->kernel = true;
  Block* b = f->add_block();
  std::vector<Inst*> copy(fn.next_value, nullptr);
  for (const Inst* in : insts) {
    if (in->op == Op::Ret || !live[in->id]) continue;
    Inst* c = f->make(in->op);
    c->imm = in->imm;
    c->aux = in->aux;
    c->line = in->line;
    for (const Inst* a : in->args) c->args.push_back(copy[stands[a->id]->id]);
    c->block = b;
    b->insts.push_back(c);
    copy[in->id] = c;
    ++out.ops;
  }
  Inst* r = f->make(Op::Ret);
  for (const Inst* a : ret->args) r->args.push_back(copy[stands[a->id]->id]);
  r->block = b;
  b->insts.push_back(r);
  out.module->functions.push_back(std::move(f));
  return out;
}

}  // namespace fscript::ir
