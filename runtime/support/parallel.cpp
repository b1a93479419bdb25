// The threads run_parts starts its parts on (parallel.h): kept idle between calls, each waiting on
// its own condition for its next part; one made under another default stack size is retired, and
// a fork's child starts with none.
#include "runtime/support/parallel.h"

#include <pthread.h>

#include <condition_variable>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

namespace fscript::support {
namespace {

// The stack a thread made now gets (set_default_thread_stack), 0 where that cannot be read.
size_t default_stack() {
  size_t size = 0;
#if defined(__GLIBC__)
  pthread_attr_t attr;
  if (pthread_getattr_default_np(&attr) == 0) {
    pthread_attr_getstacksize(&attr, &size);
    pthread_attr_destroy(&attr);
  }
#endif
  return size;
}

struct Worker {
  std::mutex m;
  std::condition_variable wake;
  std::function<void()> work;  // set: a part to run; empty with `stop`: end
  std::latch* done = nullptr;
  bool stop = false;
  size_t stack = 0;
  std::thread thread;
};

class Pool {
 public:
  Pool() {
    pthread_atfork([] { pool().m_.lock(); }, [] { pool().m_.unlock(); }, [] { pool().after_fork(); });
  }

  // Never destroyed: a thread still in a part when the process exits must not find the pool gone.
  static Pool& pool() {
    static Pool* p = new Pool;
    return *p;
  }

  bool start(std::function<void()>& work, std::latch& done) {
    Worker* w = take();
    if (!w) return false;
    {
      std::lock_guard<std::mutex> lock(w->m);
      w->work = std::move(work), w->done = &done;
    }
    w->wake.notify_one();
    return true;
  }

 private:
  // An idle worker of the current stack size, or a new one; retires idle ones of another size.
  Worker* take() {
    const size_t stack = default_stack();
    std::vector<std::unique_ptr<Worker>> retired;
    Worker* found = nullptr;
    {
      std::lock_guard<std::mutex> lock(m_);
      while (!idle_.empty() && !found) {
        Worker* w = idle_.back();
        idle_.pop_back();
        if (w->stack == stack) found = w;
        else retired.push_back(remove(w));
      }
    }
    for (auto& w : retired) end(*w);
    return found ? found : make(stack);
  }

  Worker* make(size_t stack) {
    auto w = std::make_unique<Worker>();
    w->stack = stack;
    try {
      w->thread = std::thread([this, p = w.get()] { run(*p); });
    } catch (const std::system_error&) {
      return nullptr;
    }
    std::lock_guard<std::mutex> lock(m_);
    all_.push_back(std::move(w));
    return all_.back().get();
  }

  void run(Worker& w) {
    for (;;) {
      std::function<void()> work;
      std::latch* done;
      {
        std::unique_lock<std::mutex> lock(w.m);
        w.wake.wait(lock, [&] { return w.work || w.stop; });
        if (!w.work) return;
        work = std::move(w.work), done = w.done;
        w.work = nullptr;
      }
      work();
      {  // idle again before the caller hears of it: its next call finds this thread, not a new one
        std::lock_guard<std::mutex> lock(m_);
        idle_.push_back(&w);
      }
      done->count_down();
    }
  }

  std::unique_ptr<Worker> remove(Worker* w) {
    for (auto& p : all_)
      if (p.get() == w) {
        auto out = std::move(p);
        p = std::move(all_.back());
        all_.pop_back();
        return out;
      }
    return nullptr;
  }

  static void end(Worker& w) {
    {
      std::lock_guard<std::mutex> lock(w.m);
      w.stop = true;
    }
    w.wake.notify_one();
    w.thread.join();
  }

  // The child of a fork has none of the parent's threads: their records are dropped unread (their
  // std::thread must not be joined or destroyed there).
  void after_fork() {
    m_.unlock();
    for (auto& w : all_) (void)w.release();
    all_.clear();
    idle_.clear();
  }

  std::mutex m_;
  std::vector<std::unique_ptr<Worker>> all_;
  std::vector<Worker*> idle_;
};

}  // namespace

bool start_pooled(std::function<void()> work, std::latch& done) { return Pool::pool().start(work, done); }

}  // namespace fscript::support
