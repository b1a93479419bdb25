// SSE backend glue: generate, map W^X, and run groups of four or eight points (the tail padded).
#include "backends/sse/sse_backend.h"

#include <cmath>

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
  uint32_t lanes = 4;
  std::vector<uint8_t> code = generate(m, budgets, error, nullptr, &arrays, &bound, false, &lanes);
  if (code.empty()) return nullptr;
  auto memory = CodeMemory::create(code, error);
  if (!memory) return nullptr;
  const ir::Function* fn = nullptr;
  for (const auto& f : m.functions)
    if (f->kernel) fn = f.get();
  return std::make_unique<SseKernel>(std::move(memory), fn->num_params, fn->num_results, budgets, std::move(arrays),
                                     bound, m.clone(), fn->row_params_from, lanes);
}

KernelFn SseKernel::general(backends::RuntimeError& err) const {
  std::call_once(general_once_, [this] {
    std::string error;
    std::vector<uint8_t> code = generate(*module_, budgets_, error, nullptr, nullptr, nullptr, false, &general_lanes_);
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

bool SseKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                           backends::RuntimeError& err) const {
  if (param_bound_ > 0 && !in_range(inputs, n)) {
    KernelFn g = general(err);
    return g && run(g, general_lanes_, inputs, outputs, n, err);
  }
  return run(entry(*code_), lanes_, inputs, outputs, n, err);
}

bool SseKernel::run(KernelFn f, uint32_t lanes, const float* const* inputs, float* const* outputs, size_t n,
                    backends::RuntimeError& err) const {
  return backends::run_generated(f, lanes, {inputs_, outputs_, &arrays_, 4, budgets_, row_from_}, inputs, outputs, n,
                                 err);
}

bool SseKernel::eval_rows(const float* first, size_t count, const float* const* rest, size_t rows,
                          float* const* outputs, backends::RuntimeError& err) const {
  return backends::jit_eval_rows(*this, row_from_, first, count, rest, rows, outputs, err);
}

PointFn SseKernel::point(backends::RuntimeError& err) const {
  if (PointFn ready = point_fn_.load(std::memory_order_acquire)) return ready;  // no call_once per call
  std::call_once(point_once_, [this] {
    std::string error;
    double bound = 0;
    std::vector<uint8_t> code = generate(*module_, budgets_, error, nullptr, nullptr, &bound, true);
    if (!code.empty() && bound == param_bound_) point_ = CodeMemory::create(code, error);
    else if (!code.empty()) error = "its input bound differs from the batch code's";
    if (!point_) point_error_ = "the sse backend could not compile the kernel's one-point code: " + error;
    else point_fn_.store(reinterpret_cast<PointFn>(const_cast<uint8_t*>(point_->start())), std::memory_order_release);
  });
  if (!point_) err.message = point_error_;
  return point_fn_.load(std::memory_order_acquire);
}

// One point: code made for a group whose four lanes hold it, reading and writing the caller's
// arrays (the batch path's padding copies cost more than a small kernel's work). A point outside
// the bounded code's range takes the general code, the point in each lane of a group.
bool SseKernel::eval(const float* inputs, float* outputs, backends::RuntimeError& err) const {
  if (row_from_) return backends::eval_one(*this, inputs_, outputs_, inputs, outputs, err);
  float bound = static_cast<float>(param_bound_);
  bool bounded = true;
  for (size_t k = 0; k < inputs_; ++k) bounded &= std::fabs(inputs[k]) <= bound;  // NaN fails
  if (param_bound_ > 0 && !bounded) return eval_general(inputs, outputs, err);
  PointFn f = point(err);
  if (!f) return false;
  static const backends::LaneArrays no_arrays;  // code without arrays never touches its argument
  if (arrays_.empty()) {
    uint64_t code =
        backends::call_generated([&] { return f(inputs, outputs, 0, 4, nullptr, backends::stack_limit()); });
    return backends::jit_status(code, no_arrays, budgets_, err);
  }
  backends::LaneArrays arrays = fresh_arrays();
  uint64_t code = backends::call_generated([&] { return f(inputs, outputs, 0, 4, &arrays, backends::stack_limit()); });
  return backends::jit_status(code, arrays, budgets_, err);
}

bool SseKernel::eval_general(const float* inputs, float* outputs, backends::RuntimeError& err) const {
  KernelFn f = general(err);
  if (!f) return false;
  backends::Scratch<const float*> in(inputs_);
  backends::Scratch<float*> out(outputs_);
  for (size_t k = 0; k < inputs_; ++k) in.data[k] = inputs + k;
  for (size_t k = 0; k < outputs_; ++k) out.data[k] = outputs + k;
  return run(f, general_lanes_, in.data, out.data, 1, err);
}

}  // namespace fscript::sse
