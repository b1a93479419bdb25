// The octree of merged dual cells, built bottom-up one level at a time over the cells that hold
// surface, and each sheet's leaf found by climbing it.
#include "runtime/mesh/dc_octree.h"

#include <algorithm>
#include <cmath>

#include "runtime/mesh/flat_index.h"

namespace fscript::mesh {
namespace {

// A node of level L covers dual cells u * 2^L .. (u + 1) * 2^L - 1 per axis, counted from the
// lowest cell (-1): 19 bits per axis, the level above them.
uint64_t node_key(int level, const int u[3]) {
  return static_cast<uint64_t>(level) << 57 | static_cast<uint64_t>(u[0]) << 38 | static_cast<uint64_t>(u[1]) << 19 |
         static_cast<uint64_t>(u[2]);
}

// The node's position: u of node_key.
void node_cells(uint64_t key, int u[3]) {
  u[0] = static_cast<int>(key >> 38 & 0x7ffff), u[1] = static_cast<int>(key >> 19 & 0x7ffff), u[2] = static_cast<int>(key & 0x7ffff);
}

// The root-mean-square distance from a solution to the QEF's planes.
double rms(const Qef& q, const Qef::Solution& s) {
  return std::sqrt(s.error / static_cast<double>(std::max<size_t>(q.count(), 1)));
}

struct Node {
  Qef qef;
  double x[3] = {0, 0, 0};
  double rms = 0;
  bool merged = false;  // one vertex for the whole node; false: its cells keep their own
};

// One level's nodes in the order they were made (a deterministic order), found by key.
struct Level {
  FlatIndex index;
  std::vector<uint64_t> keys;
  std::vector<Node> nodes;
  const Node* find(uint64_t key) const {
    const uint32_t* i = index.find(key);
    return i ? &nodes[*i] : nullptr;
  }
};

// Whether the node's 27 samples (corners, edge and face midpoints, centre) allow one vertex: one
// sheet, no ambiguous face, and every midpoint agreeing with a corner of the edge, face or body
// it is the middle of.
bool topology_safe(const Lattice& g, const int s0[3], int half) {
  bool in[3][3][3];
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) in[k][j][i] = g.inside(s0[0] + i * half, s0[1] + j * half, s0[2] + k * half);
  unsigned corners = 0;
  for (int c = 0; c < 8; ++c) corners |= static_cast<unsigned>(in[c >> 2 & 1 ? 2 : 0][c >> 1 & 1 ? 2 : 0][c & 1 ? 2 : 0]) << c;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      if (ambiguous_face(corners, axis, side)) return false;
  const CellSigns& cs = signs_of(corners, 0);
  if (cs.regions_in != 1 || cs.regions_out != 1) return false;
  for (int p = 0; p < 27; ++p) {
    int q[3] = {p % 3, p / 3 % 3, p / 9};
    int mids = (q[0] == 1) + (q[1] == 1) + (q[2] == 1);
    if (mids == 0) continue;
    bool agrees = false;  // with a corner got by moving each middle coordinate to an end
    for (int e = 0; e < 8 && !agrees; ++e) {
      int r[3];
      for (int a = 0; a < 3; ++a) r[a] = q[a] == 1 ? (e >> a & 1) * 2 : q[a];
      agrees = in[r[2]][r[1]][r[0]] == in[q[2]][q[1]][q[0]];
    }
    if (!agrees) return false;
  }
  return true;
}

class Merger {
 public:
  Merger(const Lattice& g, double tolerance) : g_(g), tol_(tolerance) {
    h_ = std::min({g.h[0], g.h[1], g.h[2]});
  }

  void leaves(const std::vector<SheetVertex>& sheets) {
    levels_.emplace_back();
    Level& l = levels_[0];
    for (const SheetVertex& s : sheets) {
      int u[3] = {s.cell[0] + 1, s.cell[1] + 1, s.cell[2] + 1};
      uint64_t key = node_key(0, u);
      auto [i, fresh] = l.index.try_emplace(key, static_cast<uint32_t>(l.nodes.size()));
      if (!fresh) {
        l.nodes[i].merged = false;  // a second sheet in the cell: it keeps its vertices
        continue;
      }
      Node n;  // its vertex is solved only if no parent takes it (merge_cells)
      n.merged = true;
      n.qef = s.qef;
      l.keys.push_back(key), l.nodes.push_back(n);
    }
  }

