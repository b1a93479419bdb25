#pragma once
// What the JIT backends (sse, llvm) share around their generated code: the runtime-error codes
// it returns, the native stack limit it checks recursion against, the bounded-input guard, and
// running a batch in whole groups of lanes with the tail padded.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "backends/lane_arrays.h"

namespace fscript::backends {

// A module as the JIT backends compile it: calls of non-recursive functions inlined (masked lanes
// have no call stack of their own; an unoptimised module still has such calls), the kernel found,
// and every function it reaches through the calls left (recursive ones, compiled as callees).
struct JitProgram {
  std::unique_ptr<ir::Module> inlined;  // set when inlining had work to do
  const ir::Module* module = nullptr;   // the module to compile (`inlined` or the original)
  int kernel = -1;
  std::vector<int> functions;           // by index in the module: the kernel, then its callees
  int num_globals = 0;                  // global slots any of them uses
};
bool prepare_program(const ir::Module& m, JitProgram& out, std::string& error);

// The first source position in a function (for errors raised at its entry), or null.
const ir::Inst* first_located(const ir::Function& fn);

// Generated code returns 0 or trap_code(kind, line, col): kind 1 loop budget, 2 array error
// (message in `arrays`), 3 call depth budget, 4 recursion deeper than the thread's stack allows,
// 5 the run cancelled (support/cancel.h; asked at every loop iteration and recursive call).
// The column keeps 24 bits (a longer line reports column 0: unknown).
inline uint64_t trap_code(uint64_t kind, const ir::Inst* at) {
  uint64_t line = at ? at->line : 0, col = at && at->col < (1u << 24) ? at->col : 0;
  return kind << 56 | col << 32 | line;
}
inline uint64_t trap_kind(uint64_t code) { return code >> 56; }
// Returns whether `code` is 0, else fills `err` with the VM's message for it.
bool jit_status(uint64_t code, const LaneArrays& arrays, const Budgets& budgets, RuntimeError& err);

// The lowest address a called function's frame may reach on this thread: the end of its stack
// plus a margin for the runtime functions generated code calls. Found once per thread.
uintptr_t stack_limit();

// Runs `thunk(ctx)` on a fresh thread with a stack that holds the deepest recursion the call budget
// allows (kCallDepthCeiling frames; reserved, committed only as touched). Returns its result, or
// `fallback` when no such thread can be made.
uint64_t on_budget_stack(uint64_t (*thunk)(void*), void* ctx, uint64_t fallback);

// Calls generated code (`call()` returns its status). When its recursion outgrew this thread's
// stack (status 4), calls it again on a stack sized for the budget: the call budget, not the host's
// stack limit, decides how deep recursion goes. Generated code is a pure function of its inputs
// (outputs are overwritten, arrays start afresh per group), so the second call gives what one call
// on a big stack would have given.
template <typename Call>
uint64_t call_generated(const Call& call) {
  uint64_t code = call();
  if (trap_kind(code) != 4) return code;
  auto thunk = [](void* c) -> uint64_t { return (*static_cast<const Call*>(c))(); };
  return on_budget_stack(thunk, const_cast<Call*>(&call), code);
}

// The SSE backend's loop counters for budgets beyond int32, called when a lane's int32 counter at
// `counters` passes INT32_MAX - 1: moves the counts into the four int64 totals that follow them
// (16 bytes on) and returns 1 when a lane is over the budget.
extern "C" uint32_t fs_ticks_carry(int32_t* counters, uint64_t budget);

// `%` over a batch (math::mod per point): what the compiling backends call for it, as the batch
// twins of the other runtime rows.
void mod_batch(const float* a, const float* b, float* out, size_t n);

// Every input of the batch finite with |x| <= bound (NaN fails too).
// Inputs from `row_from` on (when not 0) are one value each: a row parameter (ir::Function), held
// to its range in `row_ranges` (one per row parameter) when given, else to the bound.
bool inputs_in_range(const float* const* inputs, size_t num_inputs, size_t n, double bound, uint32_t row_from = 0,
                     const ir::ParamRange* row_ranges = nullptr);
// The ranges the bounded code for `bound` assumes of the kernel's row parameters (empty: none known).
std::vector<ir::ParamRange> row_ranges_for(const ir::Function& fn, double bound);

// Small lists live on the stack: the one-point path must not allocate.
template <typename T, size_t N = 64>
struct Scratch {
  explicit Scratch(size_t n) : heap(n > N ? n : 0) { data = n > N ? heap.data() : local; }
  T local[N];
  std::vector<T> heap;
  T* data;
};

// Runs `group_fn(inputs, outputs, count)` on the whole groups of `width` points, then on the
// last points copied into one padded group (the unused lanes repeat the last point).
template <typename GroupFn>
bool run_padded(uint32_t width, size_t num_inputs, size_t num_outputs, const float* const* inputs,
                float* const* outputs, size_t n, GroupFn group_fn, uint32_t row_from = 0) {
  size_t whole = n - n % width;
  if (whole && !group_fn(inputs, outputs, whole)) return false;
  if (whole == n) return true;
  Scratch<float, 256> in(width * num_inputs), out(width * num_outputs);
  Scratch<const float*> ip(num_inputs);
  Scratch<float*> op(num_outputs);
  // The padding lanes repeat the last point: a lane of made-up inputs (zeros) could raise a runtime
  // error no real point raises (an index out of a zero-length array, a loop that never ends).
  for (size_t k = 0; k < num_inputs; ++k) {
    if (row_from && k >= row_from) {  // a row parameter: its one value
      ip.data[k] = inputs[k];
      continue;
    }
    std::copy(inputs[k] + whole, inputs[k] + n, in.data + width * k);
    std::fill(in.data + width * k + (n - whole), in.data + width * (k + 1), inputs[k][n - 1]);
    ip.data[k] = in.data + width * k;
  }
  for (size_t k = 0; k < num_outputs; ++k) op.data[k] = out.data + width * k;
  if (!group_fn(ip.data, op.data, width)) return false;
  for (size_t k = 0; k < num_outputs; ++k) std::copy_n(out.data + width * k, n - whole, outputs[k] + whole);
  return true;
}

// What a JIT kernel's shape is to run a batch: its inputs and outputs, the arrays its code keeps
// per call and the lanes they are laid out for, its budgets and row parameters.
struct JitShape {
  size_t num_inputs = 0, num_outputs = 0;
  const std::vector<std::string>* array_names = nullptr;
  uint32_t array_lanes = 4;
  Budgets budgets;
  uint32_t row_from = 0;
};

// A batch through generated batch code `f` at `width` lanes (both JITs): padded groups, lane
// arrays of this call's own (batches may run on several threads at once), the code's status as
// `err`.
template <typename Fn>
bool run_generated(Fn f, uint32_t width, const JitShape& k, const float* const* inputs, float* const* outputs, size_t n,
                   RuntimeError& err) {
  LaneArrays arrays;
  if (!k.array_names->empty()) arrays.init(k.array_lanes, k.budgets.max_array_elements, *k.array_names);
  return run_padded(
      width, k.num_inputs, k.num_outputs, inputs, outputs, n,
      [&](auto in, auto out, size_t count) {
        uint64_t code = call_generated([&] { return f(in, out, 0, count, &arrays, stack_limit()); });
        return jit_status(code, arrays, k.budgets, err);
      },
      k.row_from);
}

// A JIT kernel's eval_rows: with row parameters (from `row_from` on, not 0) one eval_batch per
// row, whose compiled code reads each row parameter's one value; without, the points expanded.
template <typename JitKernel>
bool jit_eval_rows(const JitKernel& k, uint32_t row_from, const float* first, size_t count, const float* const* rest,
                   size_t rows, float* const* outputs, RuntimeError& err) {
  if (!row_from) return k.Kernel::eval_rows(first, count, rest, rows, outputs, err);
  Scratch<const float*> in(k.num_inputs());
  Scratch<float*> out(k.num_outputs());
  in.data[0] = first;
  for (size_t r = 0; r < rows; ++r) {
    for (size_t i = 1; i < k.num_inputs(); ++i) in.data[i] = rest[i - 1] + r;
    for (size_t o = 0; o < k.num_outputs(); ++o) out.data[o] = outputs[o] + r * count;
    if (!k.eval_batch(in.data, out.data, count, err)) return false;
  }
  return true;
}

// One point as a batch of one.
template <typename Kernel>
bool eval_one(const Kernel& kernel, size_t num_inputs, size_t num_outputs, const float* inputs, float* outputs,
              RuntimeError& err) {
  Scratch<const float*> in(num_inputs);
  Scratch<float*> out(num_outputs);
  for (size_t k = 0; k < num_inputs; ++k) in.data[k] = inputs + k;
  for (size_t k = 0; k < num_outputs; ++k) out.data[k] = outputs + k;
  return kernel.eval_batch(in.data, out.data, 1, err);
}

}  // namespace fscript::backends
