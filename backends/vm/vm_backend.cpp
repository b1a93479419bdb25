// VM backend glue: compile to bytecode, evaluate through the executor.
#include "backends/vm/vm_backend.h"

#include "backends/vm/vm_exec.h"
#include "runtime/support/big_stack.h"

namespace fscript::vm {

namespace {
bool run_isa(const VmProgram& p, const backends::Budgets& budgets, const float* const* inputs, float* const* outputs,
             size_t n, size_t row_length, backends::RuntimeError& err, bool& out_of_stack) {
  switch (math::active_isa()) {
    case math::Isa::Base: return isa_base::run_batch(p, budgets, inputs, outputs, n, row_length, err, out_of_stack);
    case math::Isa::Avx2: return isa_avx2::run_batch(p, budgets, inputs, outputs, n, row_length, err, out_of_stack);
    case math::Isa::Avx512: return isa_avx512::run_batch(p, budgets, inputs, outputs, n, row_length, err, out_of_stack);
  }
  return false;
}
}  // namespace

bool run_batch(const VmProgram& p, const backends::Budgets& budgets, const float* const* inputs, float* const* outputs,
               size_t n, size_t row_length, backends::RuntimeError& err) {
  bool out_of_stack = false;
  bool ok = run_isa(p, budgets, inputs, outputs, n, row_length, err, out_of_stack);
  if (!out_of_stack) return ok;
  // The whole batch again (evaluation is a pure function of the inputs) on a 1 GiB stack, which
  // holds kCallDepthCeiling levels of the executor's recursion.
  out_of_stack = false;
  support::run_with_big_stack([&] { ok = run_isa(p, budgets, inputs, outputs, n, row_length, err, out_of_stack); });
  return ok;
}

std::unique_ptr<backends::Kernel> VmBackend::compile(const ir::Module& m, const backends::Budgets& b,
                                                     std::string& error) const {
  VmProgram p;
  if (!compile_program(m, p, error)) return nullptr;
  return std::make_unique<VmKernel>(std::move(p), b);
}

bool VmKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                          backends::RuntimeError& err) const {
  return run_batch(prog_, budgets_, inputs, outputs, n, n, err);  // a kernel with row parameters: one row
}

bool VmKernel::eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                         backends::RuntimeError& err) const {
  if (!prog_.row_params_from) return Kernel::eval_rows(first, count, rest, rows, outputs, err);
  std::vector<const float*> in(num_inputs());
  in[0] = first;
  for (size_t k = 1; k < in.size(); ++k) in[k] = rest[k - 1];
  return run_batch(prog_, budgets_, in.data(), outputs, rows * count, count, err);
}

bool VmKernel::eval(const float* inputs, float* outputs, backends::RuntimeError& err) const {
  std::vector<const float*> in(num_inputs());
  std::vector<float*> out(num_outputs());
  for (size_t k = 0; k < in.size(); ++k) in[k] = inputs + k;
  for (size_t k = 0; k < out.size(); ++k) out[k] = outputs + k;
  return run_batch(prog_, budgets_, in.data(), out.data(), 1, 1, err);
}

}  // namespace fscript::vm
