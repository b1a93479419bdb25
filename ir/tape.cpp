// A flat tape copied into an IR kernel function, op for op.
#include "ir/tape.h"

namespace fscript::ir {

size_t tape_length(const Function& fn) {
  size_t n = 0;
  for (const auto& b : fn.blocks)
    for (const Inst* in : b->insts) n += in->defines_value();
  return n;
}

std::unique_ptr<Module> tape_module(const IntervalTape& t) {
  auto m = std::make_unique<Module>();
  auto f = std::make_unique<Function>();
  f->name = "FRep";
  f->num_params = t.num_params();
  f->num_results = static_cast<uint32_t>(t.outputs().size());
  f->kernel = true;
  Block* b = f->add_block();
  std::vector<Inst*> value(t.num_values(), nullptr);
  auto add = [&](Inst* in) {
    in->block = b;
    b->insts.push_back(in);
  };
  for (const IntervalTape::Step& s : t.steps()) {
    Inst* in = f->make(s.op);
    in->imm = s.imm;
    if (s.op == Op::Param) in->aux = static_cast<int32_t>(s.a);
    const uint32_t operands[] = {s.a, s.b, s.c};
    for (size_t k = 0; k < s.arity && s.op != Op::Param; ++k) in->args.push_back(value[operands[k]]);
    value[s.dst] = in;
    add(in);
  }
  Inst* r = f->make(Op::Ret);
  for (uint32_t o : t.outputs()) r->args.push_back(value[o]);
  add(r);
  m->functions.push_back(std::move(f));
  return m;
}

}  // namespace fscript::ir
