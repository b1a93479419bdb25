// The direct renderer: top-level tiles shared out to the threads; in each, regions of tiles x
// depth ranges bounded front to back in batches, the open ones split on a tape simplified for
// them, the last level's open regions probed step by step; hits refined along their rays.
#include "engine/render/direct.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "engine/render/tiles.h"
#include "ir/interval_eval.h"
#include "runtime/support/parallel.h"

namespace fscript::render {

namespace {

// Levels of the descent: a region's side in samples and its depth in steps. The top level's tiles
// are shared out to the threads; the last level's open regions are probed step by step, on the tape
// of the level above. Regions deeper than wide (docs/performance.md): fewer of them to bound and
// simplify where rays go on past a thin part.
constexpr uint32_t kTile[] = {256, 64, 16, 4};
constexpr uint32_t kChunk[] = {256, 128, 32, 8};
constexpr int kLevels = 4;
// Regions of the levels below this get no tape of their own: they run their parent's.
constexpr int kOwnTapes = 3;
constexpr int kRefineSteps = 12;  // at most, refining a hit along its ray

// A hit found at one level, refined on that level's field.
struct Found {
  uint32_t col, row;
  int32_t step;
  // f at the step and at the one before where a probe has them (the same bits as evaluating them
  // again: the same point on the same function), NaN where not.
  float at = NAN, before = NAN;
  bool has_at = false, has_before = false;
};

// A sample's ray: its points are computed as RayGrid::point does, in double and then rounded.
struct Ray {
  double o[3], v[3];
  // The point at d, rounded to float and clamped to the box.
  void at(double d, const mesh::Box3& box, float p[3]) const {
    for (int a = 0; a < 3; ++a) p[a] = std::clamp(static_cast<float>(o[a] + d * v[a]), box.lo[a], box.hi[a]);
  }
  bool in_box(const mesh::Box3& box, double d) const {
    for (int a = 0; a < 3; ++a) {
      float p = static_cast<float>(o[a] + d * v[a]);
      if (!(p >= box.lo[a] && p <= box.hi[a])) return false;
    }
    return true;
  }
};

// Points gathered for one batch evaluation.
struct Batch {
  std::vector<float> x, y, z, f;
  size_t n = 0;
  void clear() { n = 0; }
  void reserve(size_t more) {
    if (n + more > x.size()) x.resize(2 * (n + more) + 256), y.resize(x.size()), z.resize(x.size());
  }
  // The ray's point at d into the batch (room reserved before).
  void put(const Ray& r, double d, const mesh::Box3& box) {
    float p[3];
    r.at(d, box, p);
    x[n] = p[0], y[n] = p[1], z[n] = p[2], ++n;
  }
  size_t size() const { return n; }
  bool eval(const mesh::Field& field, backends::RuntimeError& err) {
    if (f.size() < n) f.resize(x.size());
    mesh::EvalTimer timer;
    return n == 0 || field.eval(x.data(), y.data(), z.data(), n, f.data(), err);
  }
};

// The points one ray gave a probe's batch, [first, end), in step order.
struct Probe {
  uint32_t col, row;
  uint32_t tile;
  uint32_t first, end;
};

bool inside(float v) { return v >= 0.0f; }  // NaN is outside

struct Bracket {
  double lo, hi;      // depths: lo outside, hi inside
  double wlo, whi;    // the values regula falsi weighs them by (Illinois halves the one kept twice)
  int kept = 0;       // -1: lo kept last, +1: hi
  bool done = false;
  int face = -1;      // the box face it met, or -1
};

// A tile's last tape constant along its rays (flat() below), and which of its rays it evaluated.
struct Memo {
  std::vector<ir::IntervalTape::Step> steps;
  std::vector<uint32_t> outputs;
  std::vector<char> evaluated;
  int sign = 0;
};

// Whether `t` is the tape kept in (steps, outputs): step by step, the operands each step reads.
bool same_tape(const std::vector<ir::IntervalTape::Step>& steps, const std::vector<uint32_t>& outputs,
               const ir::IntervalTape& t) {
  if (steps.size() != t.steps().size() || outputs.size() != t.outputs().size() ||
      !std::equal(outputs.begin(), outputs.end(), t.outputs().begin()))
    return false;
  for (size_t i = 0; i < steps.size(); ++i) {
    const ir::IntervalTape::Step &a = steps[i], &b = t.steps()[i];
    if (a.op != b.op || a.square != b.square || a.arity != b.arity || a.dst != b.dst) return false;
    if (a.op == ir::Op::Param && a.a != b.a) return false;
    if (a.op == ir::Op::Const && std::bit_cast<uint32_t>(a.imm) != std::bit_cast<uint32_t>(b.imm)) return false;
    if (a.op == ir::Op::Param || a.op == ir::Op::Const) continue;
    if ((a.arity > 0 && a.a != b.a) || (a.arity > 1 && a.b != b.b) || (a.arity > 2 && a.c != b.c)) return false;
    if (std::bit_cast<uint32_t>(a.imm) != std::bit_cast<uint32_t>(b.imm)) return false;  // ops with an immediate
  }
  return true;
}

class Tracer {
 public:
  Tracer(const mesh::Field& root, const RayGrid& g, Hits& out) : root_(root), g_(g), out_(out) {
    for (int l = 0; l < kLevels; ++l) stats_.levels.push_back({kTile[l], kChunk[l], 0, 0, 0});
    for (uint32_t k = 0; k < g.steps; ++k) depths_.push_back(g.depth(k));
    for (int a = 0; a < 3; ++a) moves_[a] = g.dir[a] != 0 || g.dir_col[a] != 0 || g.dir_row[a] != 0;
    // The normals' differences: a tenth of the longest step apart, and never under a few ulps of
    // the box's coordinates.
    double longest = 0, o[3], v[3], scale = 0;
    for (uint32_t c : {0u, g.w - 1})
      for (uint32_t r : {0u, g.h - 1}) {
        g.ray(c, r, o, v);
        longest = std::max(longest, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
      }
    for (int a = 0; a < 3; ++a)
      scale = std::max({scale, std::fabs(double(g.box.lo[a])), std::fabs(double(g.box.hi[a]))});
    h_ = static_cast<float>(std::max(0.1 * longest * (g.far - g.near) / std::max(1u, g.steps - 1), 1e-6 * scale));
    if (!(h_ > 0)) h_ = 1e-6f;
  }

  // A top-level tile, pruned: its depth ranges bounded on the whole function.
  // The top level's regions over one tile (its depth ranges, front to back), bounded up front on
  // the whole function, their tapes simplified where open.
  struct Top {
    std::vector<math::Interval> bound;
    std::vector<char> within, missed;
    std::vector<std::shared_ptr<const mesh::Field>> local;
  };
  void bound_top(Rect r, Top& t) {
    const uint32_t n = (g_.steps + kChunk[0] - 1) / kChunk[0];
    const Corners c = corners(r);
    std::vector<mesh::Box3> boxes(n);
    t.bound.assign(n, math::Interval::nan_only()), t.within.assign(n, 0), t.missed.assign(n, 0), t.local.resize(n);
    for (uint32_t k = 0; k < n; ++k) {
      bool in = false;
      t.missed[k] = !region_box(c, k * kChunk[0], std::min(g_.steps, (k + 1) * kChunk[0]), boxes[k], in);
      t.within[k] = in;
    }
    root_.bounds_and_locals(
        boxes.data(), n, t.bound.data(),
        [&](size_t k, const math::Interval& v) { return !t.missed[k] && !empty(v) && !full(v, t.within[k]); },
        t.local.data());
    DirectLevel& st = stats_.levels[0];
    for (uint32_t k = 0; k < n; ++k)
      t.missed[k] || empty(t.bound[k]) ? ++st.empty : full(t.bound[k], t.within[k]) ? ++st.full : ++st.ambiguous;
  }

  // A unit of work: a tile of the second level under a top tile, its depth ranges front to back.
  bool unit(Rect u, const Top& t) {
    memo_.clear();
    std::vector<Found> found;
    size_t hits = 0;
    for (uint32_t k = 0; k < t.bound.size() && unhit(u); ++k) {
      const uint32_t c0 = k * kChunk[0], c1 = std::min(g_.steps, c0 + kChunk[0]);
      if (t.missed[k] || empty(t.bound[k])) continue;
      if (full(t.bound[k], t.within[k])) {
        for (uint32_t row = u.r0; row < u.r1; ++row)
          for (uint32_t col = u.c0; col < u.c1; ++col)
            if (step_at(col, row) < 0) step_at(col, row) = int32_t(c0), found.push_back({col, row, int32_t(c0)});
      } else if (!descend(t.local[k] ? *t.local[k] : root_, u, c0, c1, 1, hits)) {
        return false;
      }
    }
    return refine(root_, found);
  }

  // A tile without intervals: every step of every ray in order, a few steps at a time.
  bool dense(Rect r) {
    std::vector<Found> found;
    constexpr uint32_t kRun = 16;
    for (uint32_t k0 = 0; k0 < g_.steps && unhit(r); k0 += kRun) {
      uint32_t k1 = std::min(g_.steps, k0 + kRun);
      batch_.clear(), owner_.clear();
      for (uint32_t row = r.r0; row < r.r1; ++row)
        for (uint32_t col = r.c0; col < r.c1; ++col)
          if (step_at(col, row) < 0) probe(col, row, k0, k1);
      if (!finish_probe(root_, found)) return false;
    }
    return refine(root_, found);
  }

  DirectStats stats_;
  backends::RuntimeError err_;

 private:
  int32_t& step_at(uint32_t col, uint32_t row) { return out_.step[size_t(row) * g_.w + col]; }

  // A region's bound: nothing inside (NaN is outside), or all inside (and the region in the box).
  static bool empty(const math::Interval& v) { return v.empty() || v.hi < 0; }
  static bool full(const math::Interval& v, bool within) { return !v.nan && v.lo >= 0 && within; }

  uint32_t unhit_count(Rect r) {
    uint32_t n = 0;
    for (uint32_t row = r.r0; row < r.r1; ++row)
      for (uint32_t col = r.c0; col < r.c1; ++col) n += step_at(col, row) < 0;
    return n;
  }
  bool unhit(Rect r) {
    for (uint32_t row = r.r0; row < r.r1; ++row)
      for (uint32_t col = r.c0; col < r.c1; ++col)
        if (step_at(col, row) < 0) return true;
    return false;
  }

  // The box around every point of the region at steps [k0 - 1, k1) (the step before: a hit at k0
  // is refined from there), widened to hold their float roundings and cut to the shape's box;
  // false when that leaves nothing. `within`: the region lies wholly in the shape's box. Then
  // widened by the normals' differences, which may step outside both.
  // The rays of a tile's four corner samples (origin and direction each): every ray of the tile
  // lies between them.
  using Corners = std::array<double, 24>;
  Corners corners(Rect r) const {
    Corners c;
    const uint32_t cols[2] = {r.c0, r.c1 - 1}, rows[2] = {r.r0, r.r1 - 1};
    for (int k = 0; k < 4; ++k) g_.ray(cols[k & 1], rows[k >> 1], &c[6 * k], &c[6 * k + 3]);
    return c;
  }

  bool region_box(const Corners& c, uint32_t k0, uint32_t k1, mesh::Box3& b, bool& within) const {
    const double d0 = depths_[k0 ? k0 - 1 : 0], d1 = depths_[k1 - 1];
    within = true;
    for (int a = 0; a < 3; ++a) {  // axis by axis: the eight corners' coordinates stay in registers
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      for (int k = 0; k < 4; ++k) {
        const double o = c[6 * k + a], v = c[6 * k + 3 + a];
        const double p0 = o + d0 * v, p1 = o + d1 * v;  // RayGrid::at
        lo = std::min(lo, std::min(p0, p1)), hi = std::max(hi, std::max(p0, p1));
      }
      double m = 1e-9 * (std::fabs(lo) + std::fabs(hi) + (hi - lo));
      float l = below(static_cast<float>(lo - m)), h = above(static_cast<float>(hi + m));
      within = within && l >= g_.box.lo[a] && h <= g_.box.hi[a];
      b.lo[a] = std::max(l, g_.box.lo[a]), b.hi[a] = std::min(h, g_.box.hi[a]);
      if (b.lo[a] > b.hi[a]) return false;
    }
    // The normals' differences step out of the region by up to h_ (plus their rounding).
    for (int a = 0; a < 3; ++a) b.lo[a] -= 2 * h_, b.hi[a] += 2 * h_;
    return true;
  }

  // The next float down and up (finite inputs; what nextafter gives, without its call).
  static float below(float f) {
    if (f == 0) return -std::numeric_limits<float>::denorm_min();
    uint32_t u = std::bit_cast<uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? u - 1 : u + 1);
  }
  static float above(float f) { return -below(-f); }

