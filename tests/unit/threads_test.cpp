// Threads (runtime/support/parallel.h, big_stack.h): workers get the stack size the tools give
// them, not the stack limit; parts whose thread cannot start run on the caller's thread, with the
// same results.
#include <catch2/catch.hpp>
#include <pthread.h>
#include <sys/resource.h>

#include <atomic>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "runtime/support/big_stack.h"
#include "runtime/support/parallel.h"
#include "runtime/support/sanitizers.h"

using namespace fscript;

namespace {

size_t stack_of_new_thread() {
  size_t size = 0;
  std::thread([&] {
    pthread_attr_t attr;
    if (pthread_getattr_np(pthread_self(), &attr) == 0) {
      pthread_attr_getstacksize(&attr, &size);
      pthread_attr_destroy(&attr);
    }
  }).join();
  return size;
}

}  // namespace

TEST_CASE("a thread made after set_default_thread_stack has that stack, whatever ulimit -s says") {
  support::set_default_thread_stack(size_t{6} << 20);
  CHECK(stack_of_new_thread() == (size_t{6} << 20));
  support::set_default_thread_stack();
  CHECK(stack_of_new_thread() == support::kWorkerStackBytes);
}

TEST_CASE("run_parts runs the parts whose thread cannot start on the caller's thread") {
  if (support::kForeignMalloc) return;  // a sanitizer's allocator under a data limit: not this test's subject
  // Threads of a gibibyte of stack under a data limit of 256 MiB more than now: none can start.
  rlimit before{};
  REQUIRE(getrlimit(RLIMIT_DATA, &before) == 0);
  support::set_default_thread_stack(size_t{1} << 30);
  rlimit tight = before;
  std::ifstream status("/proc/self/status");
  tight.rlim_cur = RLIM_INFINITY;
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmData:", 0) == 0) tight.rlim_cur = (std::stoull(line.substr(7)) << 10) + (rlim_t{256} << 20);
  REQUIRE(setrlimit(RLIMIT_DATA, &tight) == 0);
  std::vector<int> done(8, 0);
  std::atomic<int> calls{0};
  bool ok = support::run_parts(8, [&](int k) { return ++calls, done[static_cast<size_t>(k)] = k + 1, true; });
  setrlimit(RLIMIT_DATA, &before);
  support::set_default_thread_stack();
  CHECK(ok);
  CHECK(calls == 8);
  for (int k = 0; k < 8; ++k) CHECK(done[static_cast<size_t>(k)] == k + 1);
}
