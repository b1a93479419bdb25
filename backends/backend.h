#pragma once
// The one evaluation interface. Every backend compiles a module's kernel function to a Kernel
// that evaluates batches of points in structure-of-arrays form (inputs[k][i] -> outputs[k][i]),
// plus a one-point call. Polygonizers, render2d, eval and bench only ever see Kernels.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ir/ir.h"

namespace fscript::backends {

// Limits that keep an untrusted script from hanging or exhausting the host (language spec).
struct Budgets {
  uint64_t max_loop_iterations = 10'000'000;  // per evaluation (one point)
  uint32_t max_call_depth = 1000;             // nested user-function calls
  uint64_t max_array_elements = 1'000'000;    // per evaluation, all arrays together
};
// The largest depth a user may ask for. The browser build runs on the browser's stack (about
// 1 MiB, not ours to size; docs/browser.md), which holds about a thousand of the VM's nested calls.
#ifdef __EMSCRIPTEN__
constexpr uint32_t kCallDepthCeiling = 1'000;
constexpr const char* kCallDepthCeilingText = "1,000";
#else
constexpr uint32_t kCallDepthCeiling = 100'000;
constexpr const char* kCallDepthCeilingText = "100,000";
#endif

struct RuntimeError {
  std::string message;
  uint32_t line = 0;  // source line and column of the loop, call or array access (0: unknown)
  uint32_t col = 0;
};

// The name a user wrote for an array slot: lowering numbers each declaration ("a.0") and inlining
// prefixes the callee ("FRep.a.0"); messages show "a".
inline std::string array_display_name(const std::string& slot) {
  std::string s = slot;
  size_t dot = s.rfind('.');
  if (dot != std::string::npos && dot + 1 < s.size() && s.find_first_not_of("0123456789", dot + 1) == std::string::npos)
    s.erase(dot);
  dot = s.rfind('.');
  return dot == std::string::npos ? s : s.substr(dot + 1);
}

class Kernel {
 public:
  virtual ~Kernel() = default;
  virtual size_t num_inputs() const = 0;
  virtual size_t num_outputs() const = 0;
  // Evaluates n points. Returns false on a runtime error (budget, bounds), described in `err`.
  // Safe to call from several threads at once.
  virtual bool eval_batch(const float* const* inputs, float* const* outputs, size_t n, RuntimeError& err) const = 0;
  // One point; the same results as a batch of one.
  virtual bool eval(const float* inputs, float* outputs, RuntimeError& err) const = 0;
  // Rows of a grid: row r is the points (first[i], rest[0][r], rest[1][r], ...) for i < count, and
  // its results go to outputs[o][r * count + i]. The same results as eval_batch over those points;
  // kernels with a row split (backends/row_split_kernel.h) compute what does not depend on the first
  // input once per row.
  virtual bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                         RuntimeError& err) const;
  // A caller that knows its job says `points` evaluations are ahead: a tiered kernel compiles
  // natively at once when that pays; others ignore it.
  virtual void expect_points(uint64_t points) const { (void)points; }
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  // Compiles the module's kernel function (the one flagged `kernel`). On failure returns nullptr
  // with a message (an environment failure: the module is assumed verified).
  virtual std::unique_ptr<Kernel> compile(const ir::Module& m, const Budgets& budgets, std::string& error) const = 0;
};

// Backends built into this binary that a user may force, the VM first. "auto" (tiered execution)
// is not among them: it runs them.
std::vector<std::string> available_backends();
// The backend used when none is named: "auto".
std::string default_backend();
// nullptr if `name` is unknown or not built.
std::unique_ptr<Backend> make_backend(const std::string& name);
// Why make_backend(name) gave nullptr, for the user.
std::string missing_backend_message(const std::string& name);
// Turns on the llvm backend's on-disk cache of compiled code (the user's cache directory).
// Returns false with a message when this binary has no llvm backend or no cache directory.
bool enable_llvm_disk_cache(std::string& message);
// Whether the native backend of tiered execution can load this kernel's machine code without
// compiling it (the llvm backend's in-memory or on-disk cache has it).
bool native_code_cached(const ir::Module& m, const Budgets& budgets);

}  // namespace fscript::backends
