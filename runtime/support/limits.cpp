// The watchdog and the memory cap of runtime/support/limits.h: both stop the run with _exit, since
// a limit may strike in any worker thread, deep in a JIT-compiled kernel or in an allocation.
#include "runtime/support/limits.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>
#include <system_error>
#include <thread>

#include <sys/resource.h>
#include <unistd.h>

#include "runtime/support/files.h"
#include "runtime/support/sanitizers.h"

namespace fscript::support {
namespace {

// Set once before any worker starts; read by the new-handler, which must not allocate.
char g_memory_message[256];

[[noreturn]] void stop(const char* message) {
  remove_pending_writes();
  ssize_t ignored = ::write(STDERR_FILENO, message, std::strlen(message));
  (void)ignored;
  ::_exit(1);
}

void out_of_memory() { stop(g_memory_message); }

// The process's data size now (VmData: heap, anonymous mappings, thread stacks), in bytes: the
// start-up baseline the cap is added to, so that it counts what the run itself asks for (the
// tools reserve a 1 GiB stack for deep nesting, which costs nothing until touched).
uint64_t data_bytes_now() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  unsigned long long kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "VmData: %llu kB", &kib) == 1) break;
  std::fclose(f);
  return static_cast<uint64_t>(kib) << 10;
}

}  // namespace

bool start_watchdog(const char* tool, double seconds) {
  if (!(seconds > 0)) return true;
  char message[256];
  std::snprintf(message, sizeof message, "%s: error: the run took longer than %g s (--max-seconds %g); stopped\n", tool,
                seconds, seconds);
  try {
    std::thread([seconds, text = std::string(message)] {
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
      stop(text.c_str());
    }).detach();
  } catch (const std::system_error&) {
    return false;
  }
  return true;
}

bool limit_memory(const char* tool, uint64_t mib, std::string& error) {
#ifdef FS_ASAN
  if (mib > 0) return true;  // AddressSanitizer's shadow memory would count against the limit
#endif
  std::snprintf(g_memory_message, sizeof g_memory_message,
                "%s: error: the run needs more than %llu MiB of memory (--max-memory %llu); stopped\n", tool,
                static_cast<unsigned long long>(mib), static_cast<unsigned long long>(mib));
  rlimit r{};
  if (getrlimit(RLIMIT_DATA, &r) != 0) {
    error = std::strerror(errno);
    return false;
  }
  rlim_t want = static_cast<rlim_t>(data_bytes_now() + (mib << 20));
  if (r.rlim_max != RLIM_INFINITY && want > r.rlim_max) want = r.rlim_max;  // never above the hard limit
  r.rlim_cur = want;
  if (setrlimit(RLIMIT_DATA, &r) != 0) {
    error = std::strerror(errno);
    return false;
  }
  std::set_new_handler(out_of_memory);
  return true;
}

uint64_t default_memory_limit_mib() {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 16384;
  return static_cast<uint64_t>(pages) / 4 * 3 * static_cast<uint64_t>(page) >> 20;
}

}  // namespace fscript::support
