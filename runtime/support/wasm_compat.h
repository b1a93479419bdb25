#pragma once
// Included first in every source of the browser build (CMakeLists.txt, FS_WASM): what the C++20
// library of Debian's Emscripten (3.1.6, libc++ of LLVM 14) lacks and the sources use.
#include <version>

#if !defined(__cpp_lib_bit_cast)
namespace std {
template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
  return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif
