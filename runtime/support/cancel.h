#pragma once
// Cancelling a run from another thread (fvrml-run --serve: a save, a new setting, --max-seconds,
// Ctrl-C). The meshers' evaluations ask before each batch, so a run stops within one batch.
#include <atomic>

namespace fscript::support {

// While a CancelScope lives, `flag` set means the process's run is cancelled. One run at a time
// (like the run's progress): scopes do not nest.
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>& flag);
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;
};

// Whether the run in a CancelScope has been cancelled (false outside every scope).
bool run_cancelled();

// What an evaluation stopped by a cancel reports (nobody shows it: a cancelled run's output is dropped).
constexpr const char* kCancelledMessage = "the run was cancelled";

}  // namespace fscript::support
