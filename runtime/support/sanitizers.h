#pragma once
// Which sanitizers this code is built with, for the few places that must behave differently under
// them: FS_ASAN (AddressSanitizer: its shadow memory counts against a memory limit) and
// FS_FOREIGN_MALLOC (a sanitizer's own allocator replaces glibc's: ASan, TSan, MSan).
#if defined(__SANITIZE_ADDRESS__)
#define FS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FS_ASAN 1
#endif
#endif

#if defined(FS_ASAN) || defined(__SANITIZE_THREAD__)
#define FS_FOREIGN_MALLOC 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define FS_FOREIGN_MALLOC 1
#endif
#endif

namespace fscript::support {

#ifdef FS_FOREIGN_MALLOC
constexpr bool kForeignMalloc = true;
#else
constexpr bool kForeignMalloc = false;
#endif

}  // namespace fscript::support
