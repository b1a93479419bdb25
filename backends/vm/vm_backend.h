#pragma once
// The VM backend: bytecode interpreter behind the Kernel interface.
#include "backends/backend.h"
#include "backends/vm/bytecode.h"
#include "ir/interval_eval.h"

namespace fscript::vm {

class VmKernel : public backends::Kernel {
 public:
  VmKernel(VmProgram p, const backends::Budgets& b) : prog_(std::move(p)), budgets_(b) {}
  size_t num_inputs() const override { return prog_.functions[prog_.kernel].num_params; }
  size_t num_outputs() const override { return prog_.functions[prog_.kernel].num_results; }
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                  backends::RuntimeError& err) const override;
  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 backends::RuntimeError& err) const override;
  bool eval(const float* inputs, float* outputs, backends::RuntimeError& err) const override;
  const VmProgram& program() const { return prog_; }

 private:
  VmProgram prog_;
  backends::Budgets budgets_;
};

// A flat straight-line tape (a region's simplified kernel) to bytecode, with no IR in between:
// one block, registers reused after their last use, constants as immediates or registers set once.
VmProgram tape_program(const ir::IntervalTape& t);
std::unique_ptr<backends::Kernel> compile_tape(const ir::IntervalTape& t, const backends::Budgets& b);

class VmBackend : public backends::Backend {
 public:
  std::string name() const override { return "vm"; }
  std::unique_ptr<backends::Kernel> compile(const ir::Module& m, const backends::Budgets& b,
                                            std::string& error) const override;
};

}  // namespace fscript::vm
