// The quadtree renderer: batched interval evaluation of each region's children, tape
// simplification per region, dense batches for the open tiles of the last level. Every region
// writes only its own pixels, so the picture is the same bits for any thread count and schedule.
#include "engine/render/quadtree.h"

#include <algorithm>
#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "ir/interval_eval.h"
#include "backends/vm/vm_backend.h"
#include "backends/vm/vm_points.h"
#include "ir/tape.h"
#include "engine/render/tiles.h"
#include "runtime/support/parallel.h"

namespace fscript::render {

float PlaneGrid::x(uint32_t col) const {
  return w > 1 ? x0 + static_cast<float>(col) * (x1 - x0) / static_cast<float>(w - 1) : x0;
}

float PlaneGrid::y(uint32_t row) const {
  return h > 1 ? y1 - static_cast<float>(row) * (y1 - y0) / static_cast<float>(h - 1) : y1;
}

namespace {

// Region sides per level; the open regions of the last are evaluated densely, on the tape of the
// level above. Each level splits a region into 4x4 children, bounded together in one batched
// interval pass (ir::IntervalTape::eval_batch, 16 lanes). Chosen by measurement (docs/performance.md):
// a fourth level (4x4 pixels) decides two thirds of the remaining pixels, but its simplified tapes
// and their compiles cost more than the points they save.
constexpr uint32_t kSizes[] = {256, 64, 16, 4};
constexpr size_t kLevels = sizeof(kSizes) / sizeof(kSizes[0]);

// A tape's kernel once a dense batch needs it; shared by every region that keeps the tape.
// A top tile's tape is shared by the threads that take its children: the first to need the kernel
// compiles it, once.
struct Compiled {
  const backends::Kernel* kernel = nullptr;
  std::unique_ptr<backends::Kernel> owned;
  std::once_flag once;
};

// A tape: flat, for intervals and simplification, and compiled when needed.
struct Tape {
  std::shared_ptr<const ir::IntervalTape> flat;
  std::shared_ptr<Compiled> compiled;  // made when first needed, shared by the tapes that share it
  size_t ops = 0;
};

class Renderer {
 public:
  Renderer(const backends::Kernel& dense, const PlaneGrid& g, const InsideOptions& o, const std::vector<float>& xs,
           const std::vector<float>& ys, std::vector<uint8_t>& px)
      : xs_(xs), ys_(ys), dense_(dense), g_(g), o_(o), px_(px) {
    for (uint32_t s : kSizes) stats_.levels.push_back({s, 0, 0, 0, 0});
  }

  // Bounds `rects` (regions of `level`) on `tape` in batches; fills the decided ones and hands each
  // open one, with its batch evaluation and lane, to `open`. False on a runtime error. `keep`: each
  // batch with an open region also gets a new entry there, for evaluations that outlive the call:
  // its choices (what simplification reads), not its bounds; `open` is called while it is empty.
  template <typename Open>
  bool bound(const Tape& tape, const std::vector<Rect>& rects, size_t level, Open open,
             std::deque<ir::IntervalBatchEval>* keep = nullptr) {
    QuadtreeLevel& st = stats_.levels[level];
    std::vector<ir::IntervalLanes>& in = lanes_[level];  // reused: threads share one malloc arena
    in.resize(dense_.num_inputs());
    for (auto& lanes : in)
      for (size_t k = 0; k < ir::kIntervalLanes; ++k) lanes.set(k, math::Interval{0, 0, false});
    for (size_t first = 0; first < rects.size(); first += ir::kIntervalLanes) {
      size_t n = std::min(ir::kIntervalLanes, rects.size() - first);
      for (size_t k = 0; k < ir::kIntervalLanes; ++k) {
        const Rect& r = rects[first + std::min(k, n - 1)];
        in[0].set(k, math::iv::hull(math::Interval::point(xs_[r.c0]), math::Interval::point(xs_[r.c1 - 1])));
        in[1].set(k, math::iv::hull(math::Interval::point(ys_[r.r0]), math::Interval::point(ys_[r.r1 - 1])));
      }
      // Per level: a parent's evaluation outlives its children's. One kept keeps only what
      // simplification reads (the choices): its bounds, 192 bytes a value, are the level's scratch.
      ir::IntervalBatchEval& ev = scratch_[level];
      tape.flat->eval_batch(in, ev);
      if (keep) keep->emplace_back();
      bool any = false;
      for (size_t k = 0; k < n; ++k) {
        const Rect& r = rects[first + k];
        math::Interval f = ev.output(0, k);
        if (!f.nan && f.lo >= 0) {
          ++st.full, fill(r, 255);
        } else if (f.empty() || f.hi < 0) {
          ++st.empty, fill(r, 0);  // NaN is outside too
        } else {
          ++st.ambiguous, any = true;
          if (!open(r, ev, k)) return false;
        }
      }
      if (keep && !any) keep->pop_back();
      if (keep && any) keep->back().choices = ev.choices, keep->back().outputs = ev.outputs;
    }
    return true;
  }

