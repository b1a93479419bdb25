#pragma once
// The one way work is spread over threads: run_parts(parts, task) runs task(0) .. task(parts - 1)
// at once, the caller's thread taking part 0, and waits for all. Each part is a fixed share of the
// work (chosen by the caller, never by timing), so what the parts compute is the same for any
// thread count and any schedule: the "same bytes for 1 and N threads" rule rests on that.
#include <algorithm>
#include <functional>
#include <latch>
#include <vector>

namespace fscript::support {

// Starts `work` on a thread of its own, one of a pool kept for the process (a thread made for
// every call cost a picture of 5 ms a tenth of a millisecond per call before its work started,
// twice a picture), and when `work` returns counts `done` down. False when no thread is free and
// none can be started (the system's thread or memory limit): `work` is then not run.
bool start_pooled(std::function<void()> work, std::latch& done);

// Whether every task(k) returned true. Every part runs to its end even when another fails. A part
// whose thread cannot start runs on the caller's thread after part 0: fewer threads, the same
// results. Pooled threads have the stack set_default_thread_stack gave when they were made; one
// made under another size is not reused.
template <class Task>
bool run_parts(int parts, Task task) {
  parts = std::max(1, parts);
  std::vector<char> ok(static_cast<size_t>(parts), 1);
  std::latch done(parts - 1);
  int started = 1;
  for (; started < parts; ++started) {
    int k = started;
    if (!start_pooled([&, k] { ok[static_cast<size_t>(k)] = task(k); }, done)) break;
  }
  ok[0] = task(0);
  for (int k = started; k < parts; ++k) ok[static_cast<size_t>(k)] = task(k), done.count_down();
  done.wait();
  return std::all_of(ok.begin(), ok.end(), [](char v) { return v != 0; });
}

// The same with an error per part, task(k, error): on failure `error` is the failing part with the
// lowest k (the same error whatever the timing).
template <class Error, class Task>
bool run_parts(int parts, Task task, Error& error) {
  parts = std::max(1, parts);
  std::vector<Error> errors(static_cast<size_t>(parts));
  std::vector<char> ok(static_cast<size_t>(parts), 1);
  run_parts(parts, [&](int k) { return ok[static_cast<size_t>(k)] = task(k, errors[static_cast<size_t>(k)]); });
  for (int k = 0; k < parts; ++k)
    if (!ok[static_cast<size_t>(k)]) {
      error = errors[static_cast<size_t>(k)];
      return false;
    }
  return true;
}

}  // namespace fscript::support
