// Threads (runtime/support/parallel.h, big_stack.h): workers get the stack size the tools give
// them, not the stack limit; parts whose thread cannot start run on the caller's thread, with the
// same results.
#include <catch2/catch.hpp>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

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

namespace {

// The stack size of the thread that runs part 1 of a run of two parts.
size_t stack_of_part_one() {
  size_t size = 0;
  support::run_parts(2, [&](int k) {
    pthread_attr_t attr;
    if (k == 1 && pthread_getattr_np(pthread_self(), &attr) == 0) {
      pthread_attr_getstacksize(&attr, &size);
      pthread_attr_destroy(&attr);
    }
    return true;
  });
  return size;
}

}  // namespace

TEST_CASE("run_parts keeps its threads for the next call, and runs every part at once") {
  std::thread::id first, second;
  support::run_parts(2, [&](int k) { return k == 1 ? (first = std::this_thread::get_id(), true) : true; });
  support::run_parts(2, [&](int k) { return k == 1 ? (second = std::this_thread::get_id(), true) : true; });
  CHECK(first != std::this_thread::get_id());
  CHECK(first == second);
  // Parts that wait for each other finish only if each has a thread of its own.
  std::atomic<int> arrived{0};
  bool ok = support::run_parts(4, [&](int) {
    ++arrived;
    while (arrived < 4) std::this_thread::yield();
    return true;
  });
  CHECK(ok);
}

TEST_CASE("a kept thread made under another stack size is not reused") {
  support::set_default_thread_stack(size_t{16} << 20);
  CHECK(stack_of_part_one() == (size_t{16} << 20));
  support::set_default_thread_stack();
  CHECK(stack_of_part_one() == support::kWorkerStackBytes);
}

TEST_CASE("a forked child runs parts on threads of its own") {
  support::run_parts(3, [](int) { return true; });  // the parent has kept threads
  pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    alarm(20);  // a child waiting on the parent's threads (which it does not have) dies here
    std::atomic<int> ran{0};
    bool ok = support::run_parts(3, [&](int) { return ++ran, true; });
    _exit(ok && ran == 3 ? 0 : 1);
  }
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
}
