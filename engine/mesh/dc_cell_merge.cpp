// The octree of merged dual cells: levels inside a block on dense arrays, then levels above the
// blocks over a hash of the blocks that merged whole; each sheet's vertex is its topmost merged cell.
#include "engine/mesh/dc_cell_merge.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/mesh/flat_index.h"

namespace fscript::mesh {
namespace {

// The mean squared distance from a solution to the QEF's planes: compared with the tolerance
// squared, so the square root (on every solve's dependency chain) is taken only for the stats.
double mean_square(const Qef& q, const Qef::Solution& s) {
  return s.error / static_cast<double>(std::max<size_t>(q.count(), 1));
}

// Per sample of a node's 3x3x3 (corners, edge and face midpoints, centre; p = i + 3j + 9k), the
// corners of the edge, face or body it is the middle of (bits c = i/2 + 2 j/2 + 4 k/2); 0 for corners.
const std::array<uint8_t, 27>& middle_of() {
  static const auto t = [] {
    std::array<uint8_t, 27> out{};
    for (int p = 0; p < 27; ++p) {
      int q[3] = {p % 3, p / 3 % 3, p / 9};
      if (q[0] != 1 && q[1] != 1 && q[2] != 1) continue;
      for (int c = 0; c < 8; ++c) {
        bool on = true;
        for (int a = 0; a < 3; ++a) on = on && (q[a] == 1 || q[a] == 2 * (c >> a & 1));
        out[static_cast<size_t>(p)] |= static_cast<uint8_t>(on << c);
      }
    }
    return out;
  }();
  return t;
}

// The signs of the 27 samples of a node whose lowest sample is s0 and whose side is 2 * half: bit p
// (p = i + 3j + 9k) set where sample s0 + half * (i, j, k) is inside.
template <class Inside>
uint32_t node_samples(Inside inside, const int s0[3], int half) {
  uint32_t in = 0;
  for (int p = 0; p < 27; ++p)
    in |= static_cast<uint32_t>(inside(s0[0] + p % 3 * half, s0[1] + p / 3 % 3 * half, s0[2] + p / 9 * half)) << p;
  return in;
}

// The same for a node inside a block (s0 in the block's samples), three samples of a row at a time.
uint32_t node_samples(const Block& b, const int s0[3], int half) {
  uint32_t in = 0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) {
      uint32_t r = b.rows[s0[2] + k * half][s0[1] + j * half] >> s0[0];
      in |= ((r & 1) | (r >> half & 1) << 1 | (r >> 2 * half & 1) << 2) << (3 * j + 9 * k);
    }
  return in;
}

// Whether any of the 36 squares of the 3x3x3 samples (four per face of each child, faces inside
// the node too) is ambiguous: corners a, d of one sign and b, c of the other ([[a b] [c d]]). Bit
// parallel: the squares normal to each axis, their lowest samples picked by a mask.
constexpr uint32_t lowest_samples(int ni, int nj, int nk) {
  uint32_t m = 0;
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) m |= 1u << (i + 3 * j + 9 * k);
  return m;
}

bool ambiguous_square(uint32_t in) {
  auto diagonal = [in](int b, int c, int d, uint32_t lowest) {
    uint32_t A = in, B = in >> b, C = in >> c, D = in >> d;
    return (~(A ^ D) & ~(B ^ C) & (A ^ B) & lowest) != 0;
  };
  // Lowest samples (i, j, k) with i, j < 2 (squares normal to z), i, k < 2 (y), j, k < 2 (x).
  constexpr uint32_t kZ = lowest_samples(2, 2, 3), kY = lowest_samples(2, 3, 2), kX = lowest_samples(3, 2, 2);
  return diagonal(1, 3, 4, kZ) || diagonal(1, 9, 10, kY) || diagonal(3, 9, 12, kX);
}

