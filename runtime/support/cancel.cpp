// The run's cancel flag: a pointer the evaluation threads read before each batch.
#include "runtime/support/cancel.h"

namespace fscript::support {

namespace {
std::atomic<const std::atomic<bool>*> current{nullptr};
}  // namespace

CancelScope::CancelScope(const std::atomic<bool>& flag) { current.store(&flag); }

CancelScope::~CancelScope() { current.store(nullptr); }

bool run_cancelled() {
  const std::atomic<bool>* flag = current.load(std::memory_order_acquire);
  return flag && flag->load(std::memory_order_relaxed);
}

}  // namespace fscript::support
