// Tiered execution (backends/tiered/tiered.h): the VM at once, native code from a background
// compile once the work done says it pays.
#include "backends/tiered/tiered.h"

#include "backends/llvm_module.h"

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <vector>
#include <algorithm>
#include <mutex>
#include <system_error>
#include <thread>

#include "ir/ir.h"

namespace fscript::backends {
namespace {

using Clock = std::chrono::steady_clock;

// The VM starts the native compile once it has spent this share of the compile's estimated time
// (the ski-rental rule): a job that ends sooner never waits for a compile, and one that goes on
// pays at most about twice what it would had it known its size. A smaller share switched sooner
// but made small scenes wait at their end for compiles they did not need (figure 2: +30 ms).
constexpr double kStartShare = 1.0;
constexpr double kVmNsPerOpPoint = 0.5;  // before the kernel has timed itself
constexpr size_t kChunk = 16384;         // points per VM call: timed, and a chance to switch
// A kernel whose LLVM code is estimated further off than this (its compile, and the module's load
// on a process's first compile) gets the SSE emitter's code first (about 1 ms per 1,000
// operations) to run while LLVM works: prospero's dense picture, 0.4 s of LLVM compile, would
// otherwise spend it on the VM (docs/performance.md, "Decisions": `auto`).
constexpr double kMiddleTierNs = 50e6;

// An SSE compile of `ops` operations (the middle tier, or the native code without LLVM).
double sse_compile_ns(size_t ops) { return 0.2e6 + 1e3 * static_cast<double>(ops); }

// The wait for a kernel's first native code: the middle tier's compile where LLVM's is that far off.
double first_native_ns(size_t ops) {
  double native = native_compile_ns(ops);
  return native > kMiddleTierNs ? sse_compile_ns(ops) : native;
}

// LLVM when its module loads (the first call loads it: from the compile thread, off the job's
// path), else the SSE emitter.
std::string native_backend() {
#if defined(FS_HAVE_WASM)
  return "wasm";  // the browser build: our WebAssembly emitter
#else
  return llvm_module() ? "llvm" : "sse";
#endif
}

// FSCRIPT_AUTO_SWITCH_AFTER=N (tests): compile at once, and run every batch after the N-th point
// natively, waiting for the compile if need be: a switch in the middle of a job, on purpose.
uint64_t forced_switch() {
  const char* v = std::getenv("FSCRIPT_AUTO_SWITCH_AFTER");
  return v && *v ? std::strtoull(v, nullptr, 10) : 0;
}

struct Totals {
  std::atomic<uint64_t> kernels{0}, compiles{0}, cached{0}, switched{0}, failed{0}, vm_points{0}, native_points{0};
  std::atomic<int64_t> first_switch_ns{-1};
  std::atomic<int64_t> start_ns{-1};
};
Totals& totals() {
  static Totals t;
  return t;
}
int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

// One tiered kernel's state, shared with the compile thread.
struct Shared {
  std::unique_ptr<ir::Module> module;
  Budgets budgets;
  size_t ops = 0;
  std::unique_ptr<Kernel> middle, native;  // written by the compile thread before `ready`
  std::atomic<const Kernel*> ready{nullptr};
  std::atomic<bool> started{false}, abandoned{false};
  std::mutex lock;  // with `done`: the end of the compile, for a kernel that waits for it
  std::condition_variable done_cv;
  bool done = false, running = false;
  std::atomic<uint64_t> vm_ns{0}, vm_points{0};
  std::atomic<uint64_t> announced{0};  // the points the caller said the job has (0: unknown)
  double vm_ns_per_point() const {
    uint64_t p = vm_points.load();
    return p >= 1024 ? double(vm_ns.load()) / double(p) : double(ops) * kVmNsPerOpPoint;
  }
  // With the middle tier running, whether the announced job ends before LLVM's code could arrive
  // (the SSE code taken as twice the VM's speed on such big kernels: prospero 428 against 760 ms).
  bool ends_before_native() const {
    uint64_t ahead = announced.load(), done = vm_points.load();
    return ahead > done && double(ahead - done) * vm_ns_per_point() * 0.5 < native_compile_ns(ops);
  }
};

// The one background compile thread: compiles run one at a time (the VM keeps the other cores),
// in the order asked.
class Compiler {
 public:
  void submit(std::shared_ptr<Shared> s) {
    std::lock_guard<std::mutex> hold(lock_);
    if (!thread_.joinable()) {
      try {
        thread_ = std::thread([this] { loop(); });
      } catch (const std::system_error&) {
        // No thread to be had (the browser build has none): the compile runs here, on the caller's
        // thread, once the work done says it pays, and its code takes the rest of the job.
        {
          std::lock_guard<std::mutex> run(s->lock);
          s->running = true;
        }
        compile(*s);
        return;
      }
    }
    queue_.push_back(std::move(s));
    wake_.notify_one();
  }
  ~Compiler() {
    {
      std::lock_guard<std::mutex> hold(lock_);
      stop_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void loop() {
    for (;;) {
      std::shared_ptr<Shared> s;
      {
        std::unique_lock<std::mutex> hold(lock_);
        wake_.wait(hold, [&] { return stop_ || !queue_.empty(); });
        if (stop_) return;
        s = std::move(queue_.front());
        queue_.pop_front();
      }
      {
        std::lock_guard<std::mutex> hold(s->lock);
        if (s->abandoned) {  // the kernel went away before its turn
          s->done = true;
          s->done_cv.notify_all();
          continue;
        }
        s->running = true;
      }
      compile(*s);
    }
  }

  static void compile(Shared& s) {
    std::string error;
    // Decided before the module loads, since loading it is part of the wait.
    if (native_compile_ns(s.ops) > kMiddleTierNs) {
      auto sse = make_backend("sse");  // (none in the browser build)
      if (auto m = sse ? sse->compile(*s.module, s.budgets, error) : nullptr) {
        std::lock_guard<std::mutex> hold(s.lock);
        s.middle = std::move(m);
        s.ready.store(s.middle.get(), std::memory_order_release);
      }
    }
    std::unique_ptr<Kernel> k;
    // The kernel went away while the middle tier compiled, or its job ends before LLVM's code could
    // arrive (the module's load counted), or the middle tier is the native code (no module): no
    // LLVM (a compile or a load under way cannot be stopped, and the kernel's end waits for it).
    auto finish = [&] {
      std::lock_guard<std::mutex> hold(s.lock);
      s.done = true, s.running = false;
      s.done_cv.notify_all();
    };
    if (s.abandoned || (s.middle && s.ends_before_native())) return finish();
    std::string native = native_backend();  // loads the module on the first compile
    if (s.middle && native == "sse") return finish();
    if (auto be = make_backend(native)) k = be->compile(*s.module, s.budgets, error);
    std::lock_guard<std::mutex> hold(s.lock);
    if (k) {
      s.native = std::move(k);
      s.ready.store(s.native.get(), std::memory_order_release);
    } else {
      ++totals().failed;
    }
    s.done = true, s.running = false;
    s.done_cv.notify_all();
  }

  std::mutex lock_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Shared>> queue_;
  std::thread thread_;
  bool stop_ = false;
};

Compiler& compiler() {
  static Compiler c;
  return c;
}

class TieredKernel : public Kernel {
 public:
  TieredKernel(std::unique_ptr<Kernel> vm, std::shared_ptr<Shared> s) : vm_(std::move(vm)), s_(std::move(s)) {
    ++totals().kernels;
    int64_t expected = -1;
    totals().start_ns.compare_exchange_strong(expected, now_ns());
    if (force_after_) start();
  }
  // A compile under way for this kernel is waited for (it uses the module); one still queued is
  // dropped.
  ~TieredKernel() override {
    std::unique_lock<std::mutex> hold(s_->lock);
    s_->abandoned = true;
    s_->done_cv.wait(hold, [&] { return !s_->running; });
  }

  size_t num_inputs() const override { return vm_->num_inputs(); }
  size_t num_outputs() const override { return vm_->num_outputs(); }

  // On the VM a batch goes in chunks, so the native code can take over in the middle of a big one.
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n, RuntimeError& err) const override {
    if (row_from_) return eval_rows(inputs[0], n, inputs + 1, 1, outputs, err);  // one row
    std::vector<const float*> in(inputs, inputs + num_inputs());
    std::vector<float*> out(outputs, outputs + num_outputs());
    for (size_t done = 0; done < n;) {
      size_t m = std::min(kChunk, n - done);
      if (uint64_t vm = s_->vm_points.load(); force_after_ > vm) m = std::min<size_t>(m, force_after_ - vm);
      if (const Kernel* k = native(n - done)) return k->eval_batch(in.data(), out.data(), n - done, err);
      auto t0 = Clock::now();
      if (!vm_->eval_batch(in.data(), out.data(), m, err)) return false;
      account(m,
              static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count()));
      for (auto& p : in) p += m;
      for (auto& p : out) p += m;
      done += m;
    }
    return true;
  }

