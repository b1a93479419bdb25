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
constexpr size_t kCells = static_cast<size_t>(kBlock) * kBlock * kBlock;

void put_lattice(ByteWriter& w, const Lattice& g) {
  w.put_bytes(g.n, sizeof g.n), w.put_bytes(g.lo, sizeof g.lo), w.put_bytes(g.h, sizeof g.h);
}

bool same_lattice(ByteReader& r, const Lattice& g) {
  Lattice got{};
  r.get_bytes(got.n, sizeof got.n), r.get_bytes(got.lo, sizeof got.lo), r.get_bytes(got.h, sizeof got.h);
  return r.ok && std::memcmp(got.n, g.n, sizeof g.n) == 0 && std::memcmp(got.lo, g.lo, sizeof g.lo) == 0 &&
         std::memcmp(got.h, g.h, sizeof g.h) == 0;
}

// A block as merge_blocks, number_vertices and the polygons use it: its samples' signs, crossings,
// sheets, vertices and the cells of its upper faces (only those with a sheet).
void put_block(ByteWriter& w, const Block& b) {
  w.put_bytes(b.b, sizeof b.b), w.put_bytes(b.s0, sizeof b.s0), w.put_bytes(b.m, sizeof b.m);
  w.put_bytes(b.rows, sizeof b.rows);
  w.put_vector(b.xs), w.put_vector(b.ids), w.put_vector(b.sheets), w.put_vector(b.vertex), w.put_vector(b.positions);
  std::vector<uint16_t> at, signs;
  std::vector<uint32_t> first;
  for (size_t i = 0; i < b.rim.size(); ++i)
    if (b.rim[i].first != kNone)
      at.push_back(static_cast<uint16_t>(i)), signs.push_back(static_cast<uint16_t>(b.rim[i].mask | b.rim[i].flips << 8)),
          first.push_back(b.rim[i].first);
  w.put_vector(at), w.put_vector(signs), w.put_vector(first);
  w.put(b.max_rms), w.put<uint64_t>(b.merged), w.put<uint8_t>(b.root), w.put(b.root_qef);
  w.put<uint64_t>(b.evaluated), w.put<uint8_t>(b.sound);
}

// Every index a block holds points inside it, so a damaged part cannot lead the join astray.
bool block_sound(const Block& b) {
  size_t sheets = b.sheets.size();
  if (b.ids.size() != b.xs.size() || b.vertex.size() != sheets) return false;
  for (const Crossing& c : b.xs)
    if (c.axis > 2 || c.l[0] > kBlock || c.l[1] > kBlock || c.l[2] > kBlock || c.l[c.axis] == kBlock) return false;
  for (const auto& id : b.ids)
    for (uint32_t s : id)
      if (s != kNone && s >= sheets) return false;
  for (size_t s = 0; s < sheets; ++s)
    if (b.sheets[s].cell >= kCells || (b.sheets[s].next != kNone && b.sheets[s].next >= s)) return false;
  for (uint32_t v : b.vertex)
    if (v >= b.positions.size()) return false;
  for (const Block::CellInfo& c : b.rim)
    if (c.first != kNone && c.first >= sheets) return false;
  return true;
}

bool get_block(ByteReader& r, Block& b, const Lattice& g, const int pos[3]) {
  r.get_bytes(b.b, sizeof b.b), r.get_bytes(b.s0, sizeof b.s0), r.get_bytes(b.m, sizeof b.m);
  r.get_bytes(b.rows, sizeof b.rows);
  for (int a = 0; a < 3; ++a)
    if (b.b[a] != pos[a] || b.s0[a] != pos[a] * kBlock - 1 || b.m[a] != std::min(kBlock, g.n[a] + 1 - pos[a] * kBlock))
      return false;
  b.xs = r.get_vector<Crossing>(), b.ids = r.get_vector<std::array<uint32_t, 4>>();
  b.sheets = r.get_vector<Sheet>(), b.vertex = r.get_vector<uint32_t>();
  b.positions = r.get_vector<std::array<float, 3>>();
  std::vector<uint16_t> at = r.get_vector<uint16_t>(), signs = r.get_vector<uint16_t>();
  std::vector<uint32_t> first = r.get_vector<uint32_t>();
  if (!r.ok || signs.size() != at.size() || first.size() != at.size()) return false;
  if (!at.empty()) b.rim.assign(kRim, Block::CellInfo{});
  for (size_t i = 0; i < at.size(); ++i) {
    if (at[i] >= kRim) return false;
    b.rim[at[i]] = {static_cast<uint8_t>(signs[i]), static_cast<uint8_t>(signs[i] >> 8), first[i]};
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
