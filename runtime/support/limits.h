#pragma once
// Run-wide limits for untrusted scenes and scripts: wall-clock time (--max-seconds) and memory
// (--max-memory). Both end the whole process with one clear error and exit status 1.
#include <cstdint>
#include <string>

namespace fscript::support {

// After `seconds` (> 0), from a watchdog thread: prints "TOOL: error: the run took longer than S s
// (--max-seconds S); stopped", deletes the temporary files of writes in progress and exits 1.
// False when its thread cannot start (the run would have no time limit).
bool start_watchdog(const char* tool, double seconds);

// Caps the data the process adds from now on (RLIMIT_DATA over today's VmData) at `mib` MiB and installs a new-handler: an allocation past the cap
// prints "TOOL: error: the run needs more than N MiB of memory (--max-memory N); stopped" and
// exits 1, in whatever thread it happens. False (with `error`) when the limit cannot be set.
// Under AddressSanitizer, whose shadow memory counts against the limit, it does nothing.
bool limit_memory(const char* tool, uint64_t mib, std::string& error);

// The default for --max-memory: three quarters of this machine's physical memory.
uint64_t default_memory_limit_mib();

}  // namespace fscript::support