  // Region r, open at `level` (ev, lane: its bounds on `tape`): its children at the next level on
  // a tape simplified for r; the last level's open children densely, in one batch on that tape.
  bool region(Tape& tape, Rect r, size_t level, ir::IntervalBatchEval& ev, size_t lane) {
    Tape child = narrowed(tape, ev, lane, level);
    if (last_level(level, child)) return dense(child, &r, 1);
    std::vector<Rect>& pending = pending_[level];
    pending.clear();
    bool last = level + 2 == kLevels;
    split(r, kSizes[level + 1], kids_[level]);
    bool ok = bound(child, kids_[level], level + 1, [&](Rect c, ir::IntervalBatchEval& cev, size_t k) {
      if (last) return pending.push_back(c), true;
      return region(child, c, level + 1, cev, k);
    });
    return ok && (pending.empty() || dense(child, pending.data(), pending.size()));
  }

  // The tape for an open region of `level` (ev, lane: its bounds on `tape`); `own`: not from the
  // level's reused storage (the top tiles' tapes, kept for the threads).
  Tape narrowed(Tape& tape, ir::IntervalBatchEval& ev, size_t lane, size_t level, bool own = false) {
    Tape child = simplified(tape, ev, lane, own ? SIZE_MAX : level);
    stats_.levels[level].tape_ops += child.ops;
    return child;
  }

  // Whether an open region of `level` on `tape` is evaluated whole. Bounding the last level's small
  // tiles pays only when the bounds run as SIMD: a tape with transcendentals (bounded lane by lane)
  // evaluates the region above's pixels instead.
  static bool last_level(size_t level, const Tape& tape) {
    return level + 1 == kLevels || (level + 2 == kLevels && !tape.flat->simd_only());
  }

  // Every pixel of the rects, in one batch on the tape's kernel.
  bool dense(Tape& tape, const Rect* rects, size_t count) {
    if (count == 1 && tape.compiled && tape.compiled->kernel == &dense_) return dense_rows(rects[0]);
    size_t n = 0;
    for (size_t q = 0; q < count; ++q) n += size_t(rects[q].c1 - rects[q].c0) * (rects[q].r1 - rects[q].r0);
    cols_.resize(dense_.num_inputs());
    for (auto& c : cols_) c.assign(n, 0.0f);
    where_.resize(n);
    size_t i = 0;
    for (const Rect* r = rects; r != rects + count; ++r)
      for (uint32_t row = r->r0; row < r->r1; ++row)
        for (uint32_t col = r->c0; col < r->c1; ++col, ++i) {
          cols_[0][i] = xs_[col];
          cols_[1][i] = ys_[row];
          where_[i] = size_t(row) * g_.w + col;
        }
    std::vector<const float*>& in = in_ptrs_;
    in.clear();
    for (auto& c : cols_) in.push_back(c.data());
    outs_.resize(dense_.num_outputs());
    for (auto& v : outs_) v.resize(std::max(n, vm::kPointLanes));
    if (tape.flat && n <= vm::kPointLanes) {  // a few points on a short tape: run it, do not compile it
      vm::eval_tape_points(*tape.flat, in.data(), in.size(), n, outs_[0].data());
      ++stats_.direct;
    } else {
      if (!tape.compiled) tape.compiled = std::make_shared<Compiled>();
      if (!compile(tape)) return false;
      std::vector<float*>& out = out_ptrs_;
      out.clear();
      for (auto& v : outs_) out.push_back(v.data());
      if (!tape.compiled->kernel->eval_batch(in.data(), out.data(), n, err_)) return false;
    }
    for (size_t k = 0; k < n; ++k) px_[where_[k]] = outs_[0][k] >= 0.0f ? 255 : 0;
    stats_.points += n;
    return true;
  }