// Whether a node allows one vertex, from its 27 samples (node_samples): one sheet, no ambiguous
// face, and every midpoint agreeing in sign with a corner of the edge, face or body it is the
// middle of. Its children's faces must not be ambiguous either: a cell of one sheet may still
// have one (its sheet then crosses that face twice), and a node over it can meet its own boundary
// in two loops, whose polygons then share the node's one vertex as two fans (a pinched,
// non-manifold vertex: three in the gyroid ∩ sphere at 256^3).
bool topology_safe(uint32_t in) {
  if (ambiguous_square(in)) return false;
  const std::array<uint8_t, 27>& middle = middle_of();
  unsigned corners = 0;
  for (int c = 0; c < 8; ++c) corners |= (in >> ((c & 1) * 2 + (c >> 1 & 1) * 6 + (c >> 2 & 1) * 18) & 1u) << c;
  if (ambiguous_faces(corners)) return false;
  const CellSigns& cs = signs_of(corners, 0);
  if (cs.regions_in != 1 || cs.regions_out != 1) return false;
  for (int p = 0; p < 27; ++p) {
    unsigned around = middle[static_cast<size_t>(p)];  // agrees: some corner around it has its sign
    if (around && !((in >> p & 1) ? (corners & around) : (~corners & around))) return false;
  }
  return true;
}

enum class State : uint8_t { Empty, Merged, Kept };  // no surface; one vertex; its cells keep theirs

struct Node {
  Qef qef;
  double x[3] = {0, 0, 0};
  double mean_square = 0;  // of its planes' distances
  State state = State::Empty;
};

// What a parent needs of a child: a cell of the block (a sheet's planes) or a node.
struct Child {
  State state;
  const Qef* qef;
};

// A node of lattice cells c0 .. c0 + size - 1 per axis from its children, into `out` (as made,
// empty), in place: a Node is 176 bytes and a block makes hundreds. Merged when every child with
// surface is merged, the topology allows it and the vertex stays within the tolerance.
template <class Samples, class ChildAt>
void collapse(const Lattice& g, Samples samples, ChildAt child, const int c0[3], int size, double limit2, Node& out) {
  bool any = false;
  for (int c = 0; c < 8; ++c) {
    Child n = child(c);
    if (n.state == State::Empty) continue;  // no surface in it: all its samples have one sign
    any = true;
    if (n.state == State::Kept) out.state = State::Kept;
    out.qef.merge(*n.qef);
  }
  if (!any || out.state == State::Kept) return;
  out.state = State::Kept;
  for (int a = 0; a < 3; ++a)
    if (c0[a] + size > g.n[a]) return;  // past the last cell
  if (!topology_safe(samples())) return;
  Qef::Solution s = solve_in_cells(g, out.qef, c0, size);
  out.mean_square = mean_square(out.qef, s);
  if (out.mean_square > limit2) return;
  std::copy(s.x, s.x + 3, out.x);
  out.state = State::Merged;
}

// The block's octree levels above its cells: the nodes with surface, found through a dense slot
// array per level ((kBlock >> L)^3 positions), so empty space costs nothing.
struct BlockTree {
  static constexpr uint16_t kEmpty = 0xffff;
  std::vector<uint16_t> slot[kBlockLevels + 1];  // per position: its node, or kEmpty
  std::vector<Node> nodes[kBlockLevels + 1];     // in the order their first sheet names them
  std::vector<uint32_t> where[kBlockLevels + 1];  // each node's position
  int built = 0;  // levels above this one merged nothing (not built)

