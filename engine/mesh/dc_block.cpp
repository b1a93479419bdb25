// One block of dual contouring: its samples (pruned by the brick map), sign-change edges, Hermite data
// (batched evaluation), and the sheets of its cells; and the grid of blocks that answers for signs.
#include "engine/mesh/dc_block.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>

#include "engine/mesh/dc_tubes.h"

namespace fscript::mesh {

namespace {

constexpr int kRefineSteps = 4;    // regula falsi steps per crossing, at most
constexpr double kSettled = 1e-4;  // and fewer once it moves less than this share of the edge
// The central differences' step, in cells: a crossing closer than this to a sharp edge gets a normal
// blended from both faces (the QEF then misplaces the edge's vertices), so small, but large enough
// that float rounding of the samples stays far below the differences.
constexpr double kProbe = 0.01;
constexpr size_t kSamples = static_cast<size_t>(kBlockSamples) * kBlockSamples * kBlockSamples;
constexpr size_t kCells = static_cast<size_t>(kBlock) * kBlock * kBlock;

// The set bits of v, inline: the baseline instruction set has no popcnt, and __builtin_popcount
// became a library call per row.
int bit_count(uint32_t v) {
  v -= (v >> 1) & 0x55555555u;
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  return static_cast<int>((((v + (v >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24);
}

// Scratch arrays for one batch of points, reused per thread: they only grow, and `n` says how many
// points the batch holds (shrinking and growing them again zero-filled them at every step). A batch
// is either points (add) or grid rows (add_row), which run through Field::eval_rows.
struct Batch {
  struct Row {
    const float* xs;
    size_t count;
    float y, z;
  };
  std::vector<float> x, y, z, out;
  std::vector<Row> rows;
  size_t n = 0;
  void clear() { n = 0, rows.clear(); }
  void resize(size_t m) {
    if (x.size() < m) x.resize(m), y.resize(m), z.resize(m);
    n = m;
  }
  void set(size_t i, double px, double py, double pz) { x[i] = float(px), y[i] = float(py), z[i] = float(pz); }
  void add(double px, double py, double pz) {
    if (n == x.size()) x.resize(2 * n + 64), y.resize(2 * n + 64), z.resize(2 * n + 64);
    set(n++, px, py, pz);
  }
  // `count` points of one row: x from xs (alive until run()), y and z fixed.
  void add_row(const float* xs, size_t count, float py, float pz) {
    rows.push_back({xs, count, py, pz});
    n += count;
  }
  bool run(const Field& f, backends::RuntimeError& err) {
    if (out.size() < n) out.resize(std::max(n, x.size()));
    EvalTimer timed;
    if (rows.empty()) return n == 0 || f.eval(x.data(), y.data(), z.data(), n, out.data(), err);
    // Rows over the same run of x values go as one eval_rows call (a block's bricks cut its rows
    // into a few distinct runs), their results copied back to each row's place.
    // Grouped in one pass, then laid out group by group (a counting sort): a block has a handful of
    // distinct runs (searched linearly) and hundreds of rows.
    thread_local std::vector<size_t> at, group_of, first_row, start, sorted;
    thread_local std::vector<float> group_out;
    at.resize(rows.size()), group_of.resize(rows.size()), sorted.resize(rows.size());
    first_row.clear(), start.assign(1, 0);
    for (size_t r = 0, o = 0; r < rows.size(); o += rows[r].count, ++r) {
      at[r] = o;
      size_t gr = 0;
      while (gr < first_row.size() &&
             !(rows[first_row[gr]].xs == rows[r].xs && rows[first_row[gr]].count == rows[r].count))
        ++gr;
      if (gr == first_row.size()) first_row.push_back(r), start.push_back(0);
      group_of[r] = gr, ++start[gr + 1];
    }
    for (size_t gr = 1; gr < start.size(); ++gr) start[gr] += start[gr - 1];
    for (size_t r = 0; r < rows.size(); ++r) sorted[start[group_of[r]]++] = r;  // start[gr]: now its end
    for (size_t gr = 0, from = 0; gr < first_row.size(); from = start[gr], ++gr) {
      const size_t r = first_row[gr], m = start[gr] - from, count = rows[r].count;
      const size_t* members = sorted.data() + from;
      if (y.size() < m) y.resize(m), z.resize(m);
      for (size_t i = 0; i < m; ++i) y[i] = rows[members[i]].y, z[i] = rows[members[i]].z;
      group_out.resize(m * count);
      if (!f.eval_rows(rows[r].xs, count, y.data(), z.data(), m, group_out.data(), err)) return false;
      for (size_t i = 0; i < m; ++i) std::copy_n(group_out.data() + i * count, count, out.data() + at[members[i]]);
    }
    return true;
  }
};

Batch& scratch() {
  thread_local Batch b;
  return b;
}

// Every sign-change edge between the block's samples, by lower sample then axis: each row of
// samples is a bit mask of its inside samples, compared with its neighbours along x, y and z.
void find_crossings(Block& b) {
  b.xs.clear();
  auto& rows = b.rows;
  std::fill(&rows[0][0], &rows[0][0] + kBlockSamples * kBlockSamples, 0u);
  const uint32_t in_row = (2u << b.m[0]) - 1;  // samples 0 .. m[0]
  for (int k = 0; k <= b.m[2]; ++k)
    for (int j = 0; j <= b.m[1]; ++j) {  // the row's samples past m[0] are padding, masked off
      const float* f = &b.f[Block::sample(0, j, k)];
      uint32_t r = static_cast<uint32_t>(f[kBlock] > 0) << kBlock;
#if defined(__SSE2__)
      for (int i = 0; i < kBlock; i += 4)  // four samples per compare
        r |= static_cast<uint32_t>(_mm_movemask_ps(_mm_cmpgt_ps(_mm_loadu_ps(f + i), _mm_setzero_ps()))) << i;
#else
      for (int i = 0; i < kBlock; ++i) r |= static_cast<uint32_t>(f[i] > 0) << i;
#endif
      rows[k][j] = r & in_row;
    }
  const uint32_t along_x = (1u << b.m[0]) - 1;
  auto changes = [&](int j, int k, uint32_t change[3]) {
    uint32_t r = rows[k][j];
    change[0] = (r ^ (r >> 1)) & along_x, change[1] = j < b.m[1] ? r ^ rows[k][j + 1] : 0;
    change[2] = k < b.m[2] ? r ^ rows[k + 1][j] : 0;
  };
  // Counted first, so the list takes exactly its room: the blocks' data is most of a big mesh's
  // memory, and memory touched for the first time is dear on this kind of virtual machine (0.13 ms a
  // megabyte when the host has it at hand, up to 1 ms when not: docs/performance.md).
  size_t count = 0;
  for (int k = 0; k <= b.m[2]; ++k)
    for (int j = 0; j <= b.m[1]; ++j) {
      uint32_t change[3];
      changes(j, k, change);
      count += static_cast<size_t>(bit_count(change[0]) + bit_count(change[1]) + bit_count(change[2]));
    }
  b.xs.reserve(count);
  for (int k = 0; k <= b.m[2]; ++k)
    for (int j = 0; j <= b.m[1]; ++j) {
      uint32_t r = rows[k][j], change[3];
      changes(j, k, change);
      for (uint32_t any = change[0] | change[1] | change[2]; any; any &= any - 1) {
        int i = __builtin_ctz(any);
        for (int a = 0; a < 3; ++a)
          if (change[a] >> i & 1)
            b.xs.push_back(Crossing{{uint8_t(i), uint8_t(j), uint8_t(k)}, uint8_t(a), (r >> i & 1) != 0});
      }
    }
}

// Whether the block counts sample l as its own (in the figures): the samples on its upper faces
// are the next block's, or padding.
bool owned(const int l[3]) { return l[0] < kBlock && l[1] < kBlock && l[2] < kBlock; }

// The values at the ends of the crossing edges that lie in decided bricks. An end whose value
// contradicts its brick's bound makes the block unsound (the caller samples densely instead).
bool exact_ends(const Field& f, const Lattice& g, Block& b, backends::RuntimeError& err) {
  std::vector<size_t> where;
  Batch& pts = scratch();
  pts.clear();
  for (const Crossing& c : b.xs)
    for (int end = 0; end < 2; ++end) {
      int l[3] = {c.l[0], c.l[1], c.l[2]};
      l[c.axis] += end;
      size_t at = Block::sample(l[0], l[1], l[2]);
      if (b.decided[at] != 1) continue;
      b.decided[at] = 2;
      where.push_back(at);
      b.evaluated += owned(l);
      pts.add(g.coord(0, b.s0[0] + l[0]), g.coord(1, b.s0[1] + l[1]), g.coord(2, b.s0[2] + l[2]));
    }
  if (!pts.run(f, err)) return false;
  for (size_t q = 0; q < where.size(); ++q) {
    b.sound = b.sound && (pts.out[q] > 0) == (b.f[where[q]] > 0);
    b.f[where[q]] = pts.out[q];
  }
  return true;
}

// One component of the gradient at a point on the surface (f = 0 there) from its probes `step`
// either side: central where both are defined, one-sided where one is, 0 where neither.
double gradient(float plus, float minus, double step) {
  bool p = std::isfinite(plus), m = std::isfinite(minus);
  if (p && m) return (double(plus) - minus) / (2 * step);
  return p ? plus / step : m ? -minus / step : 0.0;
}

}  // namespace

BlockGrid::BlockGrid(const Lattice& g, std::vector<int32_t> slots, std::vector<Block> blocks)
    : g_(g), slot_(std::move(slots)), blocks_(std::move(blocks)) {
  for (int a = 0; a < 3; ++a) nb_[a] = blocks_along(g, a);
}

BlockGrid::BlockGrid(const Lattice& g, const BrickMap* bricks) : g_(g) {
  for (int a = 0; a < 3; ++a) nb_[a] = blocks_along(g, a);
  slot_.assign(static_cast<size_t>(nb_[0]) * nb_[1] * nb_[2], kAllOutside);
  blocks_.reserve(slot_.size());  // virtual until used: no copies as it grows
  size_t at = 0;
  for (int k = 0; k < nb_[2]; ++k)
    for (int j = 0; j < nb_[1]; ++j)
      for (int i = 0; i < nb_[0]; ++i, ++at) {
        Block b;
        b.b[0] = i, b.b[1] = j, b.b[2] = k;
        bool in = false, out = false;
        int lo[3], hi[3];  // its samples' lattice range, and the bricks that hold them
        for (int a = 0; a < 3; ++a) {
          b.s0[a] = b.b[a] * kBlock - 1;
          b.m[a] = std::min(kBlock, g.n[a] + 1 - b.b[a] * kBlock);
          out = out || b.s0[a] < 0 || b.s0[a] + b.m[a] >= g.n[a];
          lo[a] = std::max(0, b.s0[a]) / BrickMap::kBrick,
          hi[a] = std::min(g.n[a] - 1, b.s0[a] + b.m[a]) / BrickMap::kBrick;
        }
        bool open = !bricks;
        for (int bk = lo[2]; bk <= hi[2] && !open; ++bk)
          for (int bj = lo[1]; bj <= hi[1] && !open; ++bj)
            for (int bi = lo[0]; bi <= hi[0] && !open; ++bi) {
              BrickClass c = bricks->at(bi, bj, bk);
              open = c == BrickClass::Open;
              (c == BrickClass::Inside ? in : out) = true;
            }
        if (!open && !(in && out)) {
          slot_[at] = in ? kAllInside : kAllOutside;
          continue;
        }
        slot_[at] = static_cast<int32_t>(blocks_.size());
        blocks_.push_back(std::move(b));
      }
}

const Block* BlockGrid::at(int bi, int bj, int bk) const {
  if (bi < 0 || bj < 0 || bk < 0 || bi >= nb_[0] || bj >= nb_[1] || bk >= nb_[2]) return nullptr;
  int32_t s = slot_[(static_cast<size_t>(bk) * nb_[1] + static_cast<size_t>(bj)) * nb_[0] + static_cast<size_t>(bi)];
  return s >= 0 ? &blocks_[static_cast<size_t>(s)] : nullptr;
}

int32_t BlockGrid::slot_at(int bi, int bj, int bk) const {
  if (bi < 0 || bj < 0 || bk < 0 || bi >= nb_[0] || bj >= nb_[1] || bk >= nb_[2]) return kAllOutside;
  return slot_[(static_cast<size_t>(bk) * nb_[1] + static_cast<size_t>(bj)) * nb_[0] + static_cast<size_t>(bi)];
}

bool BlockGrid::inside(int i, int j, int k) const {
  int s[3] = {i, j, k}, b[3], l[3];
  if (g_.padding(s)) return false;
  for (int a = 0; a < 3; ++a) {  // a sample on a block face: the lower block's, or the last block's
    b[a] = std::min((s[a] + 1) / kBlock, nb_[a] - 1);
    l[a] = s[a] + 1 - b[a] * kBlock;
  }
  int32_t slot =
      slot_[(static_cast<size_t>(b[2]) * nb_[1] + static_cast<size_t>(b[1])) * nb_[0] + static_cast<size_t>(b[0])];
  if (slot < 0) return slot == kAllInside;
  return blocks_[static_cast<size_t>(slot)].inside(l[0], l[1], l[2]);
}

unsigned BlockGrid::mask(const int c[3]) const {
  unsigned m = 0;
  for (int q = 0; q < 8; ++q)
    m |= static_cast<unsigned>(inside(c[0] + (q & 1), c[1] + (q >> 1 & 1), c[2] + (q >> 2 & 1))) << q;
  return m;
}

void cells_of(const Crossing& c, int out[4][3]) {
  int u = kNextAxis[c.axis], w = kNextAxis[u];
  for (int q = 0; q < 4; ++q) out[q][0] = c.l[0], out[q][1] = c.l[1], out[q][2] = c.l[2];
  --out[1][u], --out[2][u], --out[2][w], --out[3][w];  // winding (0, 0), (1, 0), (1, 1), (0, 1) below
}

int Block::key(const CellInfo& c, int in, int out) {
  if (c.flips & kOneSheet) return 0;
  int k = sheet_key(c.mask, kuhn_flips(c.mask), in, out);
  if (!(c.flips & kTubes) && !joins_middle(c.mask)) return k;
  return k + 64 * cell_cuts(c.mask, c.flips & kTubes).piece[static_cast<size_t>(cube_edge(in, out))];
}

uint32_t Block::sheet(const CellInfo& c, int in, int out) const {
  if (c.flips & kOneSheet) return c.first;
  int k = key(c, in, out);
  uint32_t s = c.first;
  while (s != kNone && sheets[s].key != k) s = sheets[s].next();
  return s;
}

size_t Block::rim_index(int i, int j, int k) {
  constexpr int S = kBlock, L = kBlock - 1;
  if (k == L) return static_cast<size_t>(j * S + i);
  if (j == L) return static_cast<size_t>(S * S + k * S + i);
  return static_cast<size_t>(S * S + L * S + k * L + j);
}

namespace {
std::vector<Block::CellInfo>& cell_buffer() {
  thread_local std::vector<Block::CellInfo> buffer;
  return buffer;
}
}  // namespace

void Block::keep_rim() {
  constexpr int L = kBlock - 1;
  rim.clear();
  auto keep = [&](int i, int j, int k) {
    if (i >= m[0] || j >= m[1] || k >= m[2]) return;
    const CellInfo& c = cells[cell(i, j, k)];
    if (c.first != kNone) rim.push_back({static_cast<uint16_t>(rim_index(i, j, k)), c.mask, c.flips, c.first});
  };
  for (int a = 0; a < kBlock; ++a)
    for (int c = 0; c < kBlock; ++c) keep(c, a, L), keep(c, L, a), keep(L, c, a);  // the faces k, j and i = L
  std::sort(rim.begin(), rim.end(), [](const RimCell& x, const RimCell& y) { return x.at < y.at; });
  rim.erase(std::unique(rim.begin(), rim.end(), [](const RimCell& x, const RimCell& y) { return x.at == y.at; }),
            rim.end());
  rim.shrink_to_fit();
  for (const Sheet& s : sheets) cells[s.cell] = CellInfo{};  // every cell written has a sheet
  cells.swap(cell_buffer());
}

Block::CellInfo Block::rim_cell(int i, int j, int k) const {
  auto at = static_cast<uint16_t>(rim_index(i, j, k));
  auto it = std::lower_bound(rim.begin(), rim.end(), at, [](const RimCell& c, uint16_t v) { return c.at < v; });
  CellInfo c;
  if (it != rim.end() && it->at == at) c.mask = it->mask, c.flips = it->flips, c.first = it->first;
  return c;
}

bool sample_block(const Field& f, const BrickMap* bricks, const Lattice& g, Block& b, backends::RuntimeError& err) {
  constexpr int B = BrickMap::kBrick;
  // The samples live in buffers of this thread while the block is sampled: fresh ones per block
  // spent a fifth of the sampling in page faults.
  thread_local std::vector<float> samples;
  thread_local std::vector<uint8_t> flags;
  struct Lend {
    Block& b;
    Lend(Block& blk) : b(blk) { b.f.swap(samples), b.decided.swap(flags); }
    ~Lend() { b.f.swap(samples), b.decided.swap(flags); }
  } lend(b);
  b.f.resize(kSamples);
  float* f0 = b.f.data();
  for (size_t q = 0; q < kSamples; ++q)
    f0[q] = -1.0f;  // the padding's value (a plain loop: vector::assign's is not vectorized)
  b.decided.assign(kSamples, 0);
  b.evaluated = 0;
  b.sound = true;
  Batch& pts = scratch();
  pts.clear();
  struct Run {
    size_t at, n;  // samples at .. at + n - 1 of the block, evaluated as one run of the batch
  };
  thread_local std::vector<Run> runs;
  runs.clear();
  float xs[kBlockSamples];
  for (int i = 0; i <= b.m[0]; ++i) xs[i] = float(g.coord(0, b.s0[0] + i));
  // The bricks cut every row at the same places: the runs along x (at most three bricks a row of
  // 17 samples) found once per block, not per row.
  struct XRun {
    int first, last, brick;
  };
  XRun xruns[kBlockSamples];
  int nx = 0;
  for (int i = b.s0[0] < 0 ? 1 : 0, end = std::min(b.m[0], g.n[0] - 1 - b.s0[0]); i <= end;) {
    int si = b.s0[0] + i, run_end = std::min(end, i + B - 1 - si % B);
    xruns[nx++] = {i, run_end, si / B};
    i = run_end + 1;
  }
  for (int k = 0; k <= b.m[2]; ++k)
    for (int j = 0; j <= b.m[1]; ++j) {
      int sj = b.s0[1] + j, sk = b.s0[2] + k;
      if (sj < 0 || sj >= g.n[1] || sk < 0 || sk >= g.n[2]) continue;
      float y = float(g.coord(1, sj)), z = float(g.coord(2, sk));
      for (int r = 0; r < nx; ++r) {  // a brick's run of the row at a time
        const int i = xruns[r].first, run_end = xruns[r].last;
        BrickClass c = bricks ? bricks->at(xruns[r].brick, sj / B, sk / B) : BrickClass::Open;
        size_t at = Block::sample(i, j, k), n = static_cast<size_t>(run_end - i + 1);
        if (c == BrickClass::Open) {
          if (!runs.empty() && runs.back().at + runs.back().n == at) runs.back().n += n;  // the row's run goes on
          else runs.push_back({at, n});
          pts.add_row(xs + i, n, y, z);
          if (j < kBlock && k < kBlock)
            b.evaluated += static_cast<size_t>(std::max(0, std::min(run_end, kBlock - 1) - i + 1));
        } else {
          std::fill_n(b.f.begin() + static_cast<std::ptrdiff_t>(at), n, c == BrickClass::Inside ? 1.0f : -1.0f);
          std::fill_n(b.decided.begin() + static_cast<std::ptrdiff_t>(at), n, uint8_t{1});
        }
      }
    }
  // The field simplified for the block's region as the brick map descended (its box holds the
  // block's samples: they start one step below the region).
  static_assert(BrickMap::kLocal == kBlock, "a block is a region of the brick map's local fields");
  if (bricks) b.local = bricks->local_at(b.b[0], b.b[1], b.b[2]);
  if (!pts.run(b.field(f), err)) return false;
  const float* out = pts.out.data();
  for (const Run& r : runs) std::copy(out, out + r.n, b.f.begin() + static_cast<std::ptrdiff_t>(r.at)), out += r.n;
  find_crossings(b);
  bool ok = exact_ends(b.field(f), g, b, err);
  const size_t stride[3] = {1, kBlockSamples, static_cast<size_t>(kBlockSamples) * kBlockSamples};
  b.ends.resize(b.xs.size());
  for (size_t e = 0; e < b.xs.size(); ++e) {
    size_t q = Block::sample(b.xs[e].l[0], b.xs[e].l[1], b.xs[e].l[2]);
    b.ends[e] = {b.f[q], b.f[q + stride[b.xs[e].axis]]};
  }
  if (b.xs.empty()) b.local.reset();  // nothing more to evaluate here
  return ok;  // the signs stay in rows
}

namespace {

// The block's edges under refinement, and their crossings (scratch arrays reused per thread).
struct Edges {
  std::vector<size_t> real, active;               // crossings on real edges (not into the padding)
  std::vector<size_t> rest;                       // of those, the ones the first step did not settle
  std::vector<double> lo_t, hi_t, lo_f, hi_f;     // bracket along the edge (t in [0, 1]) and f there
  std::vector<double> t, v;                       // the crossing, and f there
  std::vector<std::array<double, 3>> at;          // per crossing: the edge's lower end, then the crossing
  std::vector<float> grad;                        // f and its gradient per crossing, four arrays of n
  // Where the chord through the bracket's ends crosses zero (bisection where f is undefined).
  double false_position(size_t r) const {
    double d = lo_f[r] - hi_f[r];
    return d != 0 && std::isfinite(d) ? lo_t[r] + (hi_t[r] - lo_t[r]) * lo_f[r] / d : 0.5 * (lo_t[r] + hi_t[r]);
  }
  // The point of crossing r's edge at t (0: its lower end).
  std::array<double, 3> point(const Block& b, const Lattice& g, size_t r, double at_t) const {
    std::array<double, 3> p = at[real[r]];
    int a = b.xs[real[r]].axis;
    p[a] += at_t * g.h[a];
    return p;
  }
  // f = value at t for crossing r: the end of the bracket with its sign moves there.
  void narrow(size_t r, double value) {
    v[r] = value;
    bool same_as_lo = (value > 0) == (lo_f[r] > 0);
    (same_as_lo ? lo_t[r] : hi_t[r]) = t[r];
    (same_as_lo ? lo_f[r] : hi_f[r]) = value;
  }
};

// The normal at crossing r from its probes (6 r .. 6 r + 5 in `out`); false when there is none.
bool probed_normal(const float* out, const Lattice& g, double normal[3]) {
  for (int a = 0; a < 3; ++a) normal[a] = -gradient(out[2 * a], out[2 * a + 1], kProbe * g.h[a]);
  return std::abs(normal[0]) + std::abs(normal[1]) + std::abs(normal[2]) > 0;
}

// Minus the gradient in o[1..3] at q, when it is finite and not zero.
bool gradient_normal(float* const o[4], size_t q, double normal[3]) {
  for (int a = 0; a < 3; ++a) normal[a] = -double(o[1 + a][q]);
  return std::isfinite(normal[0]) && std::isfinite(normal[1]) && std::isfinite(normal[2]) &&
      std::abs(normal[0]) + std::abs(normal[1]) + std::abs(normal[2]) > 0;
}

// f and its gradient at the points of pts (the field has one), into E.grad.
bool eval_gradient(const Field& f, Batch& pts, size_t n, Edges& E, float* o[4], backends::RuntimeError& err) {
  E.grad.resize(4 * n);
  for (int k = 0; k < 4; ++k) o[k] = E.grad.data() + k * n;
  EvalTimer timed;
  return f.eval_gradient(pts.x.data(), pts.y.data(), pts.z.data(), n, o, err);
}

// The first step of a field with a gradient: f and its gradient at the chord's zero, then one
// Newton step along the edge from there. Where that step stays in the bracket and moves less than
// kNewtonReach of the edge, the crossing is its end and the normal the gradient, for one evaluation
// (regula falsi took two or three, and the normal one more); the others go on to E.rest.
bool newton(const Field& f, const Lattice& g, Block& b, Edges& E, std::vector<Plane>& planes,
            backends::RuntimeError& err) {
  constexpr double kNewtonReach = 0.05;
  Batch& pts = scratch();
  const size_t n = E.real.size();
  pts.clear();
  pts.resize(n);
  for (size_t r = 0; r < n; ++r) {
    E.t[r] = E.false_position(r);
    std::array<double, 3> p = E.point(b, g, r, E.t[r]);
    pts.set(r, p[0], p[1], p[2]);
  }
  float* o[4];
  if (!eval_gradient(f, pts, n, E, o, err)) return false;
  E.rest.clear();
  for (size_t r = 0; r < n; ++r) {
    E.narrow(r, o[0][r]);
    const int a = b.xs[E.real[r]].axis;
    double normal[3], slope = double(o[1 + a][r]) * g.h[a];  // df/dt along the edge
    double next = E.v[r] == 0 ? E.t[r] : E.t[r] - E.v[r] / slope;
    if (!gradient_normal(o, r, normal) || !std::isfinite(next) || std::abs(next - E.t[r]) > kNewtonReach ||
        next < E.lo_t[r] || next > E.hi_t[r]) {
      E.rest.push_back(r);
      continue;
    }
    E.t[r] = next;
    E.at[E.real[r]] = E.point(b, g, r, next);
    planes[E.real[r]] = Qef::plane(E.at[E.real[r]].data(), normal);
  }
  b.gradient_normals += static_cast<uint32_t>(n - E.rest.size());
  return true;
}

// Normals of the crossings E.rest: minus the field's own gradient where it has one
// (ir::gradient_module, one evaluation each), else central differences, kProbe cells either side
// (forward differences from the crossing cost two evaluations less but take a sharp edge's other face
// whole where a probe crosses it: vertices 0.16 of a cell off in unit_dc_csg, against under 0.1).
bool normals(const Field& f, const Lattice& g, Block& b, Edges& E, std::vector<Plane>& planes,
             backends::RuntimeError& err) {
  Batch& pts = scratch();
  thread_local std::vector<size_t> probe;  // crossings whose normal the differences give
  probe.clear();
  for (size_t r : E.rest) E.at[E.real[r]] = E.point(b, g, r, E.t[r]);
  if (f.has_gradient()) {
    pts.clear();
    pts.resize(E.rest.size());
    for (size_t q = 0; q < E.rest.size(); ++q) {
      const std::array<double, 3>& p = E.at[E.real[E.rest[q]]];
      pts.set(q, p[0], p[1], p[2]);
    }
    float* o[4];
    if (!eval_gradient(f, pts, E.rest.size(), E, o, err)) return false;
    for (size_t q = 0; q < E.rest.size(); ++q) {
      double normal[3];
      if (gradient_normal(o, q, normal)) planes[E.real[E.rest[q]]] = Qef::plane(E.at[E.real[E.rest[q]]].data(), normal);
      else probe.push_back(E.rest[q]);
    }
  } else {
    probe = E.rest;
  }
  b.gradient_normals += static_cast<uint32_t>(E.rest.size() - probe.size());
  b.difference_normals += static_cast<uint32_t>(probe.size());
  if (probe.empty()) return true;
  pts.clear();
  pts.resize(6 * probe.size());
  const double d[3] = {kProbe * g.h[0], kProbe * g.h[1], kProbe * g.h[2]};
  for (size_t q = 0; q < probe.size(); ++q) {
    const std::array<double, 3>& p = E.at[E.real[probe[q]]];
    pts.set(6 * q, p[0] + d[0], p[1], p[2]), pts.set(6 * q + 1, p[0] - d[0], p[1], p[2]);
    pts.set(6 * q + 2, p[0], p[1] + d[1], p[2]), pts.set(6 * q + 3, p[0], p[1] - d[1], p[2]);
    pts.set(6 * q + 4, p[0], p[1], p[2] + d[2]), pts.set(6 * q + 5, p[0], p[1], p[2] - d[2]);
  }
  if (!pts.run(f, err)) return false;
  for (size_t q = 0; q < probe.size(); ++q) {
    const Crossing& c = b.xs[E.real[probe[q]]];
    double normal[3];
    if (!probed_normal(pts.out.data() + 6 * q, g, normal))
      normal[0] = normal[1] = normal[2] = 0, normal[c.axis] = c.lower_inside ? 1 : -1;  // the edge's own direction
    planes[E.real[probe[q]]] = Qef::plane(E.at[E.real[probe[q]]].data(), normal);
  }
  return true;
}

}  // namespace

bool hermite(const Field& whole, const Lattice& g, Block& b, std::vector<Plane>& planes, backends::RuntimeError& err) {
  const Field& f = b.field(whole);
  thread_local Edges E;
  std::vector<size_t>& real = E.real;
  std::vector<double>&lo_t = E.lo_t, &hi_t = E.hi_t, &lo_f = E.lo_f, &hi_f = E.hi_f, &t = E.t, &v = E.v;
  real.clear(), lo_t.clear(), hi_t.clear(), lo_f.clear(), hi_f.clear();
  E.at.resize(b.xs.size());
  planes.assign(b.xs.size(), Plane{});
  for (size_t e = 0; e < b.xs.size(); ++e) {
    const Crossing& c = b.xs[e];
    int a = c.axis, s[3], u[3];
    for (int k = 0; k < 3; ++k) s[k] = u[k] = b.s0[k] + c.l[k], E.at[e][static_cast<size_t>(k)] = g.coord(k, s[k]);
    ++u[a];
    if (g.padding(s) || g.padding(u)) {  // the box face, facing out of the solid
      bool upper_pad = g.padding(u);
      double normal[3] = {0, 0, 0};
      E.at[e][static_cast<size_t>(a)] = upper_pad ? g.end(a) : g.lo[a];
      normal[a] = upper_pad ? 1 : -1;
      planes[e] = Qef::plane(E.at[e].data(), normal);
      continue;
    }
    real.push_back(e);
    lo_t.push_back(0), hi_t.push_back(1), lo_f.push_back(b.ends[e][0]), hi_f.push_back(b.ends[e][1]);
  }
  b.ends = {};
  t.assign(real.size(), 0), v.assign(real.size(), 0);
  E.rest.resize(real.size());
  for (size_t r = 0; r < real.size(); ++r) E.rest[r] = r;
  if (f.has_gradient() && !newton(f, g, b, E, planes, err)) return false;
  // Regula falsi for the rest.
  Batch& pts = scratch();
  E.active = E.rest;
  for (int step = 0; step < kRefineSteps && !E.active.empty(); ++step) {
    pts.clear();
    pts.resize(E.active.size());
    for (size_t q = 0; q < E.active.size(); ++q) {
      size_t r = E.active[q];
      t[r] = E.false_position(r);
      std::array<double, 3> p = E.point(b, g, r, t[r]);
      pts.set(q, p[0], p[1], p[2]);
    }
    if (!pts.run(f, err)) return false;
    size_t kept = 0;
    for (size_t q = 0; q < E.active.size(); ++q) {
      size_t r = E.active[q];
      E.narrow(r, pts.out[q]);
      // Settled: the chord's next step would move the crossing by less than kSettled of the edge.
      double d = std::abs(lo_f[r] - hi_f[r]);
      if (!(std::isfinite(d) && std::abs(v[r]) * (hi_t[r] - lo_t[r]) <= kSettled * d)) E.active[kept++] = r;
    }
    E.active.resize(kept);
  }
  // A settled crossing stays where f was last evaluated; the others go to the final chord's zero.
  for (size_t r : E.active) t[r] = std::clamp(E.false_position(r), 0.0, 1.0);
  return normals(f, g, b, E, planes, err);
}

namespace {

// Corner q of the cell at bit q: two corners along x at a time, from the rows' bits.
unsigned cell_mask(const Block& b, int i, int j, int k) {
  auto two = [&](int y, int z) { return b.rows[z][y] >> i & 3u; };
  return two(j, k) | two(j + 1, k) << 2 | two(j, k + 1) << 4 | two(j + 1, k + 1) << 6;
}

// A cell's inside corners and its tube faces (dc_cells.h), looking across the block's faces
// through the grid.
void cell_signs(const BlockGrid& grid, Block& b, const int l[3], size_t c, std::vector<size_t>& tube_cells) {
  unsigned mask = cell_mask(b, l[0], l[1], l[2]), tubes = 0;
  if (ambiguous_faces(mask)) {
    unsigned around[6] = {};
    for (unsigned faces = ambiguous_faces(mask); faces; faces &= faces - 1) {
      int face = __builtin_ctz(faces), axis = face / 2, side = face % 2;
      int o[3] = {l[0], l[1], l[2]};
      o[axis] += side ? 1 : -1;
      bool here = o[axis] >= 0 && o[axis] < b.m[axis];
      int cell[3] = {b.s0[0] + o[0], b.s0[1] + o[1], b.s0[2] + o[2]};
      around[face] = here ? cell_mask(b, o[0], o[1], o[2]) : grid.mask(cell);
    }
    tubes = tube_faces(mask, around);
  }
  if (tubes || joins_middle(mask)) tube_cells.push_back(c);
  const CellSigns& cs = signs_of(mask, kuhn_flips(mask));
  if (!tubes && cs.regions_in == 1 && cs.regions_out == 1) tubes |= Block::kOneSheet;
  b.cells[c].mask = static_cast<uint8_t>(mask), b.cells[c].flips = static_cast<uint8_t>(tubes);
}

}  // namespace

void cell_sheets(const BlockGrid& grid, Block& b, const std::vector<Plane>& planes, std::vector<Qef>& qefs,
                 uint8_t look_across) {
  // Given back clean by keep_rim (only its cells with sheets were written): clearing all 4,096
  // cells per block cost more than the few hundred it names.
  b.cells.swap(cell_buffer());
  if (b.cells.size() != kCells) b.cells.assign(kCells, Block::CellInfo{});
  b.sheets.clear();
  qefs.clear();
  qefs.reserve(b.xs.size());
  b.ids.clear();
  b.sheets.reserve(b.xs.size());
  b.ids.reserve(b.xs.size());
  std::vector<size_t> tube_cells;
  for (size_t e = 0; e < b.xs.size(); ++e) {
    const Crossing& c = b.xs[e];
    int cells[4][3], inside[3] = {c.l[0], c.l[1], c.l[2]};
    if (!c.lower_inside) ++inside[c.axis];
    cells_of(c, cells);
    // The four cells are the edge's lower sample minus 0 or 1 along the two other axes: in the block
    // where that stays in 0 .. m - 1 (along the edge's own axis it always does).
    int u = kNextAxis[c.axis], w = kNextAxis[u];
    bool u0 = c.l[u] < b.m[u], u1 = c.l[u] > 0, w0 = c.l[w] < b.m[w], w1 = c.l[w] > 0;
    const bool here[4] = {u0 && w0, u1 && w0, u1 && w1, u0 && w1};
    std::array<uint16_t, 4> id{Block::kNoSheet, Block::kNoSheet, Block::kNoSheet, Block::kNoSheet};
    for (int q = 0; q < 4; ++q) {
      if (!here[q]) continue;
      const int* l = cells[q];
      size_t cell = Block::cell(l[0], l[1], l[2]);
      Block::CellInfo& info = b.cells[cell];
      if (info.first == kNone) cell_signs(grid, b, l, cell, tube_cells);
      int in = (inside[0] - l[0]) | (inside[1] - l[1]) << 1 | (inside[2] - l[2]) << 2;
      uint32_t s = b.sheet(info, in, in ^ (1 << c.axis));
      if (s == kNone) {
        s = static_cast<uint32_t>(b.sheets.size());
        b.sheets.push_back(Sheet{static_cast<uint32_t>(cell), info.first, Block::key(info, in, in ^ (1 << c.axis))});
        qefs.emplace_back(planes[e]);
        info.first = s;
      } else {
        qefs[s].add(planes[e]);
      }
      id[static_cast<size_t>(q)] = static_cast<uint16_t>(s);  // s < 4 * kCells < kNoSheet
    }
    b.ids.push_back(id);
  }
  record_cuts(grid, b, tube_cells, look_across);
  b.sheets.shrink_to_fit();  // a sheet per two or three crossings: the reserve's rest goes to the next block
}

}  // namespace fscript::mesh
