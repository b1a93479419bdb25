// LLVM backend glue: lower, compile (or find in the cache), run groups of `width` points.
#include "backends/llvm/llvm_backend.h"

#include "backends/jit_support.h"
#include "ir/text.h"

namespace fscript::llvmjit {

namespace {
// Changed whenever llvm_lower.cpp changes the code it makes, so the disk cache never hands back an
// object from an older lowering (2: the lanes' mask crosses calls as an integer; 3: min and max as
// x86's own instructions; 4: the one-point code's own entry; 5: the cancel check in loops and
// recursive calls).
constexpr int kLoweringRevision = 5;

// The cache key: everything the code depends on.
std::string cache_key(const ir::Module& m, uint32_t width, const backends::Budgets& budgets, bool bounded) {
  return ir::print(m) + "\nlowering " + std::to_string(kLoweringRevision) + " width " + std::to_string(width) +
      " bounded " + std::to_string(bounded) + " loops " + std::to_string(budgets.max_loop_iterations) + " depth " +
      std::to_string(budgets.max_call_depth) + " elements " + std::to_string(budgets.max_array_elements);
}
}  // namespace

bool code_cached(const ir::Module& m, uint32_t width, const backends::Budgets& budgets) {
  return has_code(cache_key(m, width, budgets, true));
}

std::shared_ptr<Program> compile_module(const ir::Module& m, uint32_t width, const backends::Budgets& budgets,
                                        bool bounded, Lowered& lowered, double& compile_ms, std::string& error) {
  compile_ms = 0;
  std::string key = cache_key(m, width, budgets, bounded) + (lowered.point_entry ? " point" : "");
  if (std::shared_ptr<Program> hit = cached(key)) return hit;
  if (!lower_to_llvm(m, width, budgets, bounded, lowered, error)) return nullptr;
  return llvmjit::compile(std::move(lowered), key, compile_ms, error);
}

std::unique_ptr<backends::Kernel> LlvmBackend::compile(const ir::Module& m, const backends::Budgets& budgets,
                                                       std::string& error) const {
  Lowered lowered;
  double ms = 0;
  std::shared_ptr<Program> code = compile_module(m, width_, budgets, true, lowered, ms, error);
  if (!code) return nullptr;
  const Program& p = *code;
  return std::make_unique<LlvmKernel>(std::move(code), width_, p.num_inputs, p.num_outputs, budgets, p.array_names,
                                      p.param_bound, m.clone(), m.kernel_function().row_params_from);
}

LlvmKernel::LlvmKernel(std::shared_ptr<Program> code, uint32_t width, size_t inputs, size_t outputs,
                       const backends::Budgets& budgets, std::vector<std::string> array_names, double param_bound,
                       std::unique_ptr<ir::Module> module, uint32_t row_from)
    : code_(std::move(code)), width_(width), inputs_(inputs), outputs_(outputs), budgets_(budgets),
      arrays_(std::move(array_names)), param_bound_(param_bound), module_(std::move(module)), row_from_(row_from) {
  if (module_ && param_bound_ > 0) row_ranges_ = backends::row_ranges_for(module_->kernel_function(), param_bound_);
}

KernelFn LlvmKernel::general(backends::RuntimeError& err) const {
  std::call_once(general_once_, [this] {
    Lowered lowered;
    double ms = 0;
    std::string error;
    general_ = compile_module(*module_, width_, budgets_, false, lowered, ms, error);
    if (!general_) general_error_ = "the llvm backend could not compile the kernel's general code: " + error;
  });
  if (!general_) err.message = general_error_;
  return general_ ? general_->entry() : nullptr;
}

bool LlvmKernel::eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                            backends::RuntimeError& err) const {
  KernelFn f = code_->entry();
  if (param_bound_ > 0 &&
      !backends::inputs_in_range(inputs, inputs_, n, param_bound_, row_from_,
                                 row_ranges_.empty() ? nullptr : row_ranges_.data()) &&
      !(f = general(err)))
    return false;
  return backends::run_generated(f, width_, {inputs_, outputs_, &arrays_, width_, budgets_, row_from_}, inputs, outputs,
                                 n, err);
}

bool LlvmKernel::eval_rows(const float* first, size_t count, const float* const* rest, size_t rows,
                           float* const* outputs, backends::RuntimeError& err) const {
  return backends::jit_eval_rows(*this, row_from_, first, count, rest, rows, outputs, err);
}

// One point: the kernel compiled again at one lane with its own entry (on the first call), so a
// call costs one point's work, not a padded group's. Its code is general (no bounded-input
// assumptions): no range check.
PointFn LlvmKernel::scalar(backends::RuntimeError& err) const {
  if (PointFn ready = scalar_fn_.load(std::memory_order_acquire)) return ready;  // no call_once per call
  std::call_once(scalar_once_, [this] {
    Lowered lowered;
    lowered.point_entry = true;
    double ms = 0;
    std::string error;
    scalar_ = compile_module(*module_, 1, budgets_, false, lowered, ms, error);
    if (!scalar_) scalar_error_ = "the llvm backend could not compile the kernel's one-point code: " + error;
    else scalar_fn_.store(scalar_->point(), std::memory_order_release);
  });
  if (!scalar_) err.message = scalar_error_;
  return scalar_ ? scalar_->point() : nullptr;
}

bool LlvmKernel::eval(const float* inputs, float* outputs, backends::RuntimeError& err) const {
  PointFn f = scalar(err);
  if (!f) return false;
  // Code without arrays never touches its arrays argument: no LaneArrays to build per call (two
  // calls, not one through a std::optional: measured 15 ns a call slower).
  static const backends::LaneArrays no_arrays;
  if (arrays_.empty()) {
    uint64_t code = backends::call_generated([&] { return f(inputs, outputs, nullptr, backends::stack_limit()); });
    return backends::jit_status(code, no_arrays, budgets_, err);
  }
  backends::LaneArrays arrays;
  arrays.init(1, budgets_.max_array_elements, arrays_);
  uint64_t code = backends::call_generated([&] { return f(inputs, outputs, &arrays, backends::stack_limit()); });
  return backends::jit_status(code, arrays, budgets_, err);
}

std::string kernel_text(const ir::Module& m, const backends::Budgets& budgets, bool assembly, std::string& error) {
  Lowered lowered;
  if (!lower_to_llvm(m, host_width(), budgets, true, lowered, error)) return "";
  std::string head = "; " + std::to_string(host_width()) + " lanes" +
      (lowered.param_bound > 0 ? "; inputs finite with |x| <= " +
               std::to_string(static_cast<int>(lowered.param_bound)) + " (other batches run the general code)"
                               : std::string()) +
      "\n";
  std::string text = assembly ? llvmjit::assembly(lowered, error) : optimized_ir(lowered, error);
  return text.empty() ? "" : head + text;
}

}  // namespace fscript::llvmjit
