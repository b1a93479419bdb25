// fscript bench and render2d: the batch path over many points, one or more threads.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "backends/llvm_module.h"
#include "backends/row_split_kernel.h"
#include "backends/tiered/tiered.h"
#include "engine/render/png.h"
#include "engine/render/quadtree.h"
#include "runtime/support/files.h"
#include "runtime/support/parallel.h"
#include "runtime/support/progress.h"
#include "tools/fscript/commands.h"

namespace fscript::cli {
namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kBatch = 4096;  // points per eval_batch call in bench and render2d

// Runs `work(begin, end)` over [0, n) in kBatch slices taken by `threads` threads as they come
// free (every point's value is its own, so the schedule changes no result); the first error stops
// every thread.
template <class Work>
bool parallel_slices(size_t n, unsigned threads, Work work, backends::RuntimeError& err) {
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  return support::run_parts(
      static_cast<int>(threads),
      [&](int, backends::RuntimeError& e) {
        while (!failed) {
          size_t b = next.fetch_add(kBatch);
          if (b >= n) return true;
          if (!work(b, std::min(n, b + kBatch), e)) return !(failed = true);
        }
        return true;
      },
      err);
}

size_t grid_side(size_t n) {
  return std::max<size_t>(2, static_cast<size_t>(std::ceil(std::cbrt(static_cast<double>(n)))));
}

// Varied inputs: a 3D grid over [-1, 1]^3 (the shared benchmarks' dense grid), t = 0.
std::vector<std::vector<float>> grid_inputs(size_t n, size_t n_in) {
  size_t side = grid_side(n);
  std::vector<std::vector<float>> cols(n_in, std::vector<float>(n, 0.0f));
  for (size_t i = 0; i < n; ++i) {
    size_t idx[3] = {i % side, (i / side) % side, (i / side / side) % side};
    for (size_t k = 0; k < n_in && k < 3; ++k)
      cols[k][i] = -1.0f + 2.0f * static_cast<float>(idx[k]) / static_cast<float>(side - 1);
  }
  return cols;
}

}  // namespace

// The same grid as rows for Kernel::eval_rows: the x of one row, and per row the other inputs.
struct GridRows {
  std::vector<float> x;
  std::vector<std::vector<float>> rest;
  size_t rows = 0;
};
GridRows grid_rows(size_t n, size_t n_in) {
  GridRows g;
  size_t side = grid_side(n);
  g.rows = (n + side - 1) / side;
  auto cols = grid_inputs(g.rows * side, n_in);
  g.x.assign(cols[0].begin(), cols[0].begin() + static_cast<std::ptrdiff_t>(side));
  for (size_t k = 1; k < n_in; ++k) {
    g.rest.emplace_back(g.rows);
    for (size_t r = 0; r < g.rows; ++r) g.rest.back()[r] = cols[k][r * side];
  }
  return g;
}

// The grid row by row, `threads` threads taking slices of rows.
bool bench_rows(const backends::Kernel& k, const GridRows& g, std::vector<std::vector<float>>& outs, unsigned threads,
                backends::RuntimeError& err) {
  size_t side = g.x.size();
  size_t per_slice = std::max<size_t>(1, kBatch / side);
  return parallel_slices(
      g.rows, std::max(1u, threads),
      [&](size_t b, size_t e, backends::RuntimeError& er) {
        for (size_t r = b; r < e; r += per_slice) {
          size_t n = std::min(per_slice, e - r);
          std::vector<const float*> rest(g.rest.size());
          std::vector<float*> out(outs.size());
          for (size_t i = 0; i < rest.size(); ++i) rest[i] = g.rest[i].data() + r;
          for (size_t i = 0; i < out.size(); ++i) out[i] = outs[i].data() + r * side;
          if (!k.eval_rows(g.x.data(), side, rest.data(), n, out.data(), er)) return false;
        }
        return true;
      },
      err);
}

