#pragma once
// Progress of a long run, for one line on the terminal: the run says how many jobs it will do
// (shapes and frames to mesh, pictures to render), each job says how much of its own work is done,
// and a ProgressLine draws the total on standard error while it lives, when that is a terminal.
// Counting is a few atomic additions, so jobs report whether or not a line is drawn.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace fscript::support {

// Adds n jobs to what the run expects (a job that starts unannounced counts too); `what` names
// them on the line ("frames", "shapes", "pictures": a string literal, kept).
void progress_expect(uint64_t n, const char* what);

// One job (a shape, a frame, a picture), counted done when it ends.
class ProgressJob {
 public:
  ProgressJob();
  ~ProgressJob();
  ProgressJob(const ProgressJob&) = delete;
  ProgressJob& operator=(const ProgressJob&) = delete;
  // Its work in units (cells, blocks, rows); advance may come from any thread.
  void set_units(uint64_t n) { units_.store(n); }
  void advance(uint64_t n);

 private:
  std::atomic<uint64_t> units_{0}, done_{0};
  std::atomic<int64_t> reported_{0};  // millionths of the job already added to the run's total
};

struct ProgressState {
  uint64_t jobs = 0, done = 0;  // jobs expected (or started, if more) and finished
  double fraction = 0;          // of the whole run, partly done jobs counted by their share
  const char* what = "jobs";    // as the last progress_expect named them
};
ProgressState progress_state();
// Forgets every count (a new run in the same process: tests, the REPL).
void progress_reset();

// "3/24 frames, 45%, about 2 s left": the state as the line shows it.
std::string progress_text(const ProgressState& s, double elapsed_s);

// Draws `label: progress_text` on standard error, redrawn in place four times a second, once the
// run has taken a second (FVRML_PROGRESS_AFTER=S in the environment: S seconds, for tests);
// nothing when `enabled` is false or standard error is not a terminal. The line is erased when the
// ProgressLine ends, so what the run prints next starts clean.
class ProgressLine {
 public:
  explicit ProgressLine(std::string label, bool enabled = true);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

 private:
  void loop();
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  double after_ = 1.0;
  std::mutex lock_;
  std::condition_variable wake_;
  bool stop_ = false, drawn_ = false;
  std::thread thread_;
};

}  // namespace fscript::support
