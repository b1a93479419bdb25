#pragma once
// The one way work is spread over threads: run_parts(parts, task) runs task(0) .. task(parts - 1)
// at once, the caller's thread taking part 0, and waits for all. Each part is a fixed share of the
// work (chosen by the caller, never by timing), so what the parts compute is the same for any
// thread count and any schedule: the "same bytes for 1 and N threads" rule rests on that.
#include <algorithm>
#include <system_error>
#include <thread>
#include <vector>

namespace fscript::support {

// Whether every task(k) returned true. Every part runs to its end even when another fails. A part
// whose thread cannot start (the system's thread or memory limit) runs on the caller's thread
// after part 0: fewer threads, the same results.
template <class Task>
bool run_parts(int parts, Task task) {
  parts = std::max(1, parts);
  std::vector<char> ok(static_cast<size_t>(parts), 1);
  std::vector<std::thread> pool;
  int started = 1;
  for (; started < parts; ++started) {
    int k = started;
    try {
      pool.emplace_back([&, k] { ok[static_cast<size_t>(k)] = task(k); });
    } catch (const std::system_error&) {
      break;
    }
  }
  ok[0] = task(0);
  for (int k = started; k < parts; ++k) ok[static_cast<size_t>(k)] = task(k);
  for (auto& t : pool) t.join();
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
