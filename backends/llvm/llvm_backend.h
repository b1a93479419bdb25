#pragma once
// The LLVM backend: the kernel lowered to vector LLVM IR at the host's SIMD width, optimised and
// compiled in-process by ORC LLJIT (llvm_jit.h). Batches run in groups of `width` points, the
// tail padded; like the SSE backend, code that assumes bounded inputs (no NaN tests where value
// ranges prove them useless) runs only batches whose inputs are in range.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/llvm/llvm_jit.h"

namespace fscript::llvmjit {

class LlvmKernel : public backends::Kernel {
 public:
  LlvmKernel(std::shared_ptr<Program> code, uint32_t width, size_t inputs, size_t outputs,
             const backends::Budgets& budgets, std::vector<std::string> array_names, double param_bound,
             std::unique_ptr<ir::Module> module, uint32_t row_from);
  size_t num_inputs() const override { return inputs_; }
  size_t num_outputs() const override { return outputs_; }
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                  backends::RuntimeError& err) const override;
  bool eval(const float* inputs, float* outputs, backends::RuntimeError& err) const override;
  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 backends::RuntimeError& err) const override;

 private:
  KernelFn general(backends::RuntimeError& err) const;
  PointFn scalar(backends::RuntimeError& err) const;
  std::shared_ptr<Program> code_;
  uint32_t width_;
  size_t inputs_, outputs_;
  backends::Budgets budgets_;
  std::vector<std::string> arrays_;
  double param_bound_;
  std::unique_ptr<ir::Module> module_;  // for the general and the one-point code
  uint32_t row_from_;                   // the kernel's row parameters (ir::Function::row_params_from)
  std::vector<ir::ParamRange> row_ranges_;  // what the bounded code assumes of them
  mutable std::once_flag general_once_;
  mutable std::shared_ptr<Program> general_;
  mutable std::string general_error_;
  mutable std::once_flag scalar_once_;
  mutable std::shared_ptr<Program> scalar_;
  mutable std::atomic<PointFn> scalar_fn_{nullptr};  // scalar_'s entry once compiled
  mutable std::string scalar_error_;
};

class LlvmBackend : public backends::Backend {
 public:
  explicit LlvmBackend(uint32_t width = 0) : width_(width ? width : host_width()) {}
  std::string name() const override { return "llvm"; }
  std::unique_ptr<backends::Kernel> compile(const ir::Module& m, const backends::Budgets& b,
                                            std::string& error) const override;

 private:
  uint32_t width_;
};

// Compiles the module's kernel at `width` lanes; `bounded` as in lower_to_llvm().
std::shared_ptr<Program> compile_module(const ir::Module& m, uint32_t width, const backends::Budgets& budgets,
                                        bool bounded, Lowered& lowered, double& compile_ms, std::string& error);

// Whether compile_module(m, width, budgets, true, ...) would find the code in a cache (in memory or
// on disk) instead of compiling it.
bool code_cached(const ir::Module& m, uint32_t width, const backends::Budgets& budgets);
// The module's kernel as optimised LLVM IR (`fscript emit-ir --llvm`) or as the host's assembly
// (`fscript emit-asm --backend llvm`), at the host's width; empty with a message on failure.
std::string kernel_text(const ir::Module& m, const backends::Budgets& budgets, bool assembly, std::string& error);

}  // namespace fscript::llvmjit
