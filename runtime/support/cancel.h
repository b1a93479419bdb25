#pragma once
// Cancelling a run from another thread (fvrml-run --serve: a save, a new setting, --max-seconds,
// Ctrl-C). The meshers' evaluations ask before each batch, and the backends' loops and recursive
// calls ask as they run, so a run stops within one batch and one loop iteration.
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

// For generated code: the address of the word that holds the current flag's address. The word is
// never null (outside every scope it names a flag that is never set), so the check is two loads
// and a byte compare: `mov rax, [slot]; cmp byte [rax], 0`.
const void* cancel_slot();

// What an evaluation stopped by a cancel reports (nobody shows it: a cancelled run's output is dropped).
constexpr const char* kCancelledMessage = "the run was cancelled";

}  // namespace fscript::support