  // An open region (r, [k0, k1)) on `field`, a tape that holds over it: split into the regions of
  // `level`, or, where the tape reads no coordinate that changes along the rays, probed once a ray.
  bool descend(const mesh::Field& field, Rect r, uint32_t k0, uint32_t k1, int level, size_t& hits) {
    return along_rays_constant(field) ? flat(field, r, k0, k1, hits) : children(field, r, k0, k1, level, hits);
  }

  // Whether `field`'s tape leaves out every coordinate the rays move along (a shape extruded along
  // the view, seen down its axis): then its value is one along each ray inside the region.
  bool along_rays_constant(const mesh::Field& field) const {
    const ir::IntervalTape* t = field.value_tape();
    if (!t) return false;
    for (const ir::IntervalTape::Step& s : t->steps())
      if (s.op == ir::Op::Param && s.a < 3 && moves_[s.a]) return false;
    return true;
  }

  // Each open ray of r at its first step in the box within [k0, k1): the same answer as every
  // step, as long as the coordinates the tape reads are the same bits at both ends of the range
  // (x + d * 0 turns -0 into +0 where d changes sign); where not, every step. When the tile's last
  // such region ran the same tape at depths of the same sign, a ray it evaluated and left open is
  // outside here too, and is not evaluated again (the inside of an extruded shape, region after
  // region).
  bool flat(const mesh::Field& field, Rect r, uint32_t k0, uint32_t k1, size_t& hits) {
    ++stats_.constant;
    const int sign = depths_[k0] >= 0 ? 1 : depths_[k1 - 1] < 0 ? -1 : 0;  // 0: x + d * 0 may change bits
    Memo& m = memo_[{r.c0, r.r0, r.c1, r.r1}];
    const ir::IntervalTape& t = *field.value_tape();  // along_rays_constant() found one
    const bool again = sign != 0 && m.sign == sign && same_tape(m.steps, m.outputs, t);
    if (!again) {
      m.steps.assign(t.steps().begin(), t.steps().end());
      m.outputs.assign(t.outputs().begin(), t.outputs().end());
      m.sign = sign;
      m.evaluated.assign(size_t(r.c1 - r.c0) * (r.r1 - r.r0), 0);
    }
    batch_.clear(), owner_.clear();
    batch_.reserve(size_t(r.c1 - r.c0) * (r.r1 - r.r0));
    if (steps_.size() < batch_.x.size()) steps_.resize(batch_.x.size());
    for (uint32_t row = r.r0; row < r.r1; ++row)
      for (uint32_t col = r.c0; col < r.c1; ++col) {
        const size_t q = size_t(row - r.r0) * (r.c1 - r.c0) + (col - r.c0);
        if (step_at(col, row) >= 0 || (again && m.evaluated[q])) continue;
        Ray ray;
        g_.ray(col, row, ray.o, ray.v);
        uint32_t k = k0;
        while (k < k1 && !ray.in_box(g_.box, depths_[k])) ++k;
        if (k == k1) continue;
        float first[3];
        for (int a = 0; a < 3; ++a) first[a] = static_cast<float>(ray.o[a] + depths_[k] * ray.v[a]);
        bool same = true;
        for (int a = 0; a < 3 && sign == 0; ++a)
          same = same &&
              (moves_[a] ||
               std::bit_cast<uint32_t>(first[a]) ==
                   std::bit_cast<uint32_t>(static_cast<float>(ray.o[a] + depths_[k1 - 1] * ray.v[a])));
        if (!same) {
          probe(col, row, k, k1);
          continue;
        }
        m.evaluated[q] = 1;
        const auto i = static_cast<uint32_t>(batch_.n++);
        batch_.x[i] = first[0], batch_.y[i] = first[1], batch_.z[i] = first[2], steps_[i] = static_cast<int32_t>(k);
        add_owner(col, row, 0, i, i + 1);
      }
    std::vector<Found>& found = flat_found_;
    found.clear();
    if (!finish_probe(field, found)) return false;
    hits += found.size();
    return refine(field, found);
  }