  static size_t index(int level, const int u[3]) {
    size_t side = static_cast<size_t>(kBlock >> level);
    return (static_cast<size_t>(u[2]) * side + static_cast<size_t>(u[1])) * side + static_cast<size_t>(u[0]);
  }
  static void position(int level, size_t at, int u[3]) {
    int side = kBlock >> level;
    u[0] = static_cast<int>(at % side), u[1] = static_cast<int>(at / side % side),
    u[2] = static_cast<int>(at / side / side);
  }
  const Node* at(int level, const int u[3]) const {
    uint16_t s = slot[level][index(level, u)];
    return s == kEmpty ? nullptr : &nodes[level][s];
  }
  // Level 0: the block's cells, as their sheets say (a vertex per sheet where there are several).
  static Child leaf(const Block& b, const std::vector<Qef>& qefs, size_t c) {
    uint32_t first = b.cells[c].first;
    if (first == kNone) return {State::Empty, nullptr};
    return {b.sheets[first].next() == kNone ? State::Merged : State::Kept, &qefs[first]};
  }
  // The level's nodes: the parents of the level below's (of the cells with sheets for level 1).
  void make_level(const Block& b, int l) {
    int side = kBlock >> l;
    slot[l].assign(static_cast<size_t>(side) * side * side, kEmpty);
    nodes[l].clear(), where[l].clear();
    auto add = [&](const int child[3]) {
      int u[3] = {child[0] / 2, child[1] / 2, child[2] / 2};
      size_t at = index(l, u);
      if (slot[l][at] != kEmpty) return;
      slot[l][at] = static_cast<uint16_t>(nodes[l].size());
      nodes[l].emplace_back(), where[l].push_back(static_cast<uint32_t>(at));
    };
    if (l == 1) {
      for (const Sheet& s : b.sheets) {
        int c[3];
        position(0, s.cell, c);  // level 0: the block's cells
        add(c);
      }
      return;
    }
    for (uint32_t at : where[l - 1]) {
      int u[3];
      position(l - 1, at, u);
      add(u);
    }
  }
  void grow(const Lattice& g, const Block& b, const std::vector<Qef>& qefs, double limit2) {
    for (int l = 1; l <= kBlockLevels; ++l) {
      make_level(b, l);
      int size = 1 << l;
      bool any = false;
      for (size_t q = 0; q < nodes[l].size(); ++q) {
        int u[3], cell[3];
        position(l, where[l][q], u);
        for (int a = 0; a < 3; ++a) cell[a] = b.s0[a] + u[a] * size;
        auto child = [&](int c) {
          int v[3] = {2 * u[0] + (c & 1), 2 * u[1] + (c >> 1 & 1), 2 * u[2] + (c >> 2 & 1)};
          if (l == 1) return leaf(b, qefs, Block::cell(v[0], v[1], v[2]));
          const Node* n = at(l - 1, v);
          return n ? Child{n->state, &n->qef} : Child{State::Empty, nullptr};
        };
        int s0[3] = {u[0] * size, u[1] * size, u[2] * size};
        auto samples = [&] { return node_samples(b, s0, size / 2); };
        collapse(g, samples, child, cell, size, limit2, nodes[l][q]);
        any = any || nodes[l][q].state == State::Merged;
      }
      built = l;
      if (!any) return;
    }
  }
  // The topmost merged level above cell c (0: the cell itself).
  int top(const int c[3]) const {
    int l = 0;
    while (l < built) {
      int u[3] = {c[0] >> (l + 1), c[1] >> (l + 1), c[2] >> (l + 1)};
      const Node* n = at(l + 1, u);
      if (!n || n->state != State::Merged) break;
      ++l;
    }
    return l;
  }
};

// A node above the blocks: level L covers lattice cells u * 2^L - 1 .. (u + 1) * 2^L - 2 per axis.
uint64_t node_key(int level, const int u[3]) {
  return static_cast<uint64_t>(level) << 57 | static_cast<uint64_t>(u[0]) << 38 | static_cast<uint64_t>(u[1]) << 19 |
      static_cast<uint64_t>(u[2]);
}

// One level above the blocks, its nodes in the order they were made, found by key.
struct Level {
  FlatIndex index;
  std::vector<uint64_t> keys;
  std::vector<Node> nodes;
  const Node* find(uint64_t key) const {
    const uint32_t* i = index.find(key);
    return i ? &nodes[*i] : nullptr;
  }
  void add(uint64_t key, const Node& n) {
    index.try_emplace(key, static_cast<uint32_t>(nodes.size()));
    keys.push_back(key), nodes.push_back(n);
  }
};

