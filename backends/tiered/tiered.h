#pragma once
// The "auto" backend: tiered execution. A kernel starts on the VM at once (no compile time); when
// the VM has spent a share of what compiling would cost (or a caller says a big job is ahead), the
// same module is compiled natively (LLVM, else the SSE emitter) on a background thread, and every
// batch after it is ready runs native. The backends agree bit for bit (docs/language.md), so the
// results do not depend on which tier ran which batch.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "backends/backend.h"

namespace fscript::backends {

// What tiered kernels did in this process, summed (fvrml-run and fscript --stats).
struct TierStats {
  uint64_t kernels = 0;     // tiered kernels made
  uint64_t compiles = 0;    // native compiles started
  uint64_t cached = 0;      // kernels native from their first batch: the code was in a cache
  uint64_t switched = 0;    // kernels whose native code arrived and was used
  uint64_t failed = 0;      // native compiles that failed (the VM went on)
  uint64_t vm_points = 0, native_points = 0;
  double first_switch_ms = -1;  // after the first tiered kernel was made; -1: never
  std::string native;           // the native backend's name
};
TierStats tier_stats();

// The estimated time to compile a module of `ops` operations natively, in nanoseconds (measured:
// docs/performance.md, "Decisions": `auto`).
double native_compile_ns(size_t ops);

class TieredBackend : public Backend {
 public:
  std::string name() const override { return "auto"; }
  std::unique_ptr<Kernel> compile(const ir::Module& m, const Budgets& budgets, std::string& error) const override;
};

}  // namespace fscript::backends