  // The regions of `level` under (r, [k0, k1)), front to back, on `field` (which holds the
  // whole function's bits over the parent's box); `hits` counts the rays they meet. Hits decided
  // here are refined here.
  bool children(const mesh::Field& field, Rect r, uint32_t k0, uint32_t k1, int level, size_t& hits) {
    Scratch& s = scratch_[level];
    split(r, kTile[level], s.tiles);
    s.corners.clear();
    for (const Rect& t : s.tiles) s.corners.push_back(corners(t));
    s.open.clear();
    size_t open = 0;
    for (const Rect& t : s.tiles) s.open.push_back(unhit_count(t)), open += s.open.back() > 0;
    std::vector<Found>& found = s.found;
    found.clear();
    DirectLevel& st = stats_.levels[static_cast<size_t>(level)];
    const bool leaf = level + 1 == kLevels;
    for (uint32_t c0 = k0; c0 < k1 && open > 0; c0 += kChunk[level]) {
      const uint32_t c1 = std::min(k1, c0 + kChunk[level]);
      s.boxes.clear(), s.live.clear(), s.within.clear();
      for (size_t i = 0; i < s.tiles.size(); ++i) {
        if (!s.open[i]) continue;
        mesh::Box3 b;
        bool in;
        if (!region_box(s.corners[i], c0, c1, b, in)) {
          ++st.empty;
          continue;
        }
        s.boxes.push_back(b), s.live.push_back(i), s.within.push_back(in);
      }
      if (s.live.empty()) continue;
      const size_t n = s.live.size();
      s.iv.resize(n), s.locals.resize(n);
      field.bounds_and_locals(
          s.boxes.data(), n, s.iv.data(),
          [&](size_t j, const math::Interval& v) { return level < kOwnTapes && !empty(v) && !full(v, s.within[j]); },
          s.locals.data());
      if (leaf) batch_.clear(), owner_.clear();
      for (size_t j = 0; j < n; ++j) {
        const size_t i = s.live[j];
        const Rect t = s.tiles[i];
        const math::Interval v = s.iv[j];
        if (empty(v)) {
          ++st.empty;
        } else if (full(v, s.within[j])) {
          ++st.full;
          for (uint32_t row = t.r0; row < t.r1; ++row)
            for (uint32_t col = t.c0; col < t.c1; ++col)
              if (step_at(col, row) < 0) step_at(col, row) = int32_t(c0), found.push_back({col, row, int32_t(c0)});
          s.open[i] = 0, --open;
        } else {
          ++st.ambiguous;
          if (leaf) {
            for (uint32_t row = t.r0; row < t.r1; ++row)
              for (uint32_t col = t.c0; col < t.c1; ++col)
                if (step_at(col, row) < 0) probe(col, row, c0, c1, static_cast<uint32_t>(i), s.within[j]);
          } else {
            std::shared_ptr<const mesh::Field> local = std::move(s.locals[j]);
            size_t met = 0;
            if (!descend(local ? *local : field, t, c0, c1, level + 1, met)) return false;
            hits += met;
            if (met && (s.open[i] = unhit_count(t)) == 0) --open;
          }
        }
      }
      if (leaf) {
        size_t before = found.size();
        if (!finish_probe(field, found)) return false;
        for (size_t f = before; f < found.size(); ++f) {
          uint32_t i = found_tile_[f - before];
          if (--s.open[i] == 0) --open;
        }
      }
    }
    hits += found.size();
    return refine(field, found);
  }

