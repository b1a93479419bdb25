#pragma once
// What every fuzz target shares: how a finding is reported (the input and what broke, then abort,
// which libFuzzer records as a crash with the input saved), and bounded compile budgets.
#include <condition_variable>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "backends/backend.h"
#include "engine/driver/driver.h"
#include "tests/unit/backend_cases.h"
#include "runtime/support/big_stack.h"

namespace fscript::fuzz {

[[noreturn]] inline void finding(const std::string& what, const std::string& input) {
  std::fprintf(stderr, "==== fuzz finding: %s\n---- input ----\n%s\n---- end ----\n", what.c_str(), input.c_str());
  std::abort();
}

// Small enough that one execution stays in milliseconds, large enough to run every construct.
inline backends::Budgets small_budgets() {
  backends::Budgets b;
  b.max_loop_iterations = 20000;
  b.max_call_depth = 64;
  b.max_array_elements = 4096;
  return b;
}

// How the targets compile a program: the VM, the small budgets, every pass verified.
inline driver::CompileOptions compile_options(bool optimize) {
  driver::CompileOptions o;
  o.backend = "vm";
  o.budgets = small_budgets();
  o.build.optimize = optimize;
  o.build.verify_each = true;
  return o;
}

// The same bits, or both NaN (NaN payloads and signs are not defined by the language): the
// backend unit tests' rule.
using test::same;

// Runs `fn` on the one thread with a big stack that serves every input (as the tools run on one:
// deep but legal nesting must not overflow). A fresh 1 GiB-stack thread per input spent half the
// time of a small input in mmap and munmap. An exception escaping `fn` ends the process: a finding.
inline void run_deep(const std::function<void()>& fn) {
  struct Runner {
    std::mutex m;
    std::condition_variable cv;
    const std::function<void()>* job = nullptr;
    bool done = false;
    Runner() {
      std::thread([this] {
        support::run_with_big_stack([this] {
          for (;;) {
            std::unique_lock<std::mutex> lock(m);
            cv.wait(lock, [this] { return job != nullptr; });
            (*job)();
            job = nullptr;
            done = true;
            cv.notify_all();
          }
        });
      }).detach();
    }
  };
  static Runner* runner = new Runner;  // never destroyed: its thread serves until the process ends
  std::unique_lock<std::mutex> lock(runner->m);
  runner->job = &fn;
  runner->done = false;
  runner->cv.notify_all();
  runner->cv.wait(lock, [] { return runner->done; });
}

}  // namespace fscript::fuzz
