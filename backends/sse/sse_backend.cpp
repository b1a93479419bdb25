// SSE backend glue: generate, map W^X, and run groups of four points (the tail padded).
#include "backends/sse/sse_backend.h"

#include <algorithm>

namespace fscript::sse {

std::unique_ptr<backend::Kernel> SseBackend::compile(const ir::Module& m, const backend::Budgets&,
                                                     std::string& error) const {
  if (!__builtin_cpu_supports("sse4.1")) {  // roundps, blendvps
    error = "the sse backend needs a CPU with SSE4.1";
    return nullptr;
  }
  std::vector<uint8_t> code = generate(m, error);
  if (code.empty()) return nullptr;
  auto memory = CodeMemory::create(code, error);
  if (!memory) return nullptr;
  const ir::Function* fn = nullptr;
  for (const auto& f : m.functions)
    if (f->kernel) fn = f.get();
  return std::make_unique<SseKernel>(std::move(memory), fn->num_params, fn->num_results);
}

bool SseKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n, backend::RuntimeError&) const {
  size_t whole = n & ~size_t{3};
  if (whole) fn()(inputs, outputs, 0, whole);
  if (whole == n) return true;
  // The last one to three points, through four-lane copies.
  std::vector<float> in(4 * inputs_, 0.0f), out(4 * outputs_, 0.0f);
  std::vector<const float*> ip(inputs_);
  std::vector<float*> op(outputs_);
  for (size_t k = 0; k < inputs_; ++k) {
    std::copy(inputs[k] + whole, inputs[k] + n, in.begin() + 4 * k);
    ip[k] = in.data() + 4 * k;
  }
  for (size_t k = 0; k < outputs_; ++k) op[k] = out.data() + 4 * k;
  fn()(ip.data(), op.data(), 0, 4);
  for (size_t k = 0; k < outputs_; ++k) std::copy_n(out.begin() + 4 * k, n - whole, outputs[k] + whole);
  return true;
}

bool SseKernel::eval(const float* inputs, float* outputs, backend::RuntimeError& err) const {
  std::vector<const float*> in(inputs_);
  std::vector<float*> out(outputs_);
  for (size_t k = 0; k < inputs_; ++k) in[k] = inputs + k;
  for (size_t k = 0; k < outputs_; ++k) out[k] = outputs + k;
  return eval_batch(in.data(), out.data(), 1, err);
}

}  // namespace fscript::sse