  // The in-box points of the ray of (col, row) at steps [k0, k1), to the batch (`within`: the
  // steps are known to lie in the box).
  void probe(uint32_t col, uint32_t row, uint32_t k0, uint32_t k1, uint32_t tile = 0, bool within = false) {
    Ray r;
    g_.ray(col, row, r.o, r.v);
    batch_.reserve(k1 - k0);
    if (steps_.size() < batch_.x.size()) steps_.resize(batch_.x.size());
    Probe pr{col, row, tile, static_cast<uint32_t>(batch_.n), 0};
    for (uint32_t k = k0; k < k1; ++k) {
      const double d = depths_[k];
      float p[3];
      for (int a = 0; a < 3; ++a) p[a] = static_cast<float>(r.o[a] + d * r.v[a]);  // RayGrid::at, rounded
      if (!within && !g_.in_box(p)) continue;
      const size_t i = batch_.n++;
      batch_.x[i] = p[0], batch_.y[i] = p[1], batch_.z[i] = p[2], steps_[i] = static_cast<int32_t>(k);
    }
    pr.end = static_cast<uint32_t>(batch_.n);
    if (pr.end > pr.first) add_owner(pr.col, pr.row, pr.tile, pr.first, pr.end);
  }

  // Field by field: a Probe built whole on the stack and copied stalled on its partial stores.
  void add_owner(uint32_t col, uint32_t row, uint32_t tile, uint32_t first, uint32_t end) {
    owner_.emplace_back();
    Probe& p = owner_.back();
    p.col = col, p.row = row, p.tile = tile, p.first = first, p.end = end;
  }