int cmd_bench(const Options& o, const std::string& file, const std::string& entry, size_t points, unsigned threads,
              BenchPath path) {
  bool one_point = path == BenchPath::OnePoint;
  Compiled c;
  if (int rc = compile_file(file, entry, o, c); rc != kExitOk) return rc;
  // The backend's own compile time (IR to a kernel), best of three, per 1,000 IR operations.
  size_t ops = c.module->instruction_count();
  std::string name = o.backend.empty() ? backends::default_backend() : o.backend;
  auto best_compile = [&] {
    double ms = 1e30;
    for (int k = 0; k < 3; ++k) {
      std::unique_ptr<backends::Kernel> again;
      auto t = Clock::now();
      driver::compile_kernel(*c.module, name, o.budgets, again);
      ms = std::min(ms, std::chrono::duration<double, std::milli>(Clock::now() - t).count());
    }
    return ms;
  };
  // The llvm backend's cold compile; the cached one below (no other backend loads LLVM for this).
  const backends::LlvmModule* lm = name == "llvm" ? backends::llvm_module() : nullptr;
  if (lm) lm->set_cache_enabled(false);
  double compile_ms = best_compile();
  std::printf("backend compile: %.3g ms for %zu IR operations (%.3g ms per 1,000)", compile_ms, ops,
              compile_ms * 1000.0 / static_cast<double>(std::max<size_t>(ops, 1)));
  if (lm) {
    lm->set_cache_enabled(true);
    best_compile();  // fills the cache
    std::printf("; %.3g ms from the cache", best_compile());
  }
  std::printf("\n");
  size_t n_in = c.kernel->num_inputs(), n_out = c.kernel->num_outputs();
  bool rows = path == BenchPath::Grid && n_in >= 2;  // one input: a row is all there is
  auto cols = rows ? std::vector<std::vector<float>>() : grid_inputs(points, n_in);
  GridRows g = rows ? grid_rows(points, n_in) : GridRows{};
  if (rows) points = g.rows * g.x.size();
  std::vector<std::vector<float>> outs(n_out, std::vector<float>(points));
  backends::RuntimeError err;
  if (one_point) {  // a backend may compile its one-point code on the first call: not timed either
    std::vector<float> in(n_in), out(n_out);
    for (size_t k = 0; k < n_in; ++k) in[k] = cols[k][0];
    if (!c.kernel->eval(in.data(), out.data(), err)) {
      print_runtime_error(*c.script.file, err);
      return kExitInput;
    }
  }
  if (rows) {  // the row split's kernels are compiled on the first rows: compile time is not timed
    GridRows few = g;
    few.rows = std::min<size_t>(g.rows, 64);  // enough points that the split runs (row_split_kernel.cpp)
    if (!bench_rows(*c.kernel, few, outs, 1, err)) {
      print_runtime_error(*c.script.file, err);
      return kExitInput;
    }
  }
  auto t0 = Clock::now();
  bool ok = rows ? bench_rows(*c.kernel, g, outs, threads, err)
                 : parallel_slices(
                       points, std::max(1u, threads),
                       [&](size_t b, size_t e, backends::RuntimeError& er) {
                         if (one_point) {
                           std::vector<float> in(n_in), out(n_out);
                           for (size_t i = b; i < e; ++i) {
                             for (size_t k = 0; k < n_in; ++k) in[k] = cols[k][i];
                             if (!c.kernel->eval(in.data(), out.data(), er)) return false;
                           }
                           return true;
                         }
                         std::vector<const float*> in(n_in);
                         std::vector<float*> out(n_out);
                         for (size_t k = 0; k < n_in; ++k) in[k] = cols[k].data() + b;
                         for (size_t k = 0; k < n_out; ++k) out[k] = outs[k].data() + b;
                         return c.kernel->eval_batch(in.data(), out.data(), e - b, er);
                       },
                       err);
  double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!ok) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  std::printf("%.6g evals/s\n%.4g ns/eval\n", static_cast<double>(points) / secs,
              secs * 1e9 / static_cast<double>(points));
  if (path == BenchPath::Grid) {
    backends::RowStats r = backends::row_stats();
    if (r.rows)
      std::printf("row split: %llu operations once per row, %llu per point, %llu values per row\n",
                  static_cast<unsigned long long>(r.hoisted), static_cast<unsigned long long>(r.per_point),
                  static_cast<unsigned long long>(r.row_values));
    else std::printf("row split: none (no work to hoist out of the rows, or the kernel is not straight-line)\n");
  }
  if (name == "auto") {
    backends::TierStats t = backends::tier_stats();
    std::printf("tiers: %llu of %llu points on %s", static_cast<unsigned long long>(t.native_points),
                static_cast<unsigned long long>(t.native_points + t.vm_points), t.native.c_str());
    if (t.first_switch_ms >= 0) std::printf(", switched at %.3g ms", t.first_switch_ms);
    std::printf("\n");
  }
  return kExitOk;
}

