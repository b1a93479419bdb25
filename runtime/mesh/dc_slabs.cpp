// Slabs of dual contouring jobs (dc_slabs.h): a slab's blocks written after their sheets are merged
// and their rims kept, read back with every index checked, and joined into one grid.
#include "runtime/mesh/dc_slabs.h"

#include <algorithm>
#include <cstring>

#include "runtime/support/bytes.h"

namespace fscript::mesh {
namespace {

using support::ByteReader;
using support::ByteWriter;

enum : uint8_t { kOutside = 0, kInside = 1, kKept = 2 };
constexpr size_t kRim = static_cast<size_t>(kBlock * kBlock + (kBlock - 1) * kBlock + (kBlock - 1) * (kBlock - 1));

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

// At least what put_block writes (so the slab's string is allocated once).
size_t block_bytes(const Block& b) {
  return 128 + b.xs.size() * (sizeof(Crossing) + 8) + b.sheets.size() * 5 + b.positions.size() * 12 + b.rim.size() * 8 +
         sizeof(Qef);
}

// A block as the join uses it (merge_blocks, number_vertices, the polygons): its corners' signs,
// crossings with their cells' sheets, the sheets' chains and vertices, and the cells of its upper
// faces that have a sheet.
void put_block(ByteWriter& w, const Block& b) {
  w.put_bytes(b.b, sizeof b.b), w.put_bytes(b.s0, sizeof b.s0), w.put_bytes(b.m, sizeof b.m);
  w.put(corner_signs(b));
  w.put_vector(b.xs);
  std::vector<std::array<uint16_t, 4>> ids(b.ids.size());
  for (size_t e = 0; e < ids.size(); ++e)
    for (size_t q = 0; q < 4; ++q) ids[e][q] = narrow(b.ids[e][q]);
  std::vector<uint16_t> next(b.sheets.size()), vertex(b.vertex.size());
  std::vector<uint8_t> key(b.sheets.size());
  for (size_t s = 0; s < b.sheets.size(); ++s) next[s] = narrow(b.sheets[s].next), key[s] = static_cast<uint8_t>(b.sheets[s].key);
  for (size_t s = 0; s < b.vertex.size(); ++s) vertex[s] = narrow(b.vertex[s]);
  w.put_vector(ids), w.put_vector(next), w.put_vector(key), w.put_vector(vertex), w.put_vector(b.positions);
  std::vector<uint16_t> at, signs;
  std::vector<uint16_t> first;
  for (size_t i = 0; i < b.rim.size(); ++i)
    if (b.rim[i].first != kNone)
      at.push_back(static_cast<uint16_t>(i)), signs.push_back(static_cast<uint16_t>(b.rim[i].mask | b.rim[i].flips << 8)),
          first.push_back(narrow(b.rim[i].first));
  w.put_vector(at), w.put_vector(signs), w.put_vector(first);
  w.put(b.max_rms), w.put<uint64_t>(b.merged), w.put<uint8_t>(b.root), w.put(b.root_qef);
  w.put<uint64_t>(b.evaluated), w.put<uint8_t>(b.sound);
}

// Every index a block holds points inside it, so a damaged part cannot lead the join astray.
bool block_sound(const Block& b) {
  size_t sheets = b.sheets.size();
  if (b.ids.size() != b.xs.size() || b.vertex.size() != sheets) return false;
  for (const Crossing& c : b.xs) {
    uint8_t inside;  // a bool's byte read from a file: 0 or 1, else loading it is undefined
    std::memcpy(&inside, &c.lower_inside, 1);
    if (inside > 1 || c.axis > 2 || c.l[0] > kBlock || c.l[1] > kBlock || c.l[2] > kBlock || c.l[c.axis] == kBlock)
      return false;
  }
  for (const auto& id : b.ids)
    for (uint32_t s : id)
      if (s != kNone && s >= sheets) return false;
  for (size_t s = 0; s < sheets; ++s)
    if (b.sheets[s].next != kNone && b.sheets[s].next >= s) return false;
  for (uint32_t v : b.vertex)
    if (v >= b.positions.size()) return false;
  for (const Block::CellInfo& c : b.rim)
    if (c.first != kNone && c.first >= sheets) return false;
  return true;
}

bool get_block(ByteReader& r, Block& b, const Lattice& g, const int pos[3]) {
  r.get_bytes(b.b, sizeof b.b), r.get_bytes(b.s0, sizeof b.s0), r.get_bytes(b.m, sizeof b.m);
  for (int a = 0; a < 3; ++a)
    if (b.b[a] != pos[a] || b.s0[a] != pos[a] * kBlock - 1 || b.m[a] != std::min(kBlock, g.n[a] + 1 - pos[a] * kBlock))
      return false;
  set_corner_signs(b, r.get<uint8_t>());
  b.xs = r.get_vector<Crossing>();
  std::vector<std::array<uint16_t, 4>> ids = r.get_vector<std::array<uint16_t, 4>>();
  std::vector<uint16_t> next = r.get_vector<uint16_t>();
  std::vector<uint8_t> key = r.get_vector<uint8_t>();
  std::vector<uint16_t> vertex = r.get_vector<uint16_t>();
  b.positions = r.get_vector<std::array<float, 3>>();
  std::vector<uint16_t> at = r.get_vector<uint16_t>(), signs = r.get_vector<uint16_t>(), first = r.get_vector<uint16_t>();
  if (!r.ok || key.size() != next.size() || signs.size() != at.size() || first.size() != at.size()) return false;
  b.ids.resize(ids.size());
  for (size_t e = 0; e < ids.size(); ++e)
    for (size_t q = 0; q < 4; ++q) b.ids[e][q] = widen(ids[e][q]);
  b.sheets.resize(next.size());
  for (size_t s = 0; s < next.size(); ++s) b.sheets[s] = Sheet{0, widen(next[s]), key[s]};  // the cell: not needed now
  b.vertex.resize(vertex.size());
  for (size_t s = 0; s < vertex.size(); ++s) b.vertex[s] = widen(vertex[s]);
  if (!at.empty()) b.rim.assign(kRim, Block::CellInfo{});
  for (size_t i = 0; i < at.size(); ++i) {
    if (at[i] >= kRim) return false;
    b.rim[at[i]] = {static_cast<uint8_t>(signs[i]), static_cast<uint8_t>(signs[i] >> 8), widen(first[i])};
  }
  b.max_rms = r.get<double>(), b.merged = r.get<uint64_t>(), b.root = r.get<uint8_t>() != 0;
  b.root_qef = r.get<Qef>(), b.evaluated = r.get<uint64_t>(), b.sound = r.get<uint8_t>() != 0;
  return r.ok && block_sound(b);
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
  for (const Block* b : kept) put_block(w, *b);
  auto data = std::make_shared<const std::string>(std::move(w.out));
  std::lock_guard<std::mutex> hold(lock_);
  slabs_.push_back(Slab{job, first, end, data, *data});
}

bool SlabSplit::grid(uint32_t job, const Lattice& g, std::unique_ptr<BlockGrid>& out, std::string& error) const {
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
    blocks.reserve(blocks.size() + static_cast<size_t>(std::count(classes.begin(), classes.end(), kKept)));
    for (size_t i = 0; i < classes.size(); ++i) {
      if (classes[i] != kKept) {
        slots.push_back(classes[i] == kInside ? BlockGrid::kAllInside : BlockGrid::kAllOutside);
        continue;
      }
      size_t at = slots.size();
      int pos[3] = {static_cast<int>(at % nx), static_cast<int>(at / nx % ny), static_cast<int>(at / nx / ny)};
      slots.push_back(static_cast<int32_t>(blocks.size()));
      if (!get_block(r, blocks.emplace_back(), g, pos)) return error = "a part's slab of this shape is damaged", false;
    }
    next = s->end;
  }
  if (next != nz)
    return error = "the parts hold block layers 0 to " + std::to_string(next) + " of this shape's " + std::to_string(nz) +
                   " (were they made by this job?)",
           false;
  out = std::make_unique<BlockGrid>(g, std::move(slots), std::move(blocks));
  return true;
}

}  // namespace fscript::mesh
