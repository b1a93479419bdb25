// A pthread with a large stack for the compiler's recursive descent.
#include "runtime/support/big_stack.h"

#include <pthread.h>

#include <exception>

namespace fscript::support {

namespace {
struct Job {
  const std::function<void()>* fn;
  std::exception_ptr error;
};
void* trampoline(void* arg) {
  auto* job = static_cast<Job*>(arg);
  try {
    (*job->fn)();
  } catch (...) {
    job->error = std::current_exception();  // rethrown on the calling thread
  }
  return nullptr;
}
}  // namespace

void run_with_big_stack(const std::function<void()>& fn, size_t stack_bytes) {
  pthread_attr_t attr;
  pthread_t thread;
  Job job{&fn, nullptr};
  if (pthread_attr_init(&attr) == 0 && pthread_attr_setstacksize(&attr, stack_bytes) == 0 &&
      pthread_create(&thread, &attr, trampoline, &job) == 0) {
    pthread_attr_destroy(&attr);
    pthread_join(thread, nullptr);
    if (job.error) std::rethrow_exception(job.error);
    return;
  }
  pthread_attr_destroy(&attr);
  fn();
}

void set_default_thread_stack(size_t bytes) {
#if defined(__EMSCRIPTEN__)
  (void)bytes;  // no threads in the browser build: its one stack is sized at link time (TOTAL_STACK)
  return;
#endif
  pthread_attr_t attr;
  if (pthread_attr_init(&attr) != 0) return;
  if (pthread_attr_setstacksize(&attr, bytes) == 0) pthread_setattr_default_np(&attr);
  pthread_attr_destroy(&attr);
}

}  // namespace fscript::support
