#pragma once
// Runs work on a thread with a large stack, so deeply nested (but accepted) input never overflows
// the native stack in the recursive parts of the compiler.
#include <cstddef>
#include <functional>

namespace fscript::support {

constexpr size_t kBigStackBytes = size_t{1} << 30;  // reserved, committed only as touched

constexpr size_t kWorkerStackBytes = size_t{8} << 20;  // Linux's usual stack limit

// Runs `fn` to completion on a fresh thread with `stack_bytes` of stack; falls back to calling it
// directly if such a thread cannot be created. An exception `fn` throws is rethrown here.
void run_with_big_stack(const std::function<void()>& fn, size_t stack_bytes = kBigStackBytes);

// Gives every thread made later without a size of its own (std::thread: the workers, the
// background compiler) `bytes` of stack. glibc otherwise takes the stack limit (ulimit -s) as
// their size: under `ulimit -s 1048576` each worker reserved a gibibyte and --max-memory made the
// second one fail. Call before any thread starts.
void set_default_thread_stack(size_t bytes = kWorkerStackBytes);

}  // namespace fscript::support
