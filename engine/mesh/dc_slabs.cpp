// Slabs of dual contouring jobs (dc_slabs.h): a slab's blocks written once worked (corners, vertices,
// each crossing's ring of vertices), read back with every index checked, and joined into the mesh.
#include "engine/mesh/dc_slabs.h"

#include <algorithm>
#include <cstring>

#include "engine/mesh/dc_cell_merge.h"
#include "engine/mesh/dc_tubes.h"
#include "runtime/support/bytes.h"

namespace fscript::mesh {
namespace {

using support::ByteReader;
using support::ByteWriter;

enum : uint8_t { kOutside = 0, kInside = 1, kKept = 2 };

void put_lattice(ByteWriter& w, const Lattice& g) {
  w.put_bytes(g.n, sizeof g.n), w.put_bytes(g.lo, sizeof g.lo), w.put_bytes(g.h, sizeof g.h);
}

bool same_lattice(ByteReader& r, const Lattice& g) {
  Lattice got{};
  r.get_bytes(got.n, sizeof got.n), r.get_bytes(got.lo, sizeof got.lo), r.get_bytes(got.h, sizeof got.h);
  return r.ok && std::memcmp(got.n, g.n, sizeof g.n) == 0 && std::memcmp(got.lo, g.lo, sizeof g.lo) == 0 &&
      std::memcmp(got.h, g.h, sizeof g.h) == 0;
}

// The signs of a block's eight corner samples (0 or m along each axis): all the join reads of its
// samples, since the nodes above the blocks test only samples on block corners (merge_blocks).
uint8_t corner_signs(const Block& b) {
  uint8_t out = 0;
  for (int c = 0; c < 8; ++c)
    out |= static_cast<uint8_t>(b.inside(c & 1 ? b.m[0] : 0, c & 2 ? b.m[1] : 0, c & 4 ? b.m[2] : 0) << c);
  return out;
}

void set_corner_signs(Block& b, uint8_t signs) {
  std::memset(b.rows, 0, sizeof b.rows);
  for (int c = 0; c < 8; ++c)
    if (signs >> c & 1) b.rows[c & 4 ? b.m[2] : 0][c & 2 ? b.m[1] : 0] |= 1u << (c & 1 ? b.m[0] : 0);
}

// A block's sheet and vertex numbers fit 16 bits (at most four sheets in each of kBlock^3 cells).
static_assert(4 * kBlock * kBlock * kBlock <= 0xffff);
constexpr uint16_t kNone16 = 0xffff;
uint16_t narrow(uint32_t v) { return v == kNone ? kNone16 : static_cast<uint16_t>(v); }
uint32_t widen(uint16_t v) { return v == kNone16 ? kNone : v; }

// A crossing's ring: the vertices of its four cells as the shard numbers them, for the join to
// number again. ref[q]: the vertex (bits 0-14) of the block at the cell's offset (bits 15-17: -1
// along x, y, z where set); or, kForeign, a cell of the layer below the slab, which the shard did
// not work: its cell in the block (bits 0-11), the crossing's inside corner in it (18-20) and axis
// (21-22), for the join to find among that block's top cells. kLowerInside in ref[0]: the solid is
// below the crossing.
using Ring = SlabSplit::Ring;
constexpr uint32_t kForeign = 1u << 31, kLowerInside = 1u << 30, kRefBits = ~kLowerInside;
constexpr size_t kFace = static_cast<size_t>(kBlock) * kBlock;  // a block's top cells, first in its rim

// The ring of crossing e of block b, or false where a cell has no vertex (as ring_of: only if two
// blocks disagreed on a sign).
bool ring_refs(const BlockGrid& grid, const Block& b, size_t e, int first_layer, Ring& out) {
  const Crossing& c = b.xs[e];
  int cells[4][3], inside[3] = {c.l[0], c.l[1], c.l[2]};
  if (!c.lower_inside) ++inside[c.axis];
  cells_of(c, cells);
  for (size_t q = 0; q < 4; ++q) {
    uint32_t s = b.id(e, q);
    if (s != kNone) {
      out[q] = b.vertex[s];
      continue;
    }
    int nb[3], nl[3];
    uint32_t delta = 0;
    for (int a = 0; a < 3; ++a) {
      nb[a] = b.b[a], nl[a] = cells[q][a];
      if (nl[a] < 0) --nb[a], nl[a] += kBlock, delta |= 1u << a;
    }
    const Block* owner = grid.at(nb[0], nb[1], nb[2]);
    if (!owner) return false;
    uint32_t in = 0;
    for (int a = 0; a < 3; ++a) in |= static_cast<uint32_t>(b.s0[a] + inside[a] - owner->s0[a] - nl[a]) << a;
    if (nb[2] < first_layer) {
      out[q] = kForeign | delta << 15 | static_cast<uint32_t>(nl[0] | nl[1] << 4 | nl[2] << 8) | in << 18 |
          static_cast<uint32_t>(c.axis) << 21;
      continue;
    }
    uint32_t t =
        owner->sheet(owner->rim_cell(nl[0], nl[1], nl[2]), static_cast<int>(in), static_cast<int>(in ^ (1u << c.axis)));
    if (t == kNone) return false;
    out[q] = delta << 15 | owner->vertex[t];
  }
  if (c.lower_inside) out[0] |= kLowerInside;
  return true;
}

// Rings in 16-bit words: a ring whose cells are all in its own block, with vertices under 2^14,
// in four words (the first with kNarrowInside for kLowerInside); any other in nine, kWide first.
constexpr uint16_t kWide = 0x8000, kNarrowInside = 0x4000;
void put_ring(std::vector<uint16_t>& out, const Ring& r) {
  bool narrow = true;
  for (uint32_t ref : r) narrow = narrow && (ref & kRefBits) < 0x4000;
  if (narrow) {
    out.push_back(static_cast<uint16_t>((r[0] & 0x3fff) | (r[0] & kLowerInside ? kNarrowInside : 0)));
    for (size_t q = 1; q < 4; ++q) out.push_back(static_cast<uint16_t>(r[q]));
    return;
  }
  out.push_back(kWide);
  for (uint32_t ref : r) out.push_back(static_cast<uint16_t>(ref)), out.push_back(static_cast<uint16_t>(ref >> 16));
}

// The rings of put_ring back; false where the words end inside a ring.
bool get_rings(const std::vector<uint16_t>& in, std::vector<Ring>& out) {
  for (size_t i = 0; i < in.size();) {
    Ring r;
    if (in[i] & kWide) {
      if (in.size() - i < 9) return false;
      for (size_t q = 0; q < 4; ++q) r[q] = in[i + 1 + 2 * q] | static_cast<uint32_t>(in[i + 2 + 2 * q]) << 16;
      i += 9;
    } else {
      if (in.size() - i < 4) return false;
      r = {static_cast<uint32_t>(in[i] & 0x3fff) | (in[i] & kNarrowInside ? kLowerInside : 0), in[i + 1], in[i + 2],
           in[i + 3]};
      i += 4;
    }
    out.push_back(r);
  }
  return true;
}

// A block of the slab as the join needs it: what merge_blocks reads (corners, root), its vertices,
// its rings; for a block of the slab's top layer also its top cells' sheets, which the rings of
// the slab above reach.
void put_block(ByteWriter& w, const BlockGrid& grid, const Block& b, int first_layer, bool top) {
  w.put_bytes(b.b, sizeof b.b), w.put_bytes(b.s0, sizeof b.s0), w.put_bytes(b.m, sizeof b.m);
  w.put(corner_signs(b));
  std::vector<uint16_t> rings;
  rings.reserve(4 * b.xs.size());
  for (size_t e = 0; e < b.xs.size(); ++e) {
    const Crossing& c = b.xs[e];
    Ring r;
    if (c.l[0] < b.m[0] && c.l[1] < b.m[1] && c.l[2] < b.m[2] && ring_refs(grid, b, e, first_layer, r))
      put_ring(rings, r);
  }
  w.put_vector(rings), w.put_vector(b.positions), w.put_vector(b.cuts), w.put_vector(b.fans);
  w.put(b.max_rms), w.put<uint64_t>(b.merged), w.put<uint8_t>(b.root), w.put(b.root_qef);
  w.put<uint8_t>(top);
  if (!top) return;
  std::vector<uint16_t> next(b.sheets.size()), vertex(b.vertex.size()), at, signs, first;
  std::vector<uint16_t> key(b.sheets.size());
  for (size_t s = 0; s < b.sheets.size(); ++s) next[s] = narrow(b.sheets[s].next()), key[s] = b.sheets[s].key;
  for (size_t s = 0; s < b.vertex.size(); ++s) vertex[s] = narrow(b.vertex[s]);
  for (const Block::RimCell& c : b.rim)
    if (c.at < kFace)
      at.push_back(c.at), signs.push_back(static_cast<uint16_t>(c.mask | c.flips << 8)),
          first.push_back(narrow(c.first));
  w.put_vector(next), w.put_vector(key), w.put_vector(vertex), w.put_vector(at), w.put_vector(signs),
      w.put_vector(first);
}

// At least what put_block writes (so the slab's string is allocated once).
size_t block_bytes(const Block& b) { return 160 + b.xs.size() * 8 + b.positions.size() * 12 + sizeof(Qef); }

// Every index a top block holds points inside it, so a damaged part cannot lead the join astray.
bool top_sound(const Block& b) {
  size_t sheets = b.sheets.size();
  if (b.vertex.size() != sheets) return false;
  for (size_t s = 0; s < sheets; ++s)
    if (b.sheets[s].next() != kNone && b.sheets[s].next() >= s) return false;
  for (uint32_t v : b.vertex)
    if (v >= b.positions.size()) return false;
  for (const Block::RimCell& c : b.rim)
    if (c.first != kNone && c.first >= sheets) return false;
  return true;
}

bool get_block(ByteReader& r, Block& b, std::vector<Ring>& rings, const Lattice& g, const int pos[3]) {
  r.get_bytes(b.b, sizeof b.b), r.get_bytes(b.s0, sizeof b.s0), r.get_bytes(b.m, sizeof b.m);
  for (int a = 0; a < 3; ++a)
    if (b.b[a] != pos[a] || b.s0[a] != pos[a] * kBlock - 1 || b.m[a] != std::min(kBlock, g.n[a] + 1 - pos[a] * kBlock))
      return false;
  set_corner_signs(b, r.get<uint8_t>());
  if (!get_rings(r.get_vector<uint16_t>(), rings)) return false;
  b.positions = r.get_vector<std::array<float, 3>>();
  b.cuts = r.get_vector<TubeCut>();
  b.fans = r.get_vector<std::array<uint32_t, 3>>();
  for (const TubeCut& c : b.cuts)
    if (c.first >= b.positions.size() || c.second >= b.positions.size()) return false;
  for (const auto& t : b.fans)
    for (uint32_t v : t)
      if (v >= b.positions.size()) return false;
  b.max_rms = r.get<double>(), b.merged = r.get<uint64_t>(), b.root = r.get<uint8_t>() != 0;
  b.root_qef = r.get<Qef>();
  if (!r.get<uint8_t>()) return r.ok;
  std::vector<uint16_t> next = r.get_vector<uint16_t>();
  std::vector<uint16_t> key = r.get_vector<uint16_t>();
  std::vector<uint16_t> vertex = r.get_vector<uint16_t>();
  std::vector<uint16_t> at = r.get_vector<uint16_t>(), signs = r.get_vector<uint16_t>(),
                        first = r.get_vector<uint16_t>();
  if (!r.ok || key.size() != next.size() || signs.size() != at.size() || first.size() != at.size()) return false;
  b.sheets.resize(next.size());
  for (size_t s = 0; s < next.size(); ++s) b.sheets[s] = Sheet{0, widen(next[s]), key[s]};  // the cell: not needed now
  b.vertex.resize(vertex.size());
  for (size_t s = 0; s < vertex.size(); ++s) b.vertex[s] = widen(vertex[s]);
  b.rim.clear();
  for (size_t i = 0; i < at.size(); ++i) {
    if (at[i] >= kFace || (i > 0 && at[i] <= at[i - 1])) return false;  // rim_cell searches it in order
    b.rim.push_back({at[i], static_cast<uint8_t>(signs[i]), static_cast<uint8_t>(signs[i] >> 8), widen(first[i])});
  }
  return top_sound(b);
}

}  // namespace

std::unique_ptr<SlabSplit> SlabSplit::make(int index, int count) {
  auto s = std::make_unique<SlabSplit>();
  s->index_ = index, s->count_ = std::max(count, 1);
  return s;
}

std::unique_ptr<SlabSplit> SlabSplit::join(std::vector<Slab> slabs) {
  auto s = std::make_unique<SlabSplit>();
  s->joining_ = true, s->slabs_ = std::move(slabs);
  return s;
}

uint32_t SlabSplit::next_job() {
  std::lock_guard<std::mutex> hold(lock_);
  return jobs_++;
}

void SlabSplit::layers_of(const std::vector<size_t>& kept, int& first, int& end) const {
  // Shard k starts at the first layer whose kept blocks before it reach k / count of the total (a
  // layer without any counts one, so empty stretches are shared out too).
  std::vector<uint64_t> before(kept.size() + 1, 0);
  for (size_t k = 0; k < kept.size(); ++k) before[k + 1] = before[k] + kept[k] + 1;
  auto start = [&](int shard) {
    uint64_t want = before.back() * static_cast<uint64_t>(shard) / static_cast<uint64_t>(count_);
    return static_cast<int>(std::lower_bound(before.begin(), before.end(), want) - before.begin());
  };
  first = start(index_), end = index_ + 1 == count_ ? static_cast<int>(kept.size()) : start(index_ + 1);
}

void SlabSplit::keep(uint32_t job, const BlockGrid& grid, int first, int end) {
  const Lattice& g = grid.lattice();
  int nx = BlockGrid::blocks_along(g, 0), ny = BlockGrid::blocks_along(g, 1);
  ByteWriter w;
  put_lattice(w, g);
  size_t per_layer = static_cast<size_t>(nx) * static_cast<size_t>(ny);
  std::vector<uint8_t> classes;
  std::vector<const Block*> kept;
  for (size_t at = per_layer * static_cast<size_t>(first); at < per_layer * static_cast<size_t>(end); ++at) {
    int32_t s = grid.slot(at);
    classes.push_back(s >= 0 ? kKept : s == BlockGrid::kAllInside ? kInside : kOutside);
    if (s >= 0) kept.push_back(&grid.blocks()[static_cast<size_t>(s)]);
  }
  size_t size = 256 + classes.size();
  for (const Block* b : kept) size += block_bytes(*b);
  w.out.reserve(size);
  w.put_vector(classes);
  for (const Block* b : kept) put_block(w, grid, *b, first, b->b[2] == end - 1);
  auto data = std::make_shared<const std::string>(std::move(w.out));
  std::lock_guard<std::mutex> hold(lock_);
  slabs_.push_back(Slab{job, first, end, data, *data});
}

bool SlabSplit::join(uint32_t job, const Lattice& g, double tolerance, Mesh& out, DualContourStats& stats,
                     std::string& error) const {
  std::unique_ptr<BlockGrid> grid;
  std::vector<std::vector<Ring>> joined;  // per block
  if (!read_slabs(job, g, grid, joined, error)) return false;
  std::vector<BlockGroup> groups;
  std::vector<int32_t> group = merge_blocks(*grid, tolerance, groups);
  const std::vector<Block>& blocks = grid->blocks();
  std::vector<uint32_t> base;
  std::vector<bool> grouped;
  number_blocks(*grid, group, groups, out, stats, base, grouped);
  // One polygon per ring, as polygons() makes it from ring_of's vertices.
  auto index_of = [&](const Block* b) { return static_cast<size_t>(b - blocks.data()); };
  auto global = [&](size_t i, uint32_t ref, uint32_t& v) {
    const Block& b = blocks[i];
    const Block* t = &b;
    if (ref >> 15 & 7) t = grid->at(b.b[0] - (ref >> 15 & 1), b.b[1] - (ref >> 16 & 1), b.b[2] - (ref >> 17 & 1));
    if (!t) return false;
    uint32_t local = ref & 0x7fff;
    if (ref & kForeign) {
      int in = ref >> 18 & 7, axis = ref >> 21 & 3, nl[3] = {int(ref & 15), int(ref >> 4 & 15), int(ref >> 8 & 15)};
      if (nl[2] != kBlock - 1 || axis > 2) return false;
      uint32_t s = t->sheet(t->rim_cell(nl[0], nl[1], nl[2]), in, in ^ (1 << axis));
      if (s == kNone) return false;
      local = t->vertex[s];
    }
    size_t ti = index_of(t);
    if (local >= t->positions.size()) return false;
    v = grouped[ti] ? base[ti] : base[ti] + local;
    return true;
  };
  for (size_t i = 0; i < blocks.size(); ++i)
    for (const Ring& r : joined[i]) {
      uint32_t ring[4];
      int n = 0;
      bool ok = true;
      for (size_t q = 0; q < 4 && ok; ++q) {
        uint32_t v = 0;
        ok = global(i, r[q] & kRefBits, v);
        if (ok && (n == 0 || ring[n - 1] != v)) ring[n++] = v;
      }
      if (!ok) return error = "a part's slab of this shape is damaged", false;
      if (n > 1 && ring[n - 1] == ring[0]) --n;
      if (n < 3) continue;
      if (!(r[0] & kLowerInside)) std::reverse(ring, ring + n);
      out.triangles.push_back({ring[0], ring[1], ring[2]});
      if (n == 4) out.triangles.push_back({ring[0], ring[2], ring[3]});
    }
  std::vector<TubeCut> cuts;
  for (size_t i = 0; i < blocks.size(); ++i) {
    auto number = [&](uint32_t v) { return grouped[i] ? base[i] : base[i] + v; };
    for (TubeCut c : blocks[i].cuts) {
      c.first = number(c.first), c.second = number(c.second);
      cuts.push_back(c);
    }
    for (const auto& t : blocks[i].fans) out.triangles.push_back({number(t[0]), number(t[1]), number(t[2])});
  }
  close_tubes(std::move(cuts), out);
  stats.triangles = out.triangles.size();
  return true;
}

bool SlabSplit::read_slabs(uint32_t job, const Lattice& g, std::unique_ptr<BlockGrid>& out,
                           std::vector<std::vector<Ring>>& joined, std::string& error) const {
  std::vector<const Slab*> mine;
  for (const Slab& s : slabs_)
    if (s.job == job) mine.push_back(&s);
  std::sort(mine.begin(), mine.end(), [](const Slab* a, const Slab* b) {
    return a->first != b->first ? a->first < b->first : a->end < b->end;  // an empty slab before its neighbour
  });
  int nx = BlockGrid::blocks_along(g, 0), ny = BlockGrid::blocks_along(g, 1), nz = BlockGrid::blocks_along(g, 2);
  std::vector<int32_t> slots;
  std::vector<Block> blocks;
  int next = 0;
  for (const Slab* s : mine) {
    if (s->first != next || s->end < s->first || s->end > nz) break;
    ByteReader r{s->bytes};
    if (!same_lattice(r, g))
      return error = r.ok ? "a part's slab of this shape has another grid (made by another job?)"
                          : "a part's slab of this shape is damaged",
             false;
    std::vector<uint8_t> classes = r.get_vector<uint8_t>();
    if (!r.ok || classes.size() != static_cast<size_t>(nx) * ny * (s->end - s->first))
      return error = "a part's slab of this shape is damaged", false;
    size_t more = static_cast<size_t>(std::count(classes.begin(), classes.end(), kKept));
    blocks.reserve(blocks.size() + more), joined.reserve(joined.size() + more);
    for (size_t i = 0; i < classes.size(); ++i) {
      if (classes[i] != kKept) {
        slots.push_back(classes[i] == kInside ? BlockGrid::kAllInside : BlockGrid::kAllOutside);
        continue;
      }
      size_t at = slots.size();
      int pos[3] = {static_cast<int>(at % nx), static_cast<int>(at / nx % ny), static_cast<int>(at / nx / ny)};
      slots.push_back(static_cast<int32_t>(blocks.size()));
      if (!get_block(r, blocks.emplace_back(), joined.emplace_back(), g, pos))
        return error = "a part's slab of this shape is damaged", false;
    }
    next = s->end;
  }
  if (next != nz)
    return error = "the parts hold block layers 0 to " + std::to_string(next) + " of this shape's " +
               std::to_string(nz) + " (were they made by this job?)",
           false;
  out = std::make_unique<BlockGrid>(g, std::move(slots), std::move(blocks));
  return true;
}

}  // namespace fscript::mesh