void node_position(uint64_t key, int u[3]) {
  u[0] = static_cast<int>(key >> 38 & 0x7ffff), u[1] = static_cast<int>(key >> 19 & 0x7ffff),
  u[2] = static_cast<int>(key & 0x7ffff);
}

uint64_t parent(uint64_t key) {
  int u[3];
  node_position(key, u);
  for (int& c : u) c /= 2;
  return node_key(static_cast<int>(key >> 57) + 1, u);
}

}  // namespace

Qef::Solution solve_in_cells(const Lattice& g, const Qef& qef, const int c0[3], int size) {
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {  // a padding cell ends at the box face; see kReach for the widening
    lo[a] = std::max(g.coord(a, c0[a]) - kReach * g.h[a], g.lo[a]);
    hi[a] = std::min(g.coord(a, c0[a] + size) + kReach * g.h[a], g.end(a));
  }
  return qef.solve(lo, hi);
}

namespace {

// Whether block sample s (inside) is one sample thick across `axis`: outside on both sides.
bool thin(const Block& b, const int s[3], int axis) {
  int lo[3] = {s[0], s[1], s[2]}, hi[3] = {s[0], s[1], s[2]};
  --lo[axis], ++hi[axis];
  if (lo[axis] < 0 || hi[axis] > b.m[axis]) return false;
  return !b.inside(lo[0], lo[1], lo[2]) && !b.inside(hi[0], hi[1], hi[2]);
}

// Vertices that leave their cells (kReach) can pass each other where the solid is thinner than a
// cell, and turn a sliver inside out (the gyroid cut by a ball along its seam). Their polygons then
// wind the wrong way round their crossings: the four cells' vertices of a polygon over cells of
// the block, seen along its crossing's axis, go round the edge the other way. Where that happens at
// a crossing whose inside sample is a sheet of solid one sample thick (thin across the crossing, or
// across exactly one axis), the polygon's vertices go back into their own cells, where four
// vertices always go round their edge the right way. A sharp edge's or corner's tip is thin across
// two or three axes, along another than its crossings': reaching out of its cell (kReach's
// purpose), it keeps its place.
// Merged vertices (one for several sheets) stay too: their cells span several, and they are flat.
void unfold(const Lattice& g, Block& b, std::vector<std::array<float, 3>>& positions) {
  std::vector<uint32_t> back;  // few: only where slivers fold
  for (size_t e = 0; e < b.xs.size(); ++e) {
    const Crossing& c = b.xs[e];
    uint32_t ring[4];
    bool here = true;
    for (size_t q = 0; q < 4 && here; ++q)
      here = b.ids[e][q] != Block::kNoSheet, ring[q] = here ? b.vertex[b.ids[e][q]] : 0;
    if (!here) continue;
    int u = kNextAxis[c.axis], w = kNextAxis[u];
    double area = 0;  // cells_of's order goes round the edge counter-clockwise about its axis
    for (int q = 0; q < 4; ++q) {
      const auto &p = positions[ring[q]], &n = positions[ring[(q + 1) % 4]];
      area += double(p[u]) * n[w] - double(p[w]) * n[u];
    }
    if (area >= 0) continue;
    int in[3] = {c.l[0], c.l[1], c.l[2]};
    if (!c.lower_inside) ++in[c.axis];
    int thin_axes = 0;
    for (int a = 0; a < 3; ++a) thin_axes += thin(b, in, a);
    if (!thin(b, in, c.axis) && thin_axes != 1) continue;
    back.insert(back.end(), ring, ring + 4);
  }
  if (back.empty()) return;
  std::sort(back.begin(), back.end());
  back.erase(std::unique(back.begin(), back.end()), back.end());
  std::vector<uint8_t> sheets_of(back.size(), 0);  // a merged vertex stands for several sheets
  for (size_t s = 0; s < b.sheets.size(); ++s) {
    auto it = std::lower_bound(back.begin(), back.end(), b.vertex[s]);
    if (it != back.end() && *it == b.vertex[s]) sheets_of[static_cast<size_t>(it - back.begin())] += 1;
  }
  for (size_t s = 0; s < b.sheets.size(); ++s) {
    uint32_t v = b.vertex[s];
    auto it = std::lower_bound(back.begin(), back.end(), v);
    if (it == back.end() || *it != v || sheets_of[static_cast<size_t>(it - back.begin())] != 1) continue;
    int c[3] = {b.sheets[s].cell % kBlock, b.sheets[s].cell / kBlock % kBlock, b.sheets[s].cell / kBlock / kBlock};
    for (int a = 0; a < 3; ++a) {
      double lo = std::max(g.coord(a, b.s0[a] + c[a]), g.lo[a]),
             hi = std::min(g.coord(a, b.s0[a] + c[a] + 1), g.end(a));
      auto& x = positions[v][static_cast<size_t>(a)];
      x = static_cast<float>(std::clamp(double(x), lo, hi));
    }
  }
}

}  // namespace

