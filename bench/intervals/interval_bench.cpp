// Interval evaluation speed: one region at a time (IntervalTape::eval) against kIntervalLanes
// regions a pass (eval_batch), and tape simplification, on a script's kernel over its tiles of
// [-1, 1]^2 (z, t fixed at 0). usage: interval_bench FILE.fs [REPEATS]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "ir/interval_eval.h"
#include "engine/driver/driver.h"
#include "runtime/support/files.h"

using namespace fscript;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Tile k of a 16x16 split of [-1, 1]^2.
math::Interval tile(size_t k, bool y) {
  float s = 2.0f / 16, lo = -1.0f + s * static_cast<float>(y ? k / 16 : k % 16);
  return {lo, lo + s, 0};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: interval_bench FILE.fs [REPEATS]\n");
    return 2;
  }
  int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  std::string text, error;
  if (!support::read_file(argv[1], text, error)) {
    std::fprintf(stderr, "%s: error: %s\n", argv[1], error.c_str());
    return 1;
  }
  driver::CompileOptions opts;
  opts.want_kernel = false;
  frontend::DiagnosticSink diag;
  driver::Compiled c;
  if (!driver::compile(std::make_unique<frontend::SourceFile>(argv[1], text), driver::default_entry(), opts, diag, c)
           .ok() ||
      !ir::interval_evaluable(c.module->kernel_function())) {
    std::fprintf(stderr, "%s%s: error: not a straight-line kernel\n", frontend::render_all(diag).c_str(), argv[1]);
    return 1;
  }
  ir::IntervalTape tape(c.module->kernel_function());
  size_t params = tape.num_params(), regions = 256, ops = tape.length();
  auto inputs = [&](size_t k) {
    std::vector<math::Interval> in(params, math::Interval{0, 0, 0});
    in[0] = tile(k, false);
    if (params > 1) in[1] = tile(k, true);
    return in;
  };
  ir::IntervalEval ev;
  auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r)
    for (size_t k = 0; k < regions; ++k) tape.eval(inputs(k), ev);
  double one = seconds_since(t0);
  ir::IntervalBatchEval bev;
  std::vector<ir::IntervalLanes> lanes(params);
  t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r)
    for (size_t first = 0; first < regions; first += ir::kIntervalLanes) {
      for (size_t k = 0; k < ir::kIntervalLanes; ++k) {
        auto in = inputs(first + k);
        for (size_t p = 0; p < params; ++p) lanes[p].set(k, in[p]);
      }
      tape.eval_batch(lanes, bev);
    }
  double batched = seconds_since(t0);
  size_t kept = 0;
  t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) kept += tape.simplified(bev, static_cast<size_t>(r) % ir::kIntervalLanes).length();
  double simplify = seconds_since(t0);
  double evals = double(repeats) * regions * ops;
  std::printf("%s: %zu operations, %zu regions x %d\n", argv[1], ops, regions, repeats);
  std::printf("  one region a pass:       %.2f ns per operation\n", one / evals * 1e9);
  std::printf("  %zu regions a pass:       %.2f ns per operation and region\n", ir::kIntervalLanes,
              batched / evals * 1e9);
  std::printf("  simplification:          %.2f ns per operation (mean kept %.0f)\n",
              simplify / (double(repeats) * ops) * 1e9, double(kept) / repeats);
  return 0;
}