  // One rect on the full kernel, as grid rows (Kernel::eval_rows: what depends only on y once a row).
  bool dense_rows(const Rect& r) {
    size_t count = r.c1 - r.c0, rows = r.r1 - r.r0, n = count * rows;
    cols_.resize(dense_.num_inputs());
    cols_[0].assign(ys_.begin() + r.r0, ys_.begin() + r.r1);
    for (size_t k = 1; k < cols_.size(); ++k) cols_[k].assign(rows, 0.0f);
    std::vector<const float*> rest;
    for (auto& c : cols_) rest.push_back(c.data());
    outs_.resize(dense_.num_outputs());
    std::vector<float*> out;
    for (auto& v : outs_) v.resize(n), out.push_back(v.data());
    if (!dense_.eval_rows(xs_.data() + r.c0, count, rest.data(), rows, out.data(), err_)) return false;
    for (size_t row = 0; row < rows; ++row)
      for (size_t col = 0; col < count; ++col)
        px_[(r.r0 + row) * g_.w + r.c0 + col] = outs_[0][row * count + col] >= 0.0f ? 255 : 0;
    stats_.points += n;
    return true;
  }

  QuadtreeStats stats_;
  backends::RuntimeError err_;

 private:
  void fill(Rect r, uint8_t v) {
    for (uint32_t row = r.r0; row < r.r1; ++row)
      std::fill_n(px_.begin() + static_cast<long>(size_t(row) * g_.w + r.c0), r.c1 - r.c0, v);
  }

  // The parent's tape specialised to the region, or the parent's itself when that saves little.
  // `level`: written into that level's tape of this renderer, reused by the next region of the
  // level (its storage kept: no allocation); none: a tape of its own (one that outlives the region).
  Tape simplified(Tape& parent, ir::IntervalBatchEval& ev, size_t lane, size_t level = SIZE_MAX) {
    std::shared_ptr<ir::IntervalTape> s;
    if (level < kLevels && pool_[level].use_count() == 1) s = pool_[level];  // free: its last region has ended
    else s = std::make_shared<ir::IntervalTape>();
    if (level < kLevels && !pool_[level]) pool_[level] = s;
    parent.flat->simplified(ev, lane, *s);
    if (s->length() * 10 > parent.ops * 9) {  // under 10% shorter: the parent, sharing its kernel too
      if (!parent.compiled) parent.compiled = std::make_shared<Compiled>();
      return parent;
    }
    Tape t;
    t.flat = std::move(s);
    t.ops = t.flat->length();
    return t;
  }

  // Simplified tapes run on the VM whatever the dense kernel's backend, compiled straight from the
  // flat tape: that compile pays for a region, the sse emitter's and llvm's do not
  // (docs/performance.md), and every backend gives the same bits.
  bool compile(Tape& tape) {
    Compiled& c = *tape.compiled;
    std::call_once(c.once, [&] {
      if (c.kernel) return;  // the whole function's: `dense` itself
      c.owned = vm::compile_tape(*tape.flat, o_.budgets);
      c.kernel = c.owned.get();
      ++stats_.kernels;
    });
    return true;
  }