  // A kernel with row parameters (a row split's body) goes by whole rows, as many as make a chunk.
  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 RuntimeError& err) const override {
    if (!row_from_) return Kernel::eval_rows(first, count, rest, rows, outputs, err);
    std::vector<const float*> r(rest, rest + num_inputs() - 1);
    std::vector<float*> out(outputs, outputs + num_outputs());
    size_t per = std::max<size_t>(1, kChunk / std::max<size_t>(count, 1));
    for (size_t done = 0; done < rows;) {
      size_t m = std::min(per, rows - done);
      if (uint64_t vm = s_->vm_points.load(); force_after_ > vm)
        m = std::min<size_t>(m, (force_after_ - vm + count - 1) / count);
      if (const Kernel* k = native((rows - done) * count))
        return k->eval_rows(first, count, r.data(), rows - done, out.data(), err);
      auto t0 = Clock::now();
      if (!vm_->eval_rows(first, count, r.data(), m, out.data(), err)) return false;
      account(m * count,
              static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count()));
      for (auto& p : r) p += m;
      for (auto& p : out) p += m * count;
      done += m;
    }
    return true;
  }

  bool eval(const float* inputs, float* outputs, RuntimeError& err) const override {
    if (const Kernel* k = native(1)) return k->eval(inputs, outputs, err);
    bool ok = vm_->eval(inputs, outputs, err);
    account(1, static_cast<uint64_t>(vm_ns_per_point()));  // one point is too short to time
    return ok;
  }