void merge_block(const Lattice& g, Block& b, const std::vector<Qef>& qefs, double tolerance) {
  thread_local BlockTree tree;
  double limit = tolerance * std::min({g.h[0], g.h[1], g.h[2]});
  tree.built = 0;
  if (tolerance > 0) tree.grow(g, b, qefs, limit * limit);
  b.vertex.assign(b.sheets.size(), kNone);
  b.merged = 0;
  // Made in buffers of the thread, the block keeping exactly its vertices' room.
  thread_local std::vector<std::array<float, 3>> positions;
  thread_local std::vector<uint32_t> node_vertex[kBlockLevels + 1];
  positions.clear();
  double max_square = 0;
  auto add = [&](const double x[3], double square) {
    positions.push_back({float(x[0]), float(x[1]), float(x[2])}), max_square = std::max(max_square, square);
  };
  for (int l = 1; l <= tree.built; ++l) node_vertex[l].assign(tree.nodes[l].size(), kNone);
  for (size_t s = 0; s < b.sheets.size(); ++s) {
    const Sheet& sh = b.sheets[s];
    int c[3];
    BlockTree::position(0, sh.cell, c);
    int l = tree.top(c);
    uint32_t* named = nullptr;
    if (l > 0) {
      int u[3] = {c[0] >> l, c[1] >> l, c[2] >> l};
      uint16_t q = tree.slot[l][BlockTree::index(l, u)];
      named = &node_vertex[l][q];
      if (*named != kNone) {
        b.vertex[s] = *named;
        continue;
      }
      const Node& n = tree.nodes[l][q];
      add(n.x, n.mean_square), ++b.merged;
    } else {  // a cell of the uniform grid: its vertex now
      int cell[3] = {b.s0[0] + c[0], b.s0[1] + c[1], b.s0[2] + c[2]};
      Qef::Solution sol = solve_in_cells(g, qefs[s], cell, 1);
      add(sol.x, mean_square(qefs[s], sol));
    }
    b.vertex[s] = static_cast<uint32_t>(positions.size() - 1);
    if (named) *named = b.vertex[s];
  }
  unfold(g, b, positions);
  b.positions.assign(positions.begin(), positions.end());
  b.max_rms = std::sqrt(max_square);
  b.root = tree.built == kBlockLevels && tree.nodes[kBlockLevels].size() == 1 &&
      tree.nodes[kBlockLevels][0].state == State::Merged;
  b.root_qef = b.root ? tree.nodes[kBlockLevels][0].qef : Qef{};
}