  ir::IntervalBatchEval scratch_[kLevels];
  // Buffers reused from region to region: the threads share one malloc arena (the huge heap), and
  // allocating them afresh put two threads behind its lock.
  std::vector<ir::IntervalLanes> lanes_[kLevels];
  std::vector<Rect> kids_[kLevels], pending_[kLevels];
  std::vector<const float*> in_ptrs_;
  std::vector<float*> out_ptrs_;
  std::shared_ptr<ir::IntervalTape> pool_[kLevels];  // per level: the tape its regions are simplified into
  const std::vector<float>&xs_, &ys_;  // the grid's coordinates, once for every renderer
  std::vector<std::vector<float>> cols_, outs_;  // dense batches' inputs and outputs, reused
  std::vector<size_t> where_;
  const backends::Kernel& dense_;
  const PlaneGrid& g_;
  const InsideOptions& o_;
  std::vector<uint8_t>& px_;
};

void merge(QuadtreeStats& into, const QuadtreeStats& part) {
  for (size_t l = 0; l < into.levels.size(); ++l) {
    into.levels[l].empty += part.levels[l].empty;
    into.levels[l].full += part.levels[l].full;
    into.levels[l].ambiguous += part.levels[l].ambiguous;
    into.levels[l].tape_ops += part.levels[l].tape_ops;
  }
  into.points += part.points;
  into.direct += part.direct;
  into.kernels += part.kernels;
}

}  // namespace

bool render_inside(const ir::Module& m, const backends::Kernel& dense, const PlaneGrid& g, const InsideOptions& o,
                   std::vector<uint8_t>& px, QuadtreeStats& stats, backends::RuntimeError& err) {
  px.resize(size_t(g.w) * g.h);  // (every pixel is written below: a reused picture is not cleared first)
  const ir::Function& fn = m.kernel_function();
  stats = {};
  stats.full_tape_ops = ir::tape_length(fn);
  bool prune = o.prune && dense.num_inputs() >= 2 && dense.num_outputs() >= 1 && ir::interval_evaluable(fn);
  if (!prune) dense.expect_points(uint64_t(g.w) * g.h);  // every pixel ahead: a tiered kernel compiles at once
  std::vector<Rect> tiles;  // the top level's regions, shared out to the threads by index
  uint32_t s = prune ? kSizes[0] : 64;
  for (uint32_t row = 0; row < g.h; row += s)
    for (uint32_t col = 0; col < g.w; col += s)
      tiles.push_back({col, row, std::min(col + s, g.w), std::min(row + s, g.h)});
  int parts = static_cast<int>(std::max(1u, std::min<unsigned>(o.threads, static_cast<unsigned>(tiles.size()))));
  std::vector<std::unique_ptr<Renderer>> renderers;
  std::vector<float> xs(g.w), ys(g.h);
  for (uint32_t c = 0; c < g.w; ++c) xs[c] = g.x(c);
  for (uint32_t r = 0; r < g.h; ++r) ys[r] = g.y(r);
  for (int p = 0; p < parts; ++p) renderers.push_back(std::make_unique<Renderer>(dense, g, o, xs, ys, px));
  Tape full;
  if (prune) full.flat = o.tape ? o.tape : std::make_shared<const ir::IntervalTape>(fn);
  full.ops = stats.full_tape_ops;
  full.compiled = std::make_shared<Compiled>();
  full.compiled->kernel = &dense;  // the full tape is what `dense` was compiled from
  // The top level is bounded up front, in batches; the threads then share out its open tiles and
  // their open children (below).
  struct Top {
    Rect r;
    size_t batch, lane;  // its bounds: top[batch], lane
    Tape tape;           // simplified for it
    std::deque<ir::IntervalBatchEval> evals;  // its children's bounds (stable addresses)
    struct Kid {
      Rect r;
      size_t batch, lane;  // its bounds: evals[batch], lane; SIZE_MAX: the tile is evaluated whole
    };
    std::vector<Kid> open;
  };
  std::vector<Top> tops;
  std::deque<ir::IntervalBatchEval> top;  // the top level's bounds (stable addresses)
  // The top level, bounded by the first thread while the others start (they wait for it).
  auto top_level = [&] {
    Renderer& r0 = *renderers[0];
    bool fine = true;
    for (size_t first = 0; first < tiles.size() && fine; first += ir::kIntervalLanes) {
      std::vector<Rect> part(tiles.begin() + static_cast<long>(first),
                             tiles.begin() + static_cast<long>(std::min(tiles.size(), first + ir::kIntervalLanes)));
      fine = r0.bound(
          full, part, 0,
          [&](Rect r, ir::IntervalBatchEval&, size_t k) {
            tops.push_back({r, top.size() - 1, k, {}, {}, {}});
            return true;
          },
          &top);
    }
    for (auto& ev : top) full.flat->lane_masks(ev);  // before the threads share them
    return fine;
  };
  std::atomic<bool> failed{false};
  const size_t kids_per_top = size_t(kSizes[0] / kSizes[1]) * (kSizes[0] / kSizes[1]);
  auto advance = [&](size_t n) {
    if (o.progress && n) o.progress->advance(n);
  };
  // A top tile's own work: its tape simplified, its children bounded on it (the decided ones filled).
  auto open_top = [&](Renderer& r, Top& t) {
    t.tape = r.narrowed(full, top[t.batch], t.lane, 0, true);
    if (!t.tape.compiled) t.tape.compiled = std::make_shared<Compiled>();  // before threads share it
    if (r.last_level(0, t.tape)) return t.open.push_back({t.r, SIZE_MAX, 0}), true;
    std::vector<Rect> kids = split(t.r, kSizes[1]);
    for (size_t first = 0; first < kids.size(); first += ir::kIntervalLanes) {
      std::vector<Rect> part(kids.begin() + static_cast<long>(first),
                             kids.begin() + static_cast<long>(std::min(kids.size(), first + ir::kIntervalLanes)));
      size_t before = t.evals.size();
      bool fine = r.bound(
          t.tape, part, 1,
          [&](Rect c, ir::IntervalBatchEval&, size_t k) {
            t.open.push_back({c, t.evals.size() - 1, k});
            return true;
          },
          &t.evals);
      if (!fine) return false;
      if (t.evals.size() > before) t.tape.flat->lane_masks(t.evals.back());
    }
    return true;
  };
  auto kid = [&](Renderer& r, Top& t, size_t i) {
    const Top::Kid& k = t.open[i];
    return k.batch == SIZE_MAX ? r.dense(t.tape, &k.r, 1) : r.region(t.tape, k.r, 1, t.evals[k.batch], k.lane);
  };
  // Each thread takes the next top tile, opens it and works through its open children; with no
  // top tile left it takes children of the others' (a thread's own tiles' tapes and bounds are in
  // its own cache: two threads reading each other's had each run a sixth slower). Each region
  // writes only its own pixels, so the picture does not depend on the schedule.
  std::atomic<size_t> next_top{0};
  std::vector<std::atomic<size_t>> next_kid(tiles.size());  // (by top tile: as many as there are open)
  std::vector<std::atomic<int>> opened(tiles.size());  // 1: its children may be taken
  // The open children of top tile i not yet taken, on `r`.
  auto drain = [&](Renderer& r, size_t i) {
    for (size_t k; !failed && (k = next_kid[i].fetch_add(1)) < tops[i].open.size();)
      if (!kid(r, tops[i], k)) return failed = true, false;
      else advance(1);
    return true;
  };
  auto work = [&](Renderer& r) {
    for (size_t i; !failed && (i = next_top.fetch_add(1)) < tops.size();) {
      Top& t = tops[i];
      if (!open_top(r, t)) return failed = true, opened[i].store(1, std::memory_order_release), false;
      advance(kids_per_top - t.open.size());  // (a tile evaluated whole: one open child, itself)
      opened[i].store(1, std::memory_order_release);
      if (!drain(r, i)) return false;
    }
    for (size_t i = 0; i < tops.size() && !failed; ++i) {
      while (!opened[i].load(std::memory_order_acquire) && !failed) std::this_thread::yield();
      if (!drain(r, i)) return false;
    }
    return true;
  };
  std::atomic<size_t> next_tile{0};
  std::atomic<int> topped{0};  // 1: the top level is bounded (or failed)
  bool ok = support::run_parts(parts, [&](int p) {
    Renderer& r = *renderers[static_cast<size_t>(p)];
    if (p == 0) {
      bool fine = !prune || top_level();
      if (o.progress) o.progress->set_units(prune ? tops.size() * kids_per_top : tiles.size());
      if (!fine) failed = true;
      topped.store(1, std::memory_order_release);
      if (!fine) return false;
    }
    while (!topped.load(std::memory_order_acquire)) std::this_thread::yield();
    if (failed) return false;
    if (prune) return work(r);
    for (size_t i; !failed && (i = next_tile.fetch_add(1)) < tiles.size();)
      if (!r.dense(full, &tiles[i], 1)) return failed = true, false;
      else advance(1);
    return true;
  });
  if (!ok) std::fill(px.begin(), px.end(), uint8_t{0});  // (no half-made picture, whatever the schedule)
  stats.pruned = prune;
  for (uint32_t sz : kSizes) stats.levels.push_back({sz, 0, 0, 0, 0});
  for (const auto& r : renderers) merge(stats, r->stats_);
  if (!prune) stats.levels.clear();
  for (const auto& r : renderers)  // the first part's error, whatever the schedule
    if (!r->err_.message.empty()) {
      err = r->err_;
      break;
    }
  return ok;
}

}  // namespace fscript::render
