#pragma once
// The SSE backend: the kernel function compiled to x86-64 machine code that evaluates four points
// per iteration in xmm registers (packed single precision; eight in ymm registers for straight-line
// kernels where the CPU has AVX2), our own encoder, register allocation
// and W^X code memory. Branches and loops run masked (sse_compile.cpp), arrays through helpers
// (sse_arrays.h); recursive functions are compiled too and called with the caller's lane mask.
#include <atomic>
#include <memory>
#include <mutex>

#include "backends/backend.h"
#include "backends/jit_support.h"
#include "backends/sse/code_memory.h"
#include "backends/lane_arrays.h"

namespace fscript::sse {

// The generated function: points [begin, end) of the batch, end - begin a multiple of its lanes (4
// or 8, from generate). Returns 0,
// or a runtime error: backends::trap_code(kind, source position), kind 1 = the loop budget, 2 = an
// array error (its message in `arrays`), 3 = the call depth budget, 4 = recursion deeper than the
// thread's stack allows (a called function's frame would go below `stack_limit`).
using KernelFn = uint64_t (*)(const float* const* inputs, float* const* outputs, uint64_t begin, uint64_t end,
                              backends::LaneArrays* arrays, uintptr_t stack_limit);
// The one-point code: the point's inputs and outputs as plain arrays, begin 0 and end 4.
using PointFn = uint64_t (*)(const float* inputs, float* outputs, uint64_t begin, uint64_t end,
                             backends::LaneArrays* arrays, uintptr_t stack_limit);

// A kernel whose code assumes bounded inputs (param_bound > 0: every input finite with |x| <=
// param_bound, which lets it drop NaN handling the value ranges prove useless) runs batches with
// an input outside that range through the general code, compiled on first need from `module`.
// One-point calls run code compiled for four equal lanes, also on first need.
class SseKernel : public backends::Kernel {
 public:
  SseKernel(std::unique_ptr<CodeMemory> code, size_t inputs, size_t outputs, const backends::Budgets& budgets,
            std::vector<std::string> array_names, double param_bound, std::unique_ptr<ir::Module> module,
            uint32_t row_from, uint32_t lanes)
      : code_(std::move(code)), inputs_(inputs), outputs_(outputs), budgets_(budgets), arrays_(std::move(array_names)),
        param_bound_(param_bound), module_(std::move(module)), row_from_(row_from), lanes_(lanes) {
    if (module_ && param_bound_ > 0) row_ranges_ = backends::row_ranges_for(module_->kernel_function(), param_bound_);
  }
  size_t num_inputs() const override { return inputs_; }
  size_t num_outputs() const override { return outputs_; }
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                  backends::RuntimeError& err) const override;
  bool eval(const float* inputs, float* outputs, backends::RuntimeError& err) const override;
  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 backends::RuntimeError& err) const override;
  const CodeMemory& code() const { return *code_; }
  uint32_t lanes() const { return lanes_; }  // points per iteration of the batch code

 private:
  static KernelFn entry(const CodeMemory& c) { return reinterpret_cast<KernelFn>(const_cast<uint8_t*>(c.start())); }
  bool in_range(const float* const* inputs, size_t n) const;
  KernelFn general(backends::RuntimeError& err) const;
  PointFn point(backends::RuntimeError& err) const;
  bool eval_general(const float* inputs, float* outputs, backends::RuntimeError& err) const;
  bool run(KernelFn f, uint32_t lanes, const float* const* inputs, float* const* outputs, size_t n,
           backends::RuntimeError& err) const;
  backends::LaneArrays fresh_arrays() const;
  std::unique_ptr<CodeMemory> code_;
  size_t inputs_, outputs_;
  backends::Budgets budgets_;
  std::vector<std::string> arrays_;  // names by slot
  double param_bound_;
  std::unique_ptr<ir::Module> module_;
  uint32_t row_from_;  // the kernel's row parameters (ir::Function::row_params_from)
  uint32_t lanes_;
  std::vector<ir::ParamRange> row_ranges_;  // what the bounded code assumes of them
  mutable std::once_flag general_once_;
  mutable std::unique_ptr<CodeMemory> general_;
  mutable uint32_t general_lanes_ = 4;
  mutable std::string general_error_;
  mutable std::once_flag point_once_;
  mutable std::unique_ptr<CodeMemory> point_;  // the one-point code, bounded as code_ is
  mutable std::atomic<PointFn> point_fn_{nullptr};
  mutable std::string point_error_;
};

class SseBackend : public backends::Backend {
 public:
  std::string name() const override { return "sse"; }
  std::unique_ptr<backends::Kernel> compile(const ir::Module& m, const backends::Budgets& b,
                                            std::string& error) const override;
};

// The machine code of the module's kernel; empty with a message when the kernel uses what this
// stage does not compile. `listing`, when given, receives the code as assembly text (emit-asm).
// With `param_bound`, the code may assume bounded inputs and says the bound it chose (0: none).
// With `uniform_lanes`, the one-point code (a PointFn): the four lanes of its one group hold the
// same point, read from and written to plain arrays; work done per pair of lanes is done once.
// `lanes` receives the points per iteration of the code: 8 for a straight-line kernel (no globals,
// arrays, loops or user calls) where the CPU has AVX2 (not FSCRIPT_ISA=base), else 4.
std::vector<uint8_t> generate(const ir::Module& m, const backends::Budgets& budgets, std::string& error,
                              std::string* listing = nullptr, std::vector<std::string>* array_names = nullptr,
                              double* param_bound = nullptr, bool uniform_lanes = false, uint32_t* lanes = nullptr);

}  // namespace fscript::sse
