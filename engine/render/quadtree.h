#pragma once
// Pictures of f(x, y, 0, 0) >= 0 by quadtree: a region whose interval is all inside or all outside
// is filled whole; the others split (256, 64, then 16 pixels; each region's 16 children bounded in
// one batched interval pass) on a tape simplified for them, and only the 16x16 tiles the intervals
// leave open are evaluated point by point, in one batch per 64x64 tile. Every pixel is the one the
// dense path gives.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "ir/interval_eval.h"
#include "ir/ir.h"
#include "runtime/support/progress.h"

namespace fscript::render {

// The samples of a picture: column i at x = x0 + i (x1 - x0) / (w - 1), row j at
// y = y1 - j (y1 - y0) / (h - 1) (row 0 on top), computed in float exactly so.
struct PlaneGrid {
  uint32_t w = 1, h = 1;
  float x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  float x(uint32_t col) const;
  float y(uint32_t row) const;
};

struct QuadtreeLevel {
  uint32_t size = 0;  // region side in pixels
  size_t empty = 0, full = 0, ambiguous = 0;
  size_t tape_ops = 0;  // summed over the ambiguous regions: the length of their simplified tapes
};

struct QuadtreeStats {
  bool pruned = false;  // false: the dense path ran (--no-prune, or a kernel intervals cannot bound)
  std::vector<QuadtreeLevel> levels;
  size_t full_tape_ops = 0;
  size_t points = 0;   // pixels evaluated point by point
  size_t kernels = 0;  // simplified kernels compiled
  size_t direct = 0;   // dense batches run straight from their tape (vm::eval_tape_points)
};

struct InsideOptions {
  backends::Budgets budgets;
  unsigned threads = 1;
  bool prune = true;
  support::ProgressJob* progress = nullptr;  // when given, told as top-level tiles are done
  // The kernel function's interval tape, when the caller built it ahead (ir::IntervalTape(fn), as
  // it compiled the kernel once: render2d's repeats); else each picture builds it.
  std::shared_ptr<const ir::IntervalTape> tape;
};

// px[row * w + col] = 255 where output 0 of `dense` is >= 0, else 0. `m` is the module `dense` was
// compiled from (its kernel function is what the intervals read).
bool render_inside(const ir::Module& m, const backends::Kernel& dense, const PlaneGrid& g, const InsideOptions& o,
                   std::vector<uint8_t>& px, QuadtreeStats& stats, backends::RuntimeError& err);

}  // namespace fscript::render
