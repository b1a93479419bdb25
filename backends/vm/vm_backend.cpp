// VM backend glue: compile to bytecode, evaluate through the executor.
#include "backends/vm/vm_backend.h"

#include "backends/vm/vm_exec.h"

namespace fscript::vm {

bool run_batch(const VmProgram& p, const backend::Budgets& budgets, const float* const* inputs,
               float* const* outputs, size_t n, backend::RuntimeError& err) {
  switch (math::active_isa()) {
    case math::Isa::Base: return isa_base::run_batch(p, budgets, inputs, outputs, n, err);
    case math::Isa::Avx2: return isa_avx2::run_batch(p, budgets, inputs, outputs, n, err);
    case math::Isa::Avx512: return isa_avx512::run_batch(p, budgets, inputs, outputs, n, err);
  }
  return false;
}

std::unique_ptr<backend::Kernel> VmBackend::compile(const ir::Module& m, const backend::Budgets& b,
                                                    std::string& error) const {
  VmProgram p;
  if (!compile_program(m, p, error)) return nullptr;
  return std::make_unique<VmKernel>(std::move(p), b);
}

bool VmKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                          backend::RuntimeError& err) const {
  return run_batch(prog_, budgets_, inputs, outputs, n, err);
}

bool VmKernel::eval(const float* inputs, float* outputs, backend::RuntimeError& err) const {
  std::vector<const float*> in(num_inputs());
  std::vector<float*> out(num_outputs());
  for (size_t k = 0; k < in.size(); ++k) in[k] = inputs + k;
  for (size_t k = 0; k < out.size(); ++k) out[k] = outputs + k;
  return run_batch(prog_, budgets_, in.data(), out.data(), 1, err);
}

}  // namespace fscript::vm