// --stats of render2d: per level, how the regions went and how long their tapes were.
void print_quadtree_stats(const render::QuadtreeStats& st, size_t pixels) {
  if (!st.pruned) {
    std::printf("pruning: off (dense: every pixel evaluated)\n");
    return;
  }
  std::printf("pruning: on, full tape %zu operations\n", st.full_tape_ops);
  for (size_t k = 0; k < st.levels.size(); ++k) {
    const auto& l = st.levels[k];
    std::printf("level %ux%u: %zu empty, %zu full, %zu ambiguous", l.size, l.size, l.empty, l.full, l.ambiguous);
    if (k + 1 == st.levels.size()) std::printf(" (evaluated point by point)\n");
    else
      std::printf(", mean simplified tape %.1f operations\n",
                  l.ambiguous ? static_cast<double>(l.tape_ops) / static_cast<double>(l.ambiguous) : 0.0);
  }
  std::printf(
      "points evaluated: %zu of %zu (%.2f%% of the dense path); simplified kernels compiled: %zu; batches run "
      "straight from their tape: %zu\n",
      st.points, pixels, 100.0 * static_cast<double>(st.points) / static_cast<double>(std::max<size_t>(pixels, 1)),
      st.kernels, st.direct);
}

int cmd_render2d(const Options& o, const std::string& file, const std::string& entry, const std::string& size,
                 const std::string& bounds, const std::string& out_path, unsigned threads, bool prune, bool stats,
                 unsigned repeat) {
  uint32_t w, h;
  float bd[4];
  if (!parse_size(size, w, h)) {
    std::cerr << "error: --size wants W or WxH with 1 <= W, H <= 32768, got '" << size << "'\n";
    return kExitUsage;
  }
  if (!parse_numbers(bounds, 4, bd)) {
    std::cerr << "error: --bounds wants four finite numbers X0,X1,Y0,Y1, got '" << bounds << "'\n";
    return kExitUsage;
  }
  if (!out_path.empty() && file != "-" && support::same_file(out_path, file)) {
    std::cerr << "error: the output " << out_path << " is the script this command reads: name another output\n";
    return kExitUsage;
  }
  Compiled c;
  if (int rc = compile_file(file, entry, o, c); rc != kExitOk) return rc;
  size_t n_in = c.kernel->num_inputs();
  if (n_in < 2) {
    std::cerr << "error: render2d needs an entry with at least two inputs (x, y)\n";
    return kExitInput;
  }
  render::PlaneGrid g{w, h, bd[0], bd[1], bd[2], bd[3]};
  render::InsideOptions ro;
  ro.budgets = o.budgets;
  ro.threads = std::max(1u, threads);
  ro.prune = prune;
  if (prune && ir::interval_evaluable(c.module->kernel_function()))  // built once, as the kernel is compiled once
    ro.tape = std::make_shared<const ir::IntervalTape>(c.module->kernel_function());
  std::vector<uint8_t> px;
  render::QuadtreeStats st;
  backends::RuntimeError err;
  double ms = 0;
  bool ok = true;
  support::progress_expect(std::max(1u, repeat), "pictures");
  std::optional<support::ProgressLine> line;  // on a terminal, for runs over a second
  line.emplace("fscript render2d");
  for (unsigned r = 0; ok && r < std::max(1u, repeat); ++r) {  // the best of `repeat` (this machine is noisy)
    auto t0 = Clock::now();
    support::ProgressJob job;
    ro.progress = &job;
    ok = render::render_inside(*c.module, *c.kernel, g, ro, px, st, err);
    ro.progress = nullptr;
    double t = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    ms = r == 0 ? t : std::min(ms, t);
  }
  line.reset();  // erased before anything else is printed
  if (!ok) {
    print_runtime_error(*c.script.file, err);
    return kExitInput;
  }
  size_t white = static_cast<size_t>(std::count(px.begin(), px.end(), uint8_t{255}));
  // Without -o the picture goes to the current folder, named after the script (stdin: render2d.png).
  std::string path = out_path;
  if (path.empty()) {
    std::string stem = file == "-" ? "render2d" : std::filesystem::path(file).stem().string();
    path = (stem.empty() ? std::string("render2d") : stem) + ".png";
  }
  // The figures first: a build without PNG (the browser's, in Node) still times the picture.
  std::printf("%zu white pixels\n%.3f ms\n", white, ms);
  std::fflush(stdout);
  std::string error;
  if (!render::write_png(path, w, h, 1, px, error)) {
    std::cerr << "error: " << error << "\n";
    return kExitInput;
  }
  std::cerr << "wrote " << path << ": " << w << "x" << h << ", " << white << " white pixels\n";
  if (stats) print_quadtree_stats(st, size_t(w) * h);
  return kExitOk;
}

}  // namespace fscript::cli
