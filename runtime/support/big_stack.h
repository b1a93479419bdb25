#pragma once
// Runs work on a thread with a large stack, so deeply nested (but accepted) input never overflows
// the native stack in the recursive parts of the compiler.
#include <cstddef>
#include <functional>

namespace fscript::support {

constexpr size_t kBigStackBytes = size_t{1} << 30;  // reserved, committed only as touched

// Runs `fn` to completion on a fresh thread with `stack_bytes` of stack; falls back to calling it
// directly if such a thread cannot be created. An exception `fn` throws is rethrown here.
void run_with_big_stack(const std::function<void()>& fn, size_t stack_bytes = kBigStackBytes);

}  // namespace fscript::support
