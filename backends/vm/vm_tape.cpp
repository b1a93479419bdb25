// Flat tape -> VM bytecode. Parameter registers come first and stay until their last use (the
// executor fills them before the code runs); every other value takes a free register and gives it
// back after its last use; constants are immediates of binary ops, else registers set once per run.
// Also the entry of running a flat tape at a few points with no bytecode at all (vm_points.h).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <cstring>

#include "backends/vm/vm_backend.h"
#include "backends/vm/vm_points.h"

namespace fscript::vm {

VmProgram tape_program(const ir::IntervalTape& t) {
  using Step = ir::IntervalTape::Step;
  const auto& steps = t.steps();
  VmProgram p;
  p.functions.emplace_back();
  VmFunction& f = p.functions.back();
  f.name = "FRep";
  f.num_params = t.num_params();
  f.num_results = static_cast<uint32_t>(t.outputs().size());
  f.param_regs.assign(f.num_params, kNoReg);
  const uint32_t n = t.num_values(), kForever = UINT32_MAX;
  std::vector<const Step*> def(n, nullptr);
  std::vector<uint32_t> last(n, 0), reg(n, kNoReg), free;
  for (uint32_t i = 0; i < steps.size(); ++i) {
    const Step& s = steps[i];
    def[s.dst] = &s;
    const uint32_t operands[] = {s.a, s.b, s.c};
    for (size_t k = 0; k < s.arity && s.op != ir::Op::Param; ++k) last[operands[k]] = i;
  }
  for (uint32_t o : t.outputs()) last[o] = kForever;
  for (const Step& s : steps)
    if (s.op == ir::Op::Param && s.a < f.num_params && f.param_regs[s.a] == kNoReg)
      f.param_regs[s.a] = reg[s.dst] = f.num_regs++;
  auto const_reg = [&](uint32_t v) {
    if (reg[v] == kNoReg) f.consts.push_back({reg[v] = f.num_regs++, def[v]->imm});
    return reg[v];
  };
  for (uint32_t i = 0; i < steps.size(); ++i) {
    const Step& s = steps[i];
    if (s.op == ir::Op::Const || s.op == ir::Op::Param) continue;
    VInst v;
    v.op = s.op;
    const uint32_t operands[] = {s.a, s.b, s.c};
    uint32_t* slots[] = {&v.a, &v.b, &v.c};
    for (size_t k = 0; k < s.arity; ++k) {
      const Step& d = *def[operands[k]];
      if (d.op == ir::Op::Const && k < 2 && takes_immediates(s.op)) {
        v.kinds |= static_cast<uint8_t>(1u << k);
        (k == 0 ? v.imm_a : v.imm_b) = d.imm;
      } else {
        *slots[k] = d.op == ir::Op::Const ? const_reg(operands[k]) : reg[operands[k]];
      }
    }
    if (free.empty()) {
      v.dst = f.num_regs++;
    } else {
      v.dst = free.back();
      free.pop_back();
    }
    reg[s.dst] = v.dst;
    f.code.push_back(v);
    for (size_t k = 0; k < s.arity; ++k)  // operands dying here (once each, not constants)
      if (last[operands[k]] == i && def[operands[k]]->op != ir::Op::Const && (k == 0 || operands[k] != operands[0]) &&
          (k < 2 || operands[k] != operands[1]))
        free.push_back(reg[operands[k]]);
  }
  VBlock b;
  b.end = static_cast<uint32_t>(f.code.size());
  b.term = ir::Op::Ret;
  for (uint32_t o : t.outputs()) b.results.push_back(def[o]->op == ir::Op::Const ? const_reg(o) : reg[o]);
  f.blocks.push_back(std::move(b));
  p.kernel = 0;
  return p;
}

void eval_tape_points(const ir::IntervalTape& t, const float* const* inputs, size_t num_inputs, size_t n, float* out) {
  float* outs[1] = {out};
  eval_tape_points(t, inputs, num_inputs, n, outs, 1);
}

void eval_tape_points(const ir::IntervalTape& t, const float* const* inputs, size_t num_inputs, size_t n,
                      float* const* out, size_t count) {
  struct Free {
    void operator()(float* p) const { std::free(p); }
  };
  thread_local std::unique_ptr<float[], Free> values;  // kPointLanes floats per value id, kept per thread
  thread_local size_t capacity = 0;
  size_t need = size_t(t.num_values()) * kPointLanes;
  if (need > capacity) {
    values.reset(static_cast<float*>(std::aligned_alloc(64, std::max<size_t>(need, 1) * sizeof(float))));
    capacity = need;
  }
  float* v = values.get();
  // Only the lanes the batch fills, in whole vectors: a region's batch is often a few tiles of 16.
  const size_t lanes = std::min(kPointLanes, std::max<size_t>(16, (n + 15) & ~size_t{15}));
  for (const ir::IntervalTape::Step& s : t.steps()) {
    if (s.op != ir::Op::Param) continue;
    float* d = v + size_t(s.dst) * kPointLanes;
    size_t given = s.a < num_inputs && inputs[s.a] ? n : 0;
    if (given) std::memcpy(d, inputs[s.a], given * sizeof(float));
    std::memset(d + given, 0, (lanes - given) * sizeof(float));
  }
  switch (math::active_isa()) {
    case math::Isa::Base: isa_base::run_tape_points(t.steps().data(), t.steps().size(), v, lanes); break;
    case math::Isa::Avx2: isa_avx2::run_tape_points(t.steps().data(), t.steps().size(), v, lanes); break;
    case math::Isa::Avx512: isa_avx512::run_tape_points(t.steps().data(), t.steps().size(), v, lanes); break;
  }
  for (size_t k = 0; k < count; ++k) std::memcpy(out[k], v + size_t(t.outputs()[k]) * kPointLanes, n * sizeof(float));
}

std::unique_ptr<backends::Kernel> compile_tape(const ir::IntervalTape& t, const backends::Budgets& b) {
  return std::make_unique<VmKernel>(tape_program(t), b);
}

}  // namespace fscript::vm
