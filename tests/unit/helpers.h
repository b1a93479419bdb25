#pragma once
// Small helpers shared by the unit tests: compile a script text, evaluate an entry.
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "backends/backend.h"
#include "engine/driver/driver.h"
#include "runtime/support/cancel.h"

namespace fscript::test {

struct Built {
  frontend::DiagnosticSink diag;
  frontend::Script script;
  std::unique_ptr<ir::Module> module;
  std::unique_ptr<backends::Kernel> kernel;
  bool ok = false;
};

// Compiles `text` for `entry` ("" = the script's entry point) on backend `be`.
inline std::unique_ptr<Built> build(const std::string& text, const std::string& entry = "", bool optimize = true,
                                    const backends::Budgets& budgets = {}, const std::string& be = "vm") {
  auto b = std::make_unique<Built>();
  driver::CompileOptions o;
  o.backend = be;
  o.budgets = budgets;
  o.build.optimize = optimize;
  o.build.verify_each = true;
  driver::Compiled c;
  b->ok = driver::compile(std::make_unique<frontend::SourceFile>("test.fs", text), driver::named_entry(entry), o,
                          b->diag, c)
              .ok();
  b->script = std::move(c.script);
  b->module = std::move(c.module);
  b->kernel = std::move(c.kernel);
  return b;
}

inline float eval1(const Built& b, std::vector<float> in) {
  in.resize(b.kernel->num_inputs(), 0.0f);
  std::vector<float> out(b.kernel->num_outputs());
  backends::RuntimeError err;
  if (!b.kernel->eval(in.data(), out.data(), err)) return -12345.0f;
  return out[0];
}

inline std::string messages(const frontend::DiagnosticSink& d) { return frontend::render_all(d); }

// Runs `fn` on a thread with exactly `stack_bytes` of stack (whatever `ulimit -s` says), so tests of
// deep recursion see the same stack on every machine.
template <typename Fn>
void on_thread_with_stack(size_t stack_bytes, Fn fn) {
  pthread_attr_t attr;
  pthread_t thread;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, stack_bytes);
  auto run = [](void* p) -> void* {
    (*static_cast<Fn*>(p))();
    return nullptr;
  };
  if (pthread_create(&thread, &attr, run, &fn) != 0) throw std::runtime_error("cannot start a thread");
  pthread_attr_destroy(&attr);
  pthread_join(thread, nullptr);
}

// The process's run cancelled by another thread `ms` milliseconds from now, as fvrml-run --serve
// does on a save: a CancelScope for this object's life, the thread joined at its end.
class CancelAfter {
 public:
  explicit CancelAfter(int ms)
      : scope_(flag_), thread_([this, ms] {
          std::this_thread::sleep_for(std::chrono::milliseconds(ms));
          flag_ = true;
        }) {}
  ~CancelAfter() { thread_.join(); }
  CancelAfter(const CancelAfter&) = delete;
  CancelAfter& operator=(const CancelAfter&) = delete;

 private:
  std::atomic<bool> flag_{false};
  support::CancelScope scope_;
  std::thread thread_;
};

}  // namespace fscript::test
