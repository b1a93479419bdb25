// SSE backend glue: generate, map W^X, and run groups of four points (the tail padded).
#include "backends/sse/sse_backend.h"

#include "backends/jit_support.h"

namespace fscript::sse {

std::unique_ptr<backends::Kernel> SseBackend::compile(const ir::Module& m, const backends::Budgets& budgets,
                                                     std::string& error) const {
  if (!__builtin_cpu_supports("sse4.1")) {  // roundps, blendvps
    error = "the sse backend needs a CPU with SSE4.1";
    return nullptr;
  }
  std::vector<std::string> arrays;
  double bound = 0;
  std::vector<uint8_t> code = generate(m, budgets, error, nullptr, &arrays, &bound);
  if (code.empty()) return nullptr;
  auto memory = CodeMemory::create(code, error);
  if (!memory) return nullptr;
  const ir::Function* fn = nullptr;
  for (const auto& f : m.functions)
    if (f->kernel) fn = f.get();
  return std::make_unique<SseKernel>(std::move(memory), fn->num_params, fn->num_results, budgets, std::move(arrays),
                                     bound, bound > 0 ? m.clone() : nullptr, fn->row_params_from);
}

KernelFn SseKernel::general(backends::RuntimeError& err) const {
  std::call_once(general_once_, [this] {
    std::string error;
    std::vector<uint8_t> code = generate(*module_, budgets_, error);
    if (!code.empty()) general_ = CodeMemory::create(code, error);
    if (!general_) general_error_ = "the sse backend could not compile the kernel's general code: " + error;
  });
  if (!general_) err.message = general_error_;
  return general_ ? entry(*general_) : nullptr;
}

bool SseKernel::in_range(const float* const* inputs, size_t n) const {
  return backends::inputs_in_range(inputs, inputs_, n, param_bound_, row_from_,
                                   row_ranges_.empty() ? nullptr : row_ranges_.data());
}

backends::LaneArrays SseKernel::fresh_arrays() const {
  backends::LaneArrays s;
  s.init(4, budgets_.max_array_elements, arrays_);
  return s;
}

bool SseKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n, backends::RuntimeError& err) const {
  KernelFn f = entry(*code_);
  if (param_bound_ > 0 && !in_range(inputs, n) && !(f = general(err))) return false;
  return run(f, inputs, outputs, n, err);
}

bool SseKernel::run(KernelFn f, const float* const* inputs, float* const* outputs, size_t n,
                    backends::RuntimeError& err) const {
  // Per call: batches may run on several threads at once. Only kernels with arrays need it.
  backends::LaneArrays arrays;
  if (!arrays_.empty()) arrays = fresh_arrays();
  return backends::run_padded(4, inputs_, outputs_, inputs, outputs, n, [&](auto in, auto out, size_t count) {
    uint64_t code = backends::call_generated([&] { return f(in, out, 0, count, &arrays, backends::stack_limit()); });
    return backends::jit_status(code, arrays, budgets_, err);
  }, row_from_);
}

bool SseKernel::eval_rows(const float* first, size_t count, const float* const* rest, size_t rows,
                          float* const* outputs, backends::RuntimeError& err) const {
  return backends::jit_eval_rows(*this, row_from_, first, count, rest, rows, outputs, err);
}

// One point: the four lanes of one group all hold it, straight into the code (the batch path's
// padding copies and per-call array state cost more than a small kernel's work).
bool SseKernel::eval(const float* inputs, float* outputs, backends::RuntimeError& err) const {
  constexpr size_t kMaxDirect = 16;
  if (inputs_ > kMaxDirect || outputs_ > kMaxDirect || !arrays_.empty() || row_from_)
    return backends::eval_one(*this, inputs_, outputs_, inputs, outputs, err);
  alignas(16) float in[4 * kMaxDirect], out[4 * kMaxDirect];
  const float* ip[kMaxDirect];
  float* op[kMaxDirect];
  for (size_t k = 0; k < inputs_; ++k) {
    for (size_t l = 0; l < 4; ++l) in[4 * k + l] = inputs[k];
    ip[k] = in + 4 * k;
  }
  for (size_t k = 0; k < outputs_; ++k) op[k] = out + 4 * k;
  KernelFn f = entry(*code_);
  if (param_bound_ > 0 && !in_range(ip, 1) && !(f = general(err))) return false;
  static const backends::LaneArrays no_arrays;  // code without arrays never touches its argument
  uint64_t code = backends::call_generated([&] { return f(ip, op, 0, 4, nullptr, backends::stack_limit()); });
  if (!backends::jit_status(code, no_arrays, budgets_, err)) return false;
  for (size_t k = 0; k < outputs_; ++k) outputs[k] = out[4 * k];
  return true;
}

}  // namespace fscript::sse