  // Level after level, every parent of the level below tries to merge; stops at a level where none does.
  void grow() {
    for (int level = 1; level < 19; ++level) {
      Level next;
      bool any = false;
      for (uint64_t child : levels_.back().keys) {
        uint64_t p = parent(child);
        if (!next.index.try_emplace(p, static_cast<uint32_t>(next.nodes.size())).second) continue;
        next.keys.push_back(p), next.nodes.push_back(collapse(p, level));
        any = any || next.nodes.back().merged;
      }
      levels_.push_back(std::move(next));
      if (!any) return;
    }
  }

  // The topmost merged node above level-0 node `key` (itself when its parent did not merge).
  std::pair<int, uint64_t> leaf(uint64_t key) const {
    int level = 0;
    for (uint64_t up = parent(key); level + 1 < static_cast<int>(levels_.size()); up = parent(up)) {
      const Node* n = levels_[static_cast<size_t>(level + 1)].find(up);
      if (!n || !n->merged) break;
      key = up, ++level;
    }
    return {level, key};
  }
  const Node& node(int level, uint64_t key) const { return *levels_[static_cast<size_t>(level)].find(key); }

 private:
  static uint64_t parent(uint64_t key) {
    int u[3];
    node_cells(key, u);
    for (int& c : u) c /= 2;
    return node_key(static_cast<int>(key >> 57) + 1, u);
  }

  Node collapse(uint64_t key, int level) const {
    Node out;
    int u[3], size = 1 << level, c0[3];  // c0: the first cell, whose lowest corner is the node's
    node_cells(key, u);
    for (int a = 0; a < 3; ++a) {
      if ((u[a] + 1) * size > g_.n[a] + 1) return out;  // past the last cell
      c0[a] = u[a] * size - 1;
    }
    const Level& below = levels_[static_cast<size_t>(level - 1)];
    for (int c = 0; c < 8; ++c) {
      int v[3] = {2 * u[0] + (c & 1), 2 * u[1] + (c >> 1 & 1), 2 * u[2] + (c >> 2 & 1)};
      const Node* child = below.find(node_key(level - 1, v));
      if (!child) continue;  // no surface in it: all its samples have one sign
      if (!child->merged) return out;
      out.qef.merge(child->qef);
    }
    if (!topology_safe(g_, c0, size / 2)) return out;
    Qef::Solution s = solve_in_cells(g_, out.qef, c0, size);
    out.rms = rms(out.qef, s);
    if (out.rms > tol_ * h_) return out;
    std::copy(s.x, s.x + 3, out.x);
    out.merged = true;
    return out;
  }

  const Lattice& g_;
  double tol_, h_;
  std::vector<Level> levels_;
};

}  // namespace

Qef::Solution solve_in_cells(const Lattice& g, const Qef& qef, const int c0[3], int size) {
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {  // a padding cell ends at the box face; see kReach for the widening
    lo[a] = std::max(g.coord(a, c0[a]) - kReach * g.h[a], g.lo[a]);
    hi[a] = std::min(g.coord(a, c0[a] + size) + kReach * g.h[a], g.end(a));
  }
  return qef.solve(lo, hi);
}

MergedVertices merge_cells(const Lattice& g, const std::vector<SheetVertex>& sheets, double tolerance) {
  MergedVertices out;
  Merger m(g, tolerance);
  m.leaves(sheets);
  if (tolerance > 0) m.grow();
  FlatIndex id(sheets.size());  // leaf node, or a sheet of a cell with several (bit 63)
  for (size_t i = 0; i < sheets.size(); ++i) {
    const SheetVertex& s = sheets[i];
    int u[3] = {s.cell[0] + 1, s.cell[1] + 1, s.cell[2] + 1};
    uint64_t cell = node_key(0, u);
    auto [level, key] = m.leaf(cell);
    const Node& n = m.node(level, key);
    bool own = level == 0 && !n.merged;
    auto [vertex, fresh] = id.try_emplace(own ? (uint64_t{1} << 63 | i) : key, static_cast<uint32_t>(out.positions.size()));
    if (fresh) {
      double x[3] = {n.x[0], n.x[1], n.x[2]}, distance = n.rms;
      if (level == 0) {  // a cell of the uniform grid: its vertex now
        Qef::Solution sol = solve_in_cells(g, s.qef, s.cell, 1);
        std::copy(sol.x, sol.x + 3, x);
        distance = rms(s.qef, sol);
      }
      out.positions.push_back({x[0], x[1], x[2]});
      out.rms.push_back(distance);
      out.merged += level > 0;
    }
    out.of_sheet.push_back(vertex);
  }
  return out;
}

}  // namespace fscript::mesh
