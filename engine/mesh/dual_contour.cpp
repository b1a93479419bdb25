// Dual contouring: samples, Hermite data on sign-change edges (batched evaluation), a QEF vertex per
// sheet of each dual cell, cells merged by the octree, a polygon per edge wound to leave the solid.
#include "engine/mesh/dual_contour.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "engine/mesh/dc_block.h"
#include "engine/mesh/dc_normals.h"
#include "engine/mesh/dc_cell_merge.h"
#include "engine/mesh/dc_tubes.h"
#include "engine/mesh/dc_slabs.h"
#include "engine/mesh/field_profile.h"
#include "engine/mesh/sample_pruning.h"
#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

// Runs step(i, err) for every block i on `threads` workers that take blocks in turn; on failure, the
// error of the lowest failing block (every block below it has run, so that is the same every time).
template <class Step>
bool for_blocks(size_t n, int threads, Step step, backends::RuntimeError& err) {
  std::atomic<size_t> next{0}, failed{SIZE_MAX};
  int parts = static_cast<int>(std::max<size_t>(1, std::min<size_t>(static_cast<size_t>(std::max(1, threads)), n)));
  std::vector<std::pair<size_t, backends::RuntimeError>> fails(static_cast<size_t>(parts), {SIZE_MAX, {}});
  support::run_parts(parts, [&](int k) {
    for (size_t i; (i = next++) < n;) {
      backends::RuntimeError e;
      if (i > failed.load() || step(i, e)) continue;
      auto& mine = fails[static_cast<size_t>(k)];
      if (i < mine.first) mine = {i, e};
      for (size_t seen = failed.load(); i < seen && !failed.compare_exchange_weak(seen, i);) {}
    }
    return true;
  });
  auto first =
      std::min_element(fails.begin(), fails.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  if (first->first == SIZE_MAX) return true;
  err = first->second;
  return false;
}

// Where the blocks of layers [first, end) are among the grid's (kept in the order of their
// positions, z slowest).
std::pair<size_t, size_t> layer_range(const std::vector<Block>& blocks, int first, int end) {
  auto at = [&](int layer) {
    return static_cast<size_t>(
        std::partition_point(blocks.begin(), blocks.end(), [&](const Block& b) { return b.b[2] < layer; }) -
        blocks.begin());
  };
  return {at(first), at(end)};
}

// The blocks this run works, [first, end) in layers: all of them, or a shard's slab (the layer
// either side sampled too: its cells' faces look into them).
struct Layers {
  int first = 0, end = 0, lo = 0, hi = 0;
};
Layers layers_for(const SlabSplit* split, const BlockGrid& grid) {
  int n = BlockGrid::blocks_along(grid.lattice(), 2);
  Layers l{0, n, 0, n};
  if (!split) return l;
  std::vector<size_t> kept(static_cast<size_t>(n), 0);
  for (const Block& b : grid.blocks()) ++kept[static_cast<size_t>(b.b[2])];
  split->layers_of(kept, l.first, l.end);
  l.lo = l.first < l.end ? std::max(0, l.first - 1) : l.first, l.hi = l.first < l.end ? std::min(n, l.end + 1) : l.end;
  return l;
}

// The blocks of the run's layers sampled (pruned by the field's bounds when it has them) with
// their crossings; densely again when a decided sample contradicts its bound.
bool sample_blocks(const ImplicitJob& job, const Lattice& g, const SlabSplit* split, Layers& layers,
                   std::unique_ptr<BlockGrid>& grid, backends::RuntimeError& err) {
  std::unique_ptr<BrickMap> bricks = job_bricks(job);
  if (bricks) job.field->expect_points(bricks->points_on_whole());
  PruneStats st = bricks ? bricks->stats() : PruneStats{};
  st.points = static_cast<size_t>(g.n[0]) * g.n[1] * g.n[2];
  bool chosen = false;
  auto run = [&](const BrickMap* map) {
    grid = std::make_unique<BlockGrid>(g, map);
    if (!chosen) layers = layers_for(split, *grid), chosen = true;  // by the pruned grid's blocks, once
    std::vector<Block>& blocks = grid->blocks();
    std::pair<size_t, size_t> range = layer_range(blocks, layers.lo, layers.hi);
    std::pair<size_t, size_t> worked = layer_range(blocks, layers.first, layers.end);
    if (job.progress)  // sampled, then meshed
      job.progress->set_units(range.second - range.first + worked.second - worked.first);
    return for_blocks(
        range.second - range.first, job.threads,
        [&](size_t i, backends::RuntimeError& e) {
          bool ok = sample_block(*job.field, map, g, blocks[range.first + i], e);
          if (job.progress) job.progress->advance(1);
          return ok;
        },
        err);
  };
  bool ok = run(bricks.get());
  auto sound = [&] {
    return std::all_of(grid->blocks().begin(), grid->blocks().end(), [](const Block& b) { return b.sound; });
  };
  if (ok && !sound()) {  // a bound the function contradicts: the dense lattice instead
    ++st.fallbacks;
    ok = run(nullptr);
  }
  st.evaluated = 0;
  for (const Block& b : grid->blocks()) st.evaluated += b.evaluated;
  add_prune_totals(st);
  if (job.stats) *job.stats = st;
  return ok;
}

// The blocks of layers [first, end) worked from their samples to their vertices: Hermite data,
// sheets, the octree inside the block; then only their rims are kept.
bool work_blocks(const ImplicitJob& job, const Lattice& g, BlockGrid& grid, int first, int end,
                 backends::RuntimeError& err) {
  std::vector<Block>& blocks = grid.blocks();
  std::pair<size_t, size_t> range = layer_range(blocks, first, end);
  return for_blocks(
      range.second - range.first, job.threads,
      [&](size_t i, backends::RuntimeError& e) {
        Block& b = blocks[range.first + i];
        if (b.xs.empty()) {
          if (job.progress) job.progress->advance(1);
          return true;
        }
        thread_local std::vector<Plane> planes;  // scratch of this thread, reused block after block
        thread_local std::vector<Qef> qefs;
        if (!hermite(*job.field, g, b, planes, e)) return false;
    // A shard looks across its slab's faces: the blocks there are another process's.
        uint8_t look_across = 0;
        if (job.mesher.slabs && b.b[2] == first && first > 0) look_across |= 1u << 4;
        if (job.mesher.slabs && b.b[2] == end - 1 && end < BlockGrid::blocks_along(g, 2)) look_across |= 1u << 5;
        cell_sheets(grid, b, planes, qefs, look_across);
        merge_block(g, b, qefs, job.mesher.tolerance);
        for (TubeCut& c : b.cuts) c.first = b.vertex[c.first], c.second = b.vertex[c.second];
        for (auto& t : b.fans)
          for (uint32_t& v : t) v = b.vertex[v];
        b.keep_rim();
        b.local.reset();
        if (job.progress) job.progress->advance(1);
        return true;
      },
      err);
}

// Each sheet's vertex (Block::vertex) as its output vertex (number_blocks); the blocks' positions
// are dropped once copied.
void number_vertices(BlockGrid& grid, const std::vector<int32_t>& group, const std::vector<BlockGroup>& groups,
                     Mesh& out, DualContourStats& stats) {
  std::vector<uint32_t> base;
  std::vector<bool> grouped;
  number_blocks(grid, group, groups, out, stats, base, grouped);
  std::vector<Block>& blocks = grid.blocks();
  for (size_t i = 0; i < blocks.size(); ++i) {
    Block& b = blocks[i];
    if (base[i] == kNone) continue;
    if (grouped[i]) std::fill(b.vertex.begin(), b.vertex.end(), base[i]);
    else
      for (uint32_t& v : b.vertex) v += base[i];
    for (TubeCut& c : b.cuts)
      c.first = grouped[i] ? base[i] : c.first + base[i], c.second = grouped[i] ? base[i] : c.second + base[i];
    for (auto& t : b.fans)
      for (uint32_t& v : t) v = grouped[i] ? base[i] : v + base[i];
    b.positions = {};
  }
}

// The output vertex of the sheet of lattice cell `cell` that holds the crossing whose inside sample
// is `inside`, along `axis`; the cell is in block b or one of the blocks before it.
uint32_t vertex_at(const BlockGrid& grid, const Block& b, const int l[3], const int inside[3], int axis) {
  int nb[3] = {b.b[0], b.b[1], b.b[2]}, nl[3] = {l[0], l[1], l[2]};
  for (int a = 0; a < 3; ++a)
    if (nl[a] < 0) --nb[a], nl[a] += kBlock;
  const Block* owner = grid.at(nb[0], nb[1], nb[2]);
  if (!owner) return kNone;  // only if the sign of a sample differed between two blocks
  int in = 0;
  for (int a = 0; a < 3; ++a) in |= (b.s0[a] + inside[a] - owner->s0[a] - nl[a]) << a;
  uint32_t s = owner->sheet(owner->rim_cell(nl[0], nl[1], nl[2]), in, in ^ (1 << axis));
  return s == kNone ? kNone : owner->vertex[s];
}

// The output vertices of crossing e's four cells in winding order, repeated ones dropped; false
// where a cell has none (only if two blocks disagreed on the sign of a sample).
bool ring_of(const BlockGrid& grid, const Block& b, size_t e, uint32_t ring[4], int& n) {
  const Crossing& c = b.xs[e];
  int cells[4][3], inside[3] = {c.l[0], c.l[1], c.l[2]};
  if (!c.lower_inside) ++inside[c.axis];
  cells_of(c, cells);
  n = 0;
  for (int q = 0; q < 4; ++q) {
    uint32_t s = b.id(e, static_cast<size_t>(q));
    uint32_t v = s != kNone ? b.vertex[s] : vertex_at(grid, b, cells[q], inside, c.axis);
    if (v == kNone) return false;
    if (n == 0 || ring[n - 1] != v) ring[n++] = v;
  }
  if (n > 1 && ring[n - 1] == ring[0]) --n;
  return true;
}

// One polygon per crossing whose highest cell is in the block, over its cells' output vertices,
// wound to face out of the solid; where merged cells repeat a vertex the quad becomes a triangle,
// or nothing inside a merged cell.
void polygons(const BlockGrid& grid, const Block& b, Mesh& out) {
  for (size_t e = 0; e < b.xs.size(); ++e) {
    const Crossing& c = b.xs[e];
    if (c.l[0] >= b.m[0] || c.l[1] >= b.m[1] || c.l[2] >= b.m[2]) continue;  // the next block's
    uint32_t ring[4];
    int n;
    if (!ring_of(grid, b, e, ring, n) || n < 3) continue;
    if (!c.lower_inside) std::reverse(ring, ring + n);  // the solid above: the polygon faces -axis
    out.triangles.push_back({ring[0], ring[1], ring[2]});
    if (n == 4) out.triangles.push_back({ring[0], ring[2], ring[3]});
  }
}

}  // namespace