  // The batch evaluated: each ray's first step inside; found_tile_ the probe's tile of each hit.
  bool finish_probe(const mesh::Field& field, std::vector<Found>& found) {
    if (!batch_.eval(field, err_)) return false;
    stats_.points += batch_.size();
    found_tile_.clear();
    const float* f = batch_.f.data();
    for (const Probe& o : owner_) {
      uint32_t i = o.first;
      while (i < o.end && !inside(f[i])) ++i;
      if (i == o.end) continue;
      step_at(o.col, o.row) = steps_[i];
      Found h{o.col, o.row, steps_[i]};
      h.at = f[i], h.has_at = true;
      if (i > o.first && steps_[i - 1] == steps_[i] - 1) h.before = f[i - 1], h.has_before = true;
      found.push_back(h), found_tile_.push_back(o.tile);
    }
    return true;
  }

  // Each hit between its step and the one before, closed in by regula falsi (Illinois), on `field`:
  // the depth, the point and the normal. A ray that comes into the box inside the shape meets the
  // box's face there.
  bool refine(const mesh::Field& field, const std::vector<Found>& found);

  // Minus the gradient by central differences h_ either side, on `field` (whose box holds them),
  // unit; facing the ray where the function has no slope there. The analytic gradient's tape
  // would have to be simplified per region as well, which costs more than the six points.
  bool normals(const mesh::Field& field, const std::vector<size_t>& which, const std::vector<Found>& found);