  void expect_points(uint64_t points) const override {
    // The first native code is what matters here: the middle tier's when LLVM's is far off (the
    // compile thread goes on to LLVM only if the announced job outlasts it).
    s_->announced = s_->vm_points.load() + points;
    if (double(points) * vm_ns_per_point() > first_native_ns(s_->ops)) start();
  }

 private:
  double vm_ns_per_point() const { return s_->vm_ns_per_point(); }

  // The native kernel when it is ready (after a forced switch point, waited for; before it, not
  // used even when ready, so the switch lands where the test put it however fast the compile was).
  const Kernel* native(size_t n) const {
    if (force_after_ && s_->vm_points.load() < force_after_) return nullptr;
    const Kernel* k = s_->ready.load(std::memory_order_acquire);
    if (!k && force_after_) {
      std::unique_lock<std::mutex> hold(s_->lock);
      s_->done_cv.wait(hold, [&] { return s_->done; });
      k = s_->ready.load(std::memory_order_acquire);
    }
    if (k) {
      if (!switched_.exchange(true)) {
        ++totals().switched;
        int64_t expected = -1;
        totals().first_switch_ns.compare_exchange_strong(expected, now_ns() - totals().start_ns.load());
      }
      totals().native_points += n;
    }
    return k;
  }

  // Past the share of the compile's estimate, the compile starts, unless the caller announced a
  // job whose rest the VM finishes sooner than the compile would (then waiting for it at the end
  // would only cost).
  void account(size_t n, uint64_t ns) const {
    uint64_t points = s_->vm_points += n;
    totals().vm_points += n;
    double estimate = native_compile_ns(s_->ops);
    if (s_->vm_ns.fetch_add(ns) + ns < kStartShare * estimate) return;
    uint64_t ahead = s_->announced.load();
    if (ahead > points && double(ahead - points) * vm_ns_per_point() < estimate) return;
    start();
  }

  void start() const {
    if (s_->started.exchange(true)) return;
    ++totals().compiles;
    compiler().submit(s_);
  }

  std::unique_ptr<Kernel> vm_;
  std::shared_ptr<Shared> s_;
  uint64_t force_after_ = forced_switch();
  uint32_t row_from_ = s_->module->kernel_function().row_params_from;
  mutable std::atomic<bool> switched_{false};
};

}  // namespace

double native_compile_ns(size_t ops) {
#ifdef FS_HAVE_LLVM
  // The first compile of a process also loads the module: dlopen and LLVM's relocations, 49 ms here.
  double load = llvm_module_loaded() ? 0 : 50e6;
  return load + 10e6 + 50e3 * static_cast<double>(ops);
#else
  return sse_compile_ns(ops);
#endif
}

std::unique_ptr<Kernel> TieredBackend::compile(const ir::Module& m, const Budgets& budgets, std::string& error) const {
  auto vm = make_backend("vm")->compile(m, budgets, error);
  if (!vm) return nullptr;
  auto s = std::make_shared<Shared>();
  s->module = m.clone();
  s->budgets = budgets;
  s->ops = m.instruction_count();
  // Machine code a cache already holds (a second run with --llvm-disk-cache) costs a load, not a
  // compile: native from the first batch.
  if (native_code_cached(m, budgets)) {
    std::string ignored;
    if (auto be = make_backend(native_backend())) s->native = be->compile(m, budgets, ignored);
    if (s->native) {
      ++totals().cached;
      s->started = true, s->done = true;
      s->ready.store(s->native.get(), std::memory_order_release);
    }
  }
  return std::make_unique<TieredKernel>(std::move(vm), std::move(s));
}

TierStats tier_stats() {
  const Totals& t = totals();
  TierStats s;
  s.kernels = t.kernels, s.compiles = t.compiles, s.cached = t.cached, s.switched = t.switched, s.failed = t.failed;
  s.vm_points = t.vm_points, s.native_points = t.native_points;
  int64_t first = t.first_switch_ns.load();
  s.first_switch_ms = first < 0 ? -1 : double(first) / 1e6;
  // Without a native compile the module was never needed: name it without loading LLVM for it.
  // With compiles but no module loaded, the native code was the SSE emitter's (the middle tier
  // alone, or a module that failed to load): asking native_backend() would load it only to say so.
#if defined(FS_HAVE_LLVM)
  s.native = llvm_module_loaded() || !t.compiles ? "llvm" : "sse";
#elif defined(FS_HAVE_WASM)
  s.native = "wasm";
#else
  s.native = "sse";
#endif
  return s;
}

}  // namespace fscript::backends
