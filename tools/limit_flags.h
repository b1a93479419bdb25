#pragma once
// The run-wide limits every tool that runs scripts takes (fscript, fvrml-run): --max-seconds and
// --max-memory, one wording, one range (runtime/support/limits.h does the work).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>

#include "runtime/support/huge_heap.h"
#include "runtime/support/limits.h"

namespace fscript::tools {

struct RunLimits {
  double max_seconds = 0;       // 0: none
  uint64_t max_memory_mib = 0;  // 0: support::default_memory_limit_mib()
};

inline void add_limit_flags(CLI::App& app, RunLimits& limits, const char* seconds_default = "none") {
  app.add_option("--max-seconds", limits.max_seconds,
                 std::string("stop a run that takes longer than S seconds, with an error and exit status 1 (default ") +
                     seconds_default + ")")
      ->check(CLI::Range(0.0, 1e7).description(""))
      ->type_name("S");
  app.add_option("--max-memory", limits.max_memory_mib,
                 "stop a run that needs more than N MiB of memory, with an error and exit status 1, at least 64 "
                 "(default: three quarters of this machine's memory)")
      ->check(CLI::Range(uint64_t{64}, uint64_t{1} << 40).description(""))
      ->type_name("N");
}

// Puts the limits in force for the rest of the process, then reserves the huge heap within them
// (runtime/support/huge_heap.h); false (after an error message) if the
// memory limit cannot be set.
inline bool apply_limits(const char* tool, const RunLimits& limits, bool watchdog = true) {
  std::string error;
  uint64_t mib = limits.max_memory_mib ? limits.max_memory_mib : support::default_memory_limit_mib();
  if (!support::limit_memory(tool, mib, error)) {
    std::cerr << tool << ": error: cannot limit memory to " << mib << " MiB: " << error << "\n";
    return false;
  }
  if (watchdog && !support::start_watchdog(tool, limits.max_seconds)) {
    std::cerr << tool << ": error: --max-seconds: the system gave no thread to keep the time\n";
    return false;
  }
  // Inside the cap, so the cap still bounds the run: a quarter of it, at most 1 GiB.
  support::reserve_huge_heap(std::min<uint64_t>(uint64_t{1} << 30, (mib << 20) / 4));
  return true;
}

}  // namespace fscript::tools
