// The run's cancel flag: a word holding the current flag's address, read by the evaluation threads
// before each batch and by generated code in its loops and recursive calls.
#include "runtime/support/cancel.h"

#include <cstdint>

namespace fscript::support {

namespace {
const std::atomic<bool> never{false};
std::atomic<const std::atomic<bool>*> current{&never};

// What generated code assumes of the two loads.
static_assert(sizeof(current) == sizeof(void*) && std::atomic<const std::atomic<bool>*>::is_always_lock_free);
static_assert(sizeof(never) == 1 && std::atomic<bool>::is_always_lock_free);
}  // namespace

CancelScope::CancelScope(const std::atomic<bool>& flag) { current.store(&flag); }

CancelScope::~CancelScope() { current.store(&never); }

bool run_cancelled() { return current.load(std::memory_order_acquire)->load(std::memory_order_relaxed); }

const void* cancel_slot() { return &current; }

}  // namespace fscript::support
