// The run's progress counters and the terminal line that shows them.
#include "runtime/support/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <system_error>

namespace fscript::support {
namespace {

constexpr int64_t kWhole = 1000000;  // a job's share, in millionths
std::atomic<uint64_t> expected{0}, started{0}, finished{0};
std::atomic<int64_t> partial{0};  // millionths of the jobs under way
std::atomic<const char*> named{"jobs"};

}  // namespace

void progress_expect(uint64_t n, const char* what) {
  expected += n;
  named = what;
}

ProgressJob::ProgressJob() { ++started; }

ProgressJob::~ProgressJob() {
  partial -= reported_.load();
  ++finished;
}

void ProgressJob::advance(uint64_t n) {
  uint64_t units = units_.load(), done = done_.fetch_add(n) + n;
  if (units == 0) return;
  int64_t now = static_cast<int64_t>(std::min<uint64_t>(kWhole, done * kWhole / units));
  int64_t before = reported_.load();
  while (now > before && !reported_.compare_exchange_weak(before, now)) {}
  if (now > before) partial += now - before;
}

ProgressState progress_state() {
  ProgressState s;
  s.what = named.load();
  s.done = finished.load();
  s.jobs = std::max({expected.load(), started.load(), s.done});
  if (s.jobs > 0) {
    double part = static_cast<double>(std::max<int64_t>(0, partial.load())) / kWhole;
    s.fraction = std::min(1.0, (static_cast<double>(s.done) + part) / static_cast<double>(s.jobs));
  }
  return s;
}

void progress_reset() { expected = 0, started = 0, finished = 0, partial = 0, named = "jobs"; }

std::string progress_text(const ProgressState& s, double elapsed_s) {
  char buf[160];
  int percent = static_cast<int>(std::floor(s.fraction * 100));
  int n = std::snprintf(buf, sizeof buf, "%llu/%llu %s, %d%%", static_cast<unsigned long long>(s.done),
                        static_cast<unsigned long long>(s.jobs), s.what, percent);
  std::string out(buf, static_cast<size_t>(std::max(0, n)));
  if (s.fraction >= 0.02 && s.fraction < 1) {  // too early, the estimate is noise
    double left = elapsed_s * (1 - s.fraction) / s.fraction;
    if (left < 1) out += ", under a second left";
    else
      std::snprintf(buf, sizeof buf, left < 60 ? ", about %.0f s left" : ", about %.0f min left",
                    left < 60 ? left : left / 60),
          out += buf;
  }
  return out;
}

ProgressLine::ProgressLine(std::string label, bool enabled)
    : label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
  if (const char* env = std::getenv("FVRML_PROGRESS_AFTER")) {
    char* end = nullptr;
    double v = std::strtod(env, &end);
    if (end != env && v >= 0) after_ = v;
  }
  if (enabled && isatty(STDERR_FILENO)) {
    try {
      thread_ = std::thread([this] { loop(); });
    } catch (const std::system_error&) {  // no thread to be had: no progress line, the run goes on
    }
  }
}

ProgressLine::~ProgressLine() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> hold(lock_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ProgressLine::loop() {
  auto write_all = [](const std::string& s) {
    for (size_t at = 0; at < s.size();) {
      ssize_t k = ::write(STDERR_FILENO, s.data() + at, s.size() - at);
      if (k <= 0) return;
      at += static_cast<size_t>(k);
    }
  };
  std::unique_lock<std::mutex> hold(lock_);
  while (!wake_.wait_for(hold, std::chrono::milliseconds(250), [this] { return stop_; })) {
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < after_) continue;  // a short run shows nothing
    write_all("\r" + label_ + ": " + progress_text(progress_state(), elapsed) + "\x1b[K");
    drawn_ = true;
  }
  if (drawn_) write_all("\r\x1b[K");  // erased: what the run prints next starts at the margin
}

}  // namespace fscript::support