  const mesh::Field& root_;
  const RayGrid& g_;
  Hits& out_;
  // Per level, what children() keeps between its layers (a call uses its own level's only).
  struct Scratch {
    std::vector<Rect> tiles;
    std::vector<Corners> corners;  // per tile
    std::vector<Found> found;      // the hits decided at this level
    std::vector<uint32_t> open;  // per tile: its rays still to meet
    std::vector<char> within;    // per live box: inside the shape's box
    std::vector<mesh::Box3> boxes;
    std::vector<size_t> live;  // the tiles bounded in this layer
    std::vector<math::Interval> iv;
    std::vector<std::shared_ptr<const mesh::Field>> locals;
  };
  Scratch scratch_[kLevels];
  std::vector<double> depths_;  // depth(k), once
  float h_ = 0;                 // the normals' differences, half the span
  Batch batch_;
  std::vector<Probe> owner_;          // per ray of a probe's batch
  std::vector<int32_t> steps_;        // per point of a probe's batch: its step
  // refine()'s buffers, reused: the threads share one malloc arena, and allocating them afresh
  // for every region put them behind its lock.
  std::vector<Bracket> brackets_;
  std::vector<size_t> want_, active_, smooth_;
  std::vector<float> ends_;
  std::vector<double> mid_;
  std::vector<uint32_t> found_tile_;  // per hit of the last probe: its tile
  std::vector<Ray> rays_;             // per hit being refined
  std::vector<Found> flat_found_;     // flat()'s hits
  std::map<std::array<uint32_t, 4>, Memo> memo_;  // per tile of the unit at hand (c0, r0, c1, r1)
  bool moves_[3] = {};                // per axis: whether some ray moves along it
  std::vector<std::array<float, 3>> points_;  // per hit refined: its point
};

bool Tracer::refine(const mesh::Field& field, const std::vector<Found>& found) {
  if (found.empty()) return true;
  const size_t n = found.size();
  std::vector<Bracket>& br = brackets_;
  br.assign(n, Bracket{});
  rays_.resize(n);
  Batch& b = batch_;
  b.clear();
  b.reserve(2 * n);
  std::vector<size_t>& want = want_;  // per batch point: which end (2 i: lo, 2 i + 1: hi) it gives
  want.clear();
  for (size_t i = 0; i < n; ++i) {
    const Found& h = found[i];
    Bracket& k = br[i];
    Ray& r = rays_[i];
    g_.ray(h.col, h.row, r.o, r.v);
    k.hi = depths_[static_cast<size_t>(h.step)];
    k.lo = h.step > 0 ? depths_[static_cast<size_t>(h.step - 1)] : k.hi;
    double enter;
    int face;
    if (h.step == 0 || !r.in_box(g_.box, k.lo)) {  // came into the box since the step before
      if (g_.entry(h.col, h.row, enter, face) && enter > k.lo && enter <= k.hi) k.lo = enter, k.face = face;
      else if (h.step == 0) k.lo = k.hi, k.face = g_.entry(h.col, h.row, enter, face) ? face : 4;
    }
    // The ends' values: from the probe where it has them, else evaluated now.
    if (!h.has_before || k.lo != depths_[static_cast<size_t>(h.step - 1)])
      b.put(r, k.lo, g_.box), want.push_back(2 * i);
    if (!h.has_at) b.put(r, k.hi, g_.box), want.push_back(2 * i + 1);
  }
  if (!b.eval(field, err_)) return false;
  stats_.refines += b.size();
  std::vector<float>& ends = ends_;
  ends.resize(2 * n);
  for (size_t i = 0; i < n; ++i) ends[2 * i] = found[i].before, ends[2 * i + 1] = found[i].at;
  for (size_t j = 0; j < want.size(); ++j) ends[want[j]] = b.f[j];
  const double tol = std::max(std::fabs(g_.near), std::fabs(g_.far)) * 0x1p-22;
  std::vector<size_t>& active = active_;  // the brackets still closing in
  active.clear();
  for (size_t i = 0; i < n; ++i) {
    Bracket& k = br[i];
    float flo = ends[2 * i], fhi = ends[2 * i + 1];
    if (k.face >= 0 && inside(flo)) k.hi = k.lo, k.done = true;  // the box's face closes the solid here
    else k.face = -1;
    k.wlo = flo, k.whi = fhi;
    if (!k.done) active.push_back(i);
  }
  std::vector<double>& mid = mid_;
  for (int it = 0; it < kRefineSteps && !active.empty(); ++it) {
    mid.clear(), b.clear();
    size_t kept = 0;
    for (size_t i : active) {
      Bracket& k = br[i];
      if (k.hi - k.lo <= tol) continue;  // a bracket left once stays as it is
      double m = 0.5 * (k.lo + k.hi);
      if (std::isfinite(k.wlo) && std::isfinite(k.whi) && k.wlo < 0 && k.whi >= 0) {
        double f = k.lo + (k.hi - k.lo) * (k.wlo / (k.wlo - k.whi));
        // Brent's rule: at least tol in from either end, so a root met (almost) exactly at one
        // end closes the bracket from the other side next (a plane's root, f exactly 0 there, left
        // regula falsi nothing but bisection: twelve steps, now two).
        if (k.hi - k.lo > 2 * tol) f = std::clamp(f, k.lo + tol, k.hi - tol);
        if (f > k.lo && f < k.hi) m = f;
      }
      if (!(m > k.lo && m < k.hi)) continue;  // no double between: as close as it gets
      b.put(rays_[i], m, g_.box), active[kept++] = i, mid.push_back(m);
    }
    active.resize(kept);
    if (active.empty()) break;
    if (!b.eval(field, err_)) return false;
    stats_.refines += b.size();
    for (size_t j = 0; j < active.size(); ++j) {
      Bracket& k = br[active[j]];
      if (inside(b.f[j])) {
        k.hi = mid[j], k.whi = b.f[j];
        if (k.kept == 1) k.wlo *= 0.5;
        k.kept = 1;
      } else {
        k.lo = mid[j], k.wlo = b.f[j];
        if (k.kept == -1) k.whi *= 0.5;
        k.kept = -1;
      }
    }
  }
  std::vector<size_t>& smooth = smooth_;
  smooth.clear();
  points_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Found& h = found[i];
    size_t at = size_t(h.row) * g_.w + h.col;
    std::array<float, 3>& p = points_[i];
    rays_[i].at(br[i].hi, g_.box, p.data());
    out_.depth[at] = static_cast<float>(br[i].hi);
    if (!out_.point.empty()) out_.point[at] = p;
    if (br[i].face >= 0) {
      std::array<float, 3> nrm{0, 0, 0};
      nrm[static_cast<size_t>(br[i].face / 2)] = br[i].face % 2 ? 1.0f : -1.0f;
      out_.normal[at] = nrm;
    } else {
      smooth.push_back(i);
    }
  }
  stats_.hits += n;
  return normals(field, smooth, found);
}

bool Tracer::normals(const mesh::Field& field, const std::vector<size_t>& which, const std::vector<Found>& found) {
  if (which.empty()) return true;
  auto at = [&](size_t j) { return size_t(found[which[j]].row) * g_.w + found[which[j]].col; };
  auto set = [&](size_t j, double gx, double gy, double gz) {
    double l = std::sqrt(gx * gx + gy * gy + gz * gz);
    if (!(l > 0) || !std::isfinite(l)) return false;
    out_.normal[at(j)] = {static_cast<float>(-gx / l), static_cast<float>(-gy / l), static_cast<float>(-gz / l)};
    return true;
  };
  Batch& d = batch_;
  d.clear();
  d.reserve(6 * which.size());
  for (size_t j = 0; j < which.size(); ++j) {
    const auto& q = points_[which[j]];
    for (int a = 0; a < 3; ++a)
      for (float s : {-h_, h_}) {
        float p[3] = {q[0], q[1], q[2]};
        p[a] += s;
        d.x[d.n] = p[0], d.y[d.n] = p[1], d.z[d.n] = p[2], ++d.n;
      }
  }
  if (!d.eval(field, err_)) return false;
  stats_.refines += d.size();
  for (size_t j = 0; j < which.size(); ++j) {
    const float* f = &d.f[6 * j];
    if (set(j, f[1] - f[0], f[3] - f[2], f[5] - f[4])) {
      ++stats_.gradients;
      continue;
    }
    const Ray& r = rays_[which[j]];
    set(j, r.v[0], r.v[1], r.v[2]);  // no slope there: facing the ray
  }
  return true;
}

void merge(DirectStats& into, const DirectStats& part) {
  for (size_t l = 0; l < into.levels.size(); ++l) {
    into.levels[l].empty += part.levels[l].empty;
    into.levels[l].full += part.levels[l].full;
    into.levels[l].ambiguous += part.levels[l].ambiguous;
  }
  into.points += part.points, into.refines += part.refines, into.gradients += part.gradients;
  into.hits += part.hits, into.constant += part.constant;
}

}  // namespace

