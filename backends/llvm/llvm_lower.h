#pragma once
// Our SSA IR to LLVM IR: every value a vector of `width` floats (the host's SIMD width), control
// flow masked as in the VM and the SSE backend (a pending lane mask per block, blocks in reverse
// post-order, back edges that jump back while lanes wait), recursive functions as callees run
// under their caller's lane mask. Exact float semantics: no fast-math flag anywhere.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "ir/ir.h"

namespace llvm {
class LLVMContext;
class Module;
}  // namespace llvm

namespace fscript::llvmjit {

// The runtime functions generated code calls, by symbol name (resolved by the JIT, llvm_jit.cpp).
// FS_RUNTIME(symbol, address, float operands)
#define FS_LLVM_RUNTIME_FUNCTIONS(X)                                                                   \
  X(fs_rt_exp, exp, 1) X(fs_rt_log, log, 1) X(fs_rt_log10, log10, 1) X(fs_rt_sin, sin, 1)            \
  X(fs_rt_cos, cos, 1) X(fs_rt_tan, tan, 1) X(fs_rt_asin, asin, 1) X(fs_rt_acos, acos, 1)            \
  X(fs_rt_atan, atan, 1) X(fs_rt_sinh, sinh, 1) X(fs_rt_cosh, cosh, 1) X(fs_rt_tanh, tanh, 1)        \
  X(fs_rt_pow, pow, 2) X(fs_rt_atan2, atan2, 2) X(fs_rt_noise, noise, 3)

// The generated kernel: points [begin, end) (end - begin a multiple of the width). Returns 0 or
// (kind << 32) | line: 1 loop budget, 2 array error (message in `arrays`), 3 call depth budget,
// 4 recursion deeper than the thread's stack allows (below `stack_limit`).
using KernelFn = uint64_t (*)(const float* const* inputs, float* const* outputs, uint64_t begin, uint64_t end,
                              void* arrays, uintptr_t stack_limit);
constexpr const char* kKernelSymbol = "fs_kernel";

struct Lowered {
  std::unique_ptr<llvm::LLVMContext> context;
  std::unique_ptr<llvm::Module> module;
  std::vector<std::string> array_names;  // by slot: the module's global arrays, then each function's
  uint32_t num_inputs = 0, num_outputs = 0;
};

// Lowers the module's kernel and every function it calls (after inlining the non-recursive ones).
// With `param_bound` > 0 the code may assume every input finite with |x| <= param_bound (see
// ir/ranges.h) and drops NaN tests the ranges prove useless.
bool lower(const ir::Module& m, uint32_t width, const backend::Budgets& budgets, double param_bound, Lowered& out,
           std::string& error);

// The parameter bound worth assuming for this module's kernel (0: none removes a NaN test).
double choose_param_bound(const ir::Module& m);

}  // namespace fscript::llvmjit
