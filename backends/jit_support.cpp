// Runtime errors, the stack limit and the input guard of the JIT backends.
#include "backends/jit_support.h"

#ifdef __EMSCRIPTEN__
#include <emscripten/stack.h>
#endif

#include "ir/ranges.h"

#include <pthread.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "backends/runtime_errors.h"
#include "ir/analysis.h"
#include "ir/passes/passes.h"
#include "runtime/math/math.h"
#include "runtime/support/big_stack.h"

namespace fscript::backends {

namespace {
constexpr uintptr_t kStackMargin = 256 * 1024;
}

bool prepare_program(const ir::Module& m, JitProgram& out, std::string& error) {
  out.module = &m;
  bool calls = false;
  for (const auto& f : m.functions)
    for (const auto& blk : f->blocks)
      for (const ir::Inst* in : blk->insts) calls |= in->op == ir::Op::Call;
  if (calls) {
    out.inlined = m.clone();
    error = ir::run_passes(*out.inlined, "inline");
    if (!error.empty()) return false;
    out.module = out.inlined.get();
  }
  const ir::Module& p = *out.module;
  for (size_t f = 0; f < p.functions.size(); ++f)
    if (p.functions[f]->kernel) out.kernel = static_cast<int>(f);
  if (out.kernel < 0) {
    error = "the module has no kernel function";
    return false;
  }
  out.functions = {out.kernel};
  std::vector<bool> seen(p.functions.size(), false);
  seen[static_cast<size_t>(out.kernel)] = true;
  for (size_t i = 0; i < out.functions.size(); ++i)
    for (const auto& blk : p.functions[static_cast<size_t>(out.functions[i])]->blocks)
      for (const ir::Inst* in : blk->insts) {
        if (in->op == ir::Op::GLoad || in->op == ir::Op::GStore)
          out.num_globals = std::max(out.num_globals, in->aux + 1);
        if (in->op == ir::Op::Call && !seen[static_cast<size_t>(in->aux)]) {
          seen[static_cast<size_t>(in->aux)] = true;
          out.functions.push_back(in->aux);
        }
      }
  return true;
}

const ir::Inst* first_located(const ir::Function& fn) {
  for (const ir::Block* blk : ir::reverse_post_order(fn))
    for (const ir::Inst* in : blk->insts)
      if (in->line) return in;
  return nullptr;
}

bool jit_status(uint64_t code, const LaneArrays& arrays, const Budgets& budgets, RuntimeError& err) {
  if (code == 0) return true;
  err.line = static_cast<uint32_t>(code);
  err.col = static_cast<uint32_t>(code >> 32) & 0xFFFFFFu;
  switch (trap_kind(code)) {
    case 1: err.message = errors::loop_budget(budgets.max_loop_iterations); break;
    case 2: err.message = arrays.message; break;
    case 3: err.message = errors::call_depth(budgets.max_call_depth); break;
    case 5: err.message = errors::cancelled(); break;
    default: err.message = errors::recursion_stack(budgets.max_call_depth); break;
  }
  return false;
}

uintptr_t stack_limit() {
  // Initial-exec TLS without a dynamic initializer: one load per call, also in the llvm module
  // (a dlopened library's default model calls __tls_get_addr, a third of a small kernel's call).
  static thread_local uintptr_t limit __attribute__((tls_model("initial-exec"))) = 0;
  if (limit) return limit;
#ifdef __EMSCRIPTEN__
  // The shadow stack's bounds (TOTAL_STACK at link time): pthread_getattr_np reports none here, and
  // the fallback below, measured from wherever the first call happens, cut recursion short.
  limit = emscripten_stack_get_end() + kStackMargin;
  return limit;
#endif
  pthread_attr_t attr;
  void* addr = nullptr;
  size_t size = 0;
  if (pthread_getattr_np(pthread_self(), &attr) != 0) {  // then assume the smallest usual stack
    limit = reinterpret_cast<uintptr_t>(__builtin_frame_address(0)) - (size_t{1} << 20) + kStackMargin;
    return limit;
  }
  pthread_attr_getstack(&attr, &addr, &size);
  pthread_attr_destroy(&attr);
  limit = reinterpret_cast<uintptr_t>(addr) + kStackMargin;
  return limit;
}

uint64_t on_budget_stack(uint64_t (*thunk)(void*), void* ctx, uint64_t fallback) {
  // 1 GiB (the default): kCallDepthCeiling frames of up to 10 KiB (the widest vector spills) with
  // room to spare. If no such thread can be made the thunk runs here and overflows its guard again.
  uint64_t result = fallback;
  support::run_with_big_stack([&] { result = thunk(ctx); });
  return result;
}

void mod_batch(const float* a, const float* b, float* out, size_t n) {
  for (size_t i = 0; i < n; ++i) out[i] = math::mod(a[i], b[i]);
}

extern "C" uint32_t fs_ticks_carry(int32_t* counters, uint64_t budget) {
  // Invariant: a lane's ticks so far = totals + counters. The counter restarts so that it passes
  // the generated code's int32 threshold exactly when the lane passes the budget (or, when that
  // is further than int32 reaches, at the next carry).
  constexpr int64_t kThreshold = INT32_MAX - 1;
  auto* totals = reinterpret_cast<int64_t*>(reinterpret_cast<char*>(counters) + 16);
  uint32_t over = 0;
  for (int i = 0; i < 4; ++i) {
    int64_t ticks = totals[i] + counters[i];
    if (static_cast<uint64_t>(ticks) > budget) {
      over = 1;
      continue;
    }
    int64_t start =
        kThreshold - std::min<int64_t>(kThreshold, static_cast<int64_t>(budget - static_cast<uint64_t>(ticks)));
    counters[i] = static_cast<int32_t>(start);
    totals[i] = ticks - start;
  }
  return over;
}

// No early exit, so the loop vectorises.
std::vector<ir::ParamRange> row_ranges_for(const ir::Function& fn, double bound) {
  std::vector<ir::ParamRange> out;
  for (uint32_t k = fn.row_params_from; fn.row_params_from && k < fn.num_params; ++k)
    if (const ir::ParamRange* r = ir::row_param_range(fn, bound, k)) out.push_back(*r);
  if (out.size() != (fn.row_params_from ? fn.num_params - fn.row_params_from : 0)) out.clear();
  return out;
}

bool inputs_in_range(const float* const* inputs, size_t num_inputs, size_t n, double bound, uint32_t row_from,
                     const ir::ParamRange* row_ranges) {
  float b = static_cast<float>(bound);
  bool ok = true;
  for (size_t k = 0; k < num_inputs; ++k) {
    if (row_from && k >= row_from && row_ranges) {
      const ir::ParamRange& r = row_ranges[k - row_from];
      float v = inputs[k][0];
      ok &= (v >= r.lo && v <= r.hi) || (v != v && r.nan);
      continue;
    }
    for (size_t i = 0, e = row_from && k >= row_from ? 1 : n; i < e; ++i) ok &= std::fabs(inputs[k][i]) <= b;
  }
  return ok;
}

}  // namespace fscript::backends