std::vector<int32_t> merge_blocks(const BlockGrid& grid, double tolerance, std::vector<BlockGroup>& groups) {
  const Lattice& g = grid.lattice();
  const std::vector<Block>& blocks = grid.blocks();
  std::vector<int32_t> group(blocks.size(), -1);
  groups.clear();
  if (!(tolerance > 0)) return group;
  double limit = tolerance * std::min({g.h[0], g.h[1], g.h[2]});
  std::vector<Level> levels(1);
  for (const Block& b : blocks)
    if (!b.positions.empty()) {  // it has sheets (each has a vertex); in a join, only its vertices are known
      Node n;
      n.state = b.root ? State::Merged : State::Kept;
      n.qef = b.root_qef;
      levels[0].add(node_key(kBlockLevels, b.b), n);
    }
  auto inside = [&](int i, int j, int k) { return grid.inside(i, j, k); };
  for (int l = kBlockLevels + 1; l < 19; ++l) {
    const Level& below = levels.back();
    Level next;
    bool any = false;
    for (uint64_t child : below.keys) {
      uint64_t p = parent(child);
      if (next.find(p)) continue;
      int u[3], c0[3], size = 1 << l;
      node_position(p, u);
      for (int a = 0; a < 3; ++a) c0[a] = u[a] * size - 1;
      auto child_at = [&](int c) {
        int v[3] = {2 * u[0] + (c & 1), 2 * u[1] + (c >> 1 & 1), 2 * u[2] + (c >> 2 & 1)};
        const Node* n = below.find(node_key(l - 1, v));
        return n ? Child{n->state, &n->qef} : Child{State::Empty, nullptr};
      };
      auto samples = [&] { return node_samples(inside, c0, size / 2); };
      Node n;
      collapse(g, samples, child_at, c0, size, limit * limit, n);
      next.add(p, n);
      any = any || next.nodes.back().state == State::Merged;
    }
    levels.push_back(std::move(next));
    if (!any) break;
  }
  FlatIndex named(16);
  for (size_t i = 0; i < blocks.size(); ++i) {
    if (!blocks[i].root) continue;
    uint64_t key = node_key(kBlockLevels, blocks[i].b), top = key;
    for (size_t l = 1; l < levels.size(); ++l) {
      key = parent(key);
      const Node* n = levels[l].find(key);
      if (!n || n->state != State::Merged) break;
      top = key;
    }
    if (top == node_key(kBlockLevels, blocks[i].b)) continue;  // the block's own root
    auto [at, fresh] = named.try_emplace(top, static_cast<uint32_t>(groups.size()));
    if (fresh) {
      const Node& n = *levels[static_cast<size_t>((top >> 57) - kBlockLevels)].find(top);
      groups.push_back(BlockGroup{top, {n.x[0], n.x[1], n.x[2]}, std::sqrt(n.mean_square)});
    }
    group[i] = static_cast<int32_t>(at);
  }
  return group;
}

void number_blocks(const BlockGrid& grid, const std::vector<int32_t>& group, const std::vector<BlockGroup>& groups,
                   Mesh& out, DualContourStats& stats, std::vector<uint32_t>& base, std::vector<bool>& grouped) {
  const std::vector<Block>& blocks = grid.blocks();
  std::vector<uint32_t> group_vertex(groups.size(), kNone);
  base.assign(blocks.size(), kNone), grouped.assign(blocks.size(), false);
  double h = std::min({grid.lattice().h[0], grid.lattice().h[1], grid.lattice().h[2]});
  size_t total = groups.size();
  for (const Block& b : blocks) total += b.positions.size();
  out.positions.reserve(total + total / 8);  // and the copies dc_normals splits off, without a move
  for (size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.positions.empty()) continue;
    if (group[i] >= 0) {
      const BlockGroup& bg = groups[static_cast<size_t>(group[i])];
      uint32_t& v = group_vertex[static_cast<size_t>(group[i])];
      if (v == kNone) {
        out.positions.push_back({float(bg.x[0]), float(bg.x[1]), float(bg.x[2])});
        v = static_cast<uint32_t>(out.positions.size() - 1), ++stats.merged;
        stats.max_error = std::max(stats.max_error, bg.rms / h);
      }
      base[i] = v, grouped[i] = true;
      continue;
    }
    base[i] = static_cast<uint32_t>(out.positions.size());
    out.positions.insert(out.positions.end(), b.positions.begin(), b.positions.end());
    stats.max_error = std::max(stats.max_error, b.max_rms / h);
    stats.merged += b.merged;
  }
  stats.cells = out.positions.size();
}

}  // namespace fscript::mesh
