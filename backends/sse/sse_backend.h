#pragma once
// The SSE backend: the kernel function compiled to x86-64 machine code that evaluates four points
// per iteration in xmm registers (packed single precision), our own encoder, register allocation
// and W^X code memory. This stage compiles straight-line kernels (one block: what inlining,
// global promotion and if-conversion leave of most scripts); a kernel with loops, branches left
// after if-conversion, arrays, global memory or recursion is refused with a message naming the
// operation (use --backend vm for those).
#include <memory>

#include "backends/backend.h"
#include "backends/sse/code_memory.h"

namespace fscript::sse {

// The generated function: points [begin, end) of the batch, end - begin a multiple of 4.
using KernelFn = void (*)(const float* const* inputs, float* const* outputs, uint64_t begin, uint64_t end);

class SseKernel : public backend::Kernel {
 public:
  SseKernel(std::unique_ptr<CodeMemory> code, size_t inputs, size_t outputs)
      : code_(std::move(code)), inputs_(inputs), outputs_(outputs) {}
  size_t num_inputs() const override { return inputs_; }
  size_t num_outputs() const override { return outputs_; }
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n, backend::RuntimeError& err) const override;
  bool eval(const float* inputs, float* outputs, backend::RuntimeError& err) const override;
  const CodeMemory& code() const { return *code_; }

 private:
  KernelFn fn() const { return reinterpret_cast<KernelFn>(const_cast<uint8_t*>(code_->start())); }
  std::unique_ptr<CodeMemory> code_;
  size_t inputs_, outputs_;
};

class SseBackend : public backend::Backend {
 public:
  std::string name() const override { return "sse"; }
  std::unique_ptr<backend::Kernel> compile(const ir::Module& m, const backend::Budgets& b, std::string& error) const override;
};

// The machine code of the module's kernel; empty with a message when the kernel uses what this
// stage does not compile. `listing`, when given, receives the code as assembly text (emit-asm).
std::vector<uint8_t> generate(const ir::Module& m, std::string& error, std::string* listing = nullptr);

}  // namespace fscript::sse
