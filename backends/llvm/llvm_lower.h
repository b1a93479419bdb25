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

// Generated code calls runtime functions by symbol name (fs_rt_* for runtime/math's batch
// functions, fs_lanes_* for arrays); the JIT resolves them from one table (llvm_jit.cpp).

// The generated kernel: points [begin, end) (end - begin a multiple of the width). Returns 0 or
// backends::trap_code(kind, position): 1 loop budget, 2 array error (message in `arrays`), 3 call
// depth budget, 4 recursion deeper than the thread's stack allows (below `stack_limit`).
using KernelFn = uint64_t (*)(const float* const* inputs, float* const* outputs, uint64_t begin, uint64_t end,
                              void* arrays, uintptr_t stack_limit);
constexpr const char* kKernelSymbol = "fs_kernel";
// One point (Kernel::eval, a one-lane module lowered with Lowered::point_entry): the inputs and
// outputs as plain arrays, so a call builds no lists of pointers; same return codes.
using PointFn = uint64_t (*)(const float* inputs, float* outputs, void* arrays, uintptr_t stack_limit);
constexpr const char* kPointSymbol = "fs_point";

struct Lowered {
  Lowered();
  ~Lowered();
  Lowered(Lowered&&) noexcept;
  std::unique_ptr<llvm::LLVMContext> context;
  std::unique_ptr<llvm::Module> module;
  std::vector<std::string> array_names;  // by slot: the module's global arrays, then each function's
  uint32_t num_inputs = 0, num_outputs = 0;
  double param_bound = 0;
  bool point_entry = false;  // set by the caller: the module exports kPointSymbol, not kKernelSymbol
};

// Lowers the module's kernel and every function it calls (after inlining the non-recursive ones).
// With `bounded`, the code may assume every input finite with |x| <= out.param_bound (the bound
// ir::best_param_bound picks; 0 when none removes a NaN test) and drops the NaN tests the value
// ranges prove useless.
bool lower_to_llvm(const ir::Module& m, uint32_t width, const backends::Budgets& budgets, bool bounded, Lowered& out,
                   std::string& error);

}  // namespace fscript::llvmjit
