// A pthread with a large stack for the compiler's recursive descent.
#include "frontend/big_stack.h"

#include <pthread.h>

namespace fscript::frontend {

static void* trampoline(void* arg) {
  (*static_cast<const std::function<void()>*>(arg))();
  return nullptr;
}

void run_with_big_stack(const std::function<void()>& fn, size_t stack_bytes) {
  pthread_attr_t attr;
  pthread_t thread;
  if (pthread_attr_init(&attr) == 0 && pthread_attr_setstacksize(&attr, stack_bytes) == 0 &&
      pthread_create(&thread, &attr, trampoline, const_cast<std::function<void()>*>(&fn)) == 0) {
    pthread_attr_destroy(&attr);
    pthread_join(thread, nullptr);
    return;
  }
  pthread_attr_destroy(&attr);
  fn();
}

}  // namespace fscript::frontend