bool dual_contour(const ImplicitJob& job, Mesh& out, DualContourStats& stats, backends::RuntimeError& err) {
  out = Mesh{};
  stats = {};
  if (!job.field) {
    err.message = "the dual contouring mesher needs a field";
    return false;
  }
  Lattice g;
  for (int a = 0; a < 3; ++a) {
    g.n[a] = std::max(1, job.cells[static_cast<size_t>(a)]);
    g.lo[a] = job.box[static_cast<size_t>(2 * a)];
    g.h[a] = (job.box[static_cast<size_t>(2 * a + 1)] - g.lo[a]) / g.n[a];
  }
  std::unique_ptr<BlockGrid> grid;
  SlabSplit* split = job.mesher.slabs;
  uint32_t number = split ? split->next_job() : 0;
  // Normals from the gradient, differences a hundredth of a cell apart where the field has none of
  // its own (so only vertices that close to a sharp edge blend its two sides).
  auto with_normals = [&] {
    double h = std::min({g.h[0], g.h[1], g.h[2]});
    Projection onto{0.05 * h, h, 1e-6 * h, job.box};
    return gradient_vertex_normals(*job.field, 0.01 * h, kCreaseAngle, job.threads, onto, out, err);
  };
  // The merge: the shards' slabs joined into the mesh, numbered and connected as below.
  if (split && split->joining())
    return split->join(number, g, job.mesher.tolerance, out, stats, err.message) && with_normals();
  Layers layers;
  if (!sample_blocks(job, g, split, layers, grid, err) || !work_blocks(job, g, *grid, layers.first, layers.end, err))
    return false;
  resolve_requests(*grid, layers.first, layers.end);
  if (split) {  // a shard: its slab's blocks, for the merge
    split->keep(number, *grid, layers.first, layers.end);
    return true;
  }
  std::vector<Block>& blocks = grid->blocks();
  std::vector<BlockGroup> groups;
  std::vector<int32_t> group = merge_blocks(*grid, job.mesher.tolerance, groups);
  number_vertices(*grid, group, groups, out, stats);
  size_t crossings = 0;  // at most two triangles each: reserved, not touched, so no doubling copies
  for (const Block& b : blocks) crossings += b.xs.size();
  out.triangles.reserve(2 * crossings);
  for (const Block& b : blocks) polygons(*grid, b, out);
  std::vector<TubeCut> cuts;
  for (const Block& b : blocks) {
    cuts.insert(cuts.end(), b.cuts.begin(), b.cuts.end());
    out.triangles.insert(out.triangles.end(), b.fans.begin(), b.fans.end());
  }
  close_tubes(std::move(cuts), out);
  stats.triangles = out.triangles.size();
  for (const Block& b : blocks)
    stats.gradient_normals += b.gradient_normals, stats.difference_normals += b.difference_normals;
  grid.reset(), group = {}, groups = {};  // the normals' memory takes the blocks' place
  return with_normals();
}

void DualContourStats::add(const DualContourStats& o) {
  cells += o.cells, merged += o.merged, triangles += o.triangles, jobs += o.jobs;
  gradient_normals += o.gradient_normals, difference_normals += o.difference_normals;
  max_error = std::max(max_error, o.max_error);
}

namespace {
std::mutex totals_lock;  // frames are meshed in parallel
DualContourStats totals;
}  // namespace

DualContourStats dual_contour_totals() {
  std::lock_guard<std::mutex> hold(totals_lock);
  return totals;
}

bool polygonize(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err) {
  if (job.profile) return polygonize_profiled(job, out, err);
  DualContourStats st;
  switch (job.mesher.kind) {
    case Mesher::MarchingTetrahedra:
      if (job.mesher.slabs && !job.mesher.slabs->joining()) return out = Mesh{}, true;  // the merge makes it whole
      return polygonize_implicit(job, out, err);
    case Mesher::DualContouring: {
      if (!dual_contour(job, out, st, err)) return false;
      st.jobs = 1;
      std::lock_guard<std::mutex> hold(totals_lock);
      totals.add(st);
      return true;
    }
  }
  return false;
}

}  // namespace fscript::mesh
