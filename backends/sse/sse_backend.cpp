// SSE backend glue: generate, map W^X, and run groups of four points (the tail padded).
#include "backends/sse/sse_backend.h"

#include <algorithm>
#include <cmath>

#include <pthread.h>

namespace fscript::sse {

constexpr uintptr_t kStackMargin = 256 * 1024;

std::unique_ptr<backend::Kernel> SseBackend::compile(const ir::Module& m, const backend::Budgets& budgets,
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
                                     bound, bound > 0 ? m.clone() : nullptr);
}

// Finite and within the bound; NaN fails the test too. No early exit, so the loop vectorises.
bool SseKernel::in_range(const float* const* inputs, size_t n) const {
  float bound = static_cast<float>(param_bound_);
  bool ok = true;
  for (size_t k = 0; k < inputs_; ++k)
    for (size_t i = 0; i < n; ++i) ok &= std::fabs(inputs[k][i]) <= bound;
  return ok;
}

KernelFn SseKernel::general(backend::RuntimeError& err) const {
  std::call_once(general_once_, [this] {
    std::string error;
    std::vector<uint8_t> code = generate(*module_, budgets_, error);
    if (!code.empty()) general_ = CodeMemory::create(code, error);
    if (!general_) general_error_ = "the sse backend could not compile the kernel's general code: " + error;
  });
  if (!general_) err.message = general_error_;
  return general_ ? entry(*general_) : nullptr;
}

// The same messages as the VM's.
bool SseKernel::status(uint64_t code, const backend::LaneArrays& arrays, backend::RuntimeError& err) const {
  if (code == 0) return true;
  err.line = static_cast<uint32_t>(code);
  switch (code >> 32) {
    case 1:
      err.message = "loop iteration budget exceeded: more than " + std::to_string(budgets_.max_loop_iterations) +
                    " iterations in one evaluation";
      break;
    case 2: err.message = arrays.message; break;
    case 3:
      err.message =
          "call depth budget exceeded: more than " + std::to_string(budgets_.max_call_depth) + " nested calls";
      break;
    default:
      err.message = "recursion too deep for this thread's stack (the budget allows " +
                    std::to_string(budgets_.max_call_depth) +
                    " nested calls); lower --max-call-depth or use --backend vm";
      break;
  }
  return false;
}

// The lowest address a called function's frame may reach on this thread: its stack's end plus a
// margin for the runtime functions the code calls. Found once per thread.
static uintptr_t stack_limit() {
  thread_local uintptr_t limit = [] {
    pthread_attr_t attr;
    void* addr = nullptr;
    size_t size = 0;
    if (pthread_getattr_np(pthread_self(), &attr) != 0)  // then assume the smallest usual stack
      return reinterpret_cast<uintptr_t>(__builtin_frame_address(0)) - (size_t{1} << 20) + kStackMargin;
    pthread_attr_getstack(&attr, &addr, &size);
    pthread_attr_destroy(&attr);
    return reinterpret_cast<uintptr_t>(addr) + kStackMargin;
  }();
  return limit;
}

backend::LaneArrays SseKernel::fresh_arrays() const {
  backend::LaneArrays s;
  s.init(4, budgets_.max_array_elements, arrays_);
  return s;
}

namespace {
// Small lists live on the stack: the one-point path must not allocate.
template <typename T>
struct Scratch {
  explicit Scratch(size_t n) : heap(n > 32 ? n : 0) { data = n > 32 ? heap.data() : local; }
  T local[32];
  std::vector<T> heap;
  T* data;
};
}  // namespace

bool SseKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n, backend::RuntimeError& err) const {
  KernelFn f = entry(*code_);
  if (param_bound_ > 0 && !in_range(inputs, n) && !(f = general(err))) return false;
  return run(f, inputs, outputs, n, err);
}

bool SseKernel::run(KernelFn f, const float* const* inputs, float* const* outputs, size_t n,
                    backend::RuntimeError& err) const {
  size_t whole = n & ~size_t{3};
  // Per call: batches may run on several threads at once. Only kernels with arrays need it.
  backend::LaneArrays arrays;
  if (!arrays_.empty()) arrays = fresh_arrays();
  if (whole && !status(f(inputs, outputs, 0, whole, &arrays, stack_limit()), arrays, err)) return false;
  if (whole == n) return true;
  // The last one to three points, through four-lane copies.
  Scratch<float> in(4 * inputs_), out(4 * outputs_);
  Scratch<const float*> ip(inputs_);
  Scratch<float*> op(outputs_);
  std::fill_n(in.data, 4 * inputs_, 0.0f);
  for (size_t k = 0; k < inputs_; ++k) {
    std::copy(inputs[k] + whole, inputs[k] + n, in.data + 4 * k);
    ip.data[k] = in.data + 4 * k;
  }
  for (size_t k = 0; k < outputs_; ++k) op.data[k] = out.data + 4 * k;
  if (!status(f(ip.data, op.data, 0, 4, &arrays, stack_limit()), arrays, err)) return false;
  for (size_t k = 0; k < outputs_; ++k) std::copy_n(out.data + 4 * k, n - whole, outputs[k] + whole);
  return true;
}

bool SseKernel::eval(const float* inputs, float* outputs, backend::RuntimeError& err) const {
  Scratch<const float*> in(inputs_);
  Scratch<float*> out(outputs_);
  for (size_t k = 0; k < inputs_; ++k) in.data[k] = inputs + k;
  for (size_t k = 0; k < outputs_; ++k) out.data[k] = outputs + k;
  return eval_batch(in.data, out.data, 1, err);
}

}  // namespace fscript::sse