bool trace(const mesh::Field& f, const RayGrid& g, const DirectOptions& o, Hits& out, DirectStats& stats,
           backends::RuntimeError& err) {
  const size_t n = size_t(g.w) * g.h;
  out.depth.assign(n, std::numeric_limits<float>::infinity());
  if (o.points) out.point.assign(n, {0, 0, 0});
  else out.point.clear(), out.point.shrink_to_fit();
  out.normal.assign(n, {0, 0, 0});
  // A sample left out is marked met (beyond every step) while tracing, so no region waits for it.
  constexpr int32_t kLeftOut = INT32_MAX;
  out.step.assign(n, -1);
  if (o.wanted)
    for (size_t i = 0; i < n; ++i)
      if (!(*o.wanted)[i]) out.step[i] = kLeftOut;
  stats = {};
  for (int l = 0; l < kLevels; ++l) stats.levels.push_back({kTile[l], kChunk[l], 0, 0, 0});
  const bool prune = o.prune && f.can_bound();
  if (!prune) f.expect_points(uint64_t(n) * g.steps / 4);
  std::vector<Rect> tiles = split({0, 0, g.w, g.h}, prune ? kTile[0] : 16);
  int parts = static_cast<int>(std::max(1u, o.threads));
  std::vector<std::unique_ptr<Tracer>> tracers;
  for (int p = 0; p < parts; ++p) tracers.push_back(std::make_unique<Tracer>(f, g, out));
  // Pruned, the top level's regions are bounded first, and the work is shared out in the next
  // level's tiles (16 under each top tile: two threads stay busy to the end); each tile writes
  // only its own samples, so the hits do not depend on the schedule.
  std::vector<Tracer::Top> top(prune ? tiles.size() : 0);
  struct Unit {
    Rect r;
    size_t top;
  };
  std::vector<Unit> units;
  for (size_t i = 0; i < tiles.size(); ++i)
    if (prune)
      for (const Rect& u : split(tiles[i], kTile[1])) units.push_back({u, i});
    else units.push_back({tiles[i], 0});
  std::atomic<bool> failed{false};
  auto share = [&](size_t count, auto job) {
    std::atomic<size_t> next{0};
    return support::run_parts(parts, [&](int p) {
      Tracer& t = *tracers[static_cast<size_t>(p)];
      for (size_t i; !failed && (i = next.fetch_add(1)) < count;)
        if (!job(t, i)) return failed = true, false;
      return true;
    });
  };
  bool ok = share(top.size(), [&](Tracer& t, size_t i) { return t.bound_top(tiles[i], top[i]), true; });
  if (o.progress) o.progress->set_units(units.size());
  ok = ok && share(units.size(), [&](Tracer& t, size_t i) {
         bool done = prune ? t.unit(units[i].r, top[units[i].top]) : t.dense(units[i].r);
         if (done && o.progress) o.progress->advance(1);
         return done;
       });
  stats.pruned = prune;
  for (const auto& t : tracers) merge(stats, t->stats_);
  for (const auto& t : tracers)
    if (!t->err_.message.empty()) {
      err = t->err_;
      break;
    }
  for (int32_t& s : out.step)
    if (s == kLeftOut) s = -1;
  return ok && !failed;
}

}  // namespace fscript::render
