// The tubes of dual contouring (dc_tubes.h): each cell's sides of cut segments recorded while its
// sheets are made, both sides paired once every block is numbered, and the gaps closed.
#include "runtime/mesh/dc_tubes.h"

#include <algorithm>
#include <tuple>

#include "runtime/mesh/dc_cells.h"

namespace fscript::mesh {
namespace {

// Whether the polygon of the crossing along `axis` from local sample `lower` (inside there or not)
// runs from cell `from` to cell `to` (two of its four cells), as polygons() winds it.
bool winds(const int lower[3], int axis, bool lower_inside, const int from[3], const int to[3]) {
  Crossing c{};
  for (int a = 0; a < 3; ++a) c.l[a] = static_cast<uint8_t>(lower[a]);
  c.axis = static_cast<uint8_t>(axis), c.lower_inside = lower_inside;
  int cells[4][3], q_from = -1, q_to = -1;
  cells_of(c, cells);
  for (int q = 0; q < 4; ++q) {
    bool is_from = true, is_to = true;
    for (int a = 0; a < 3; ++a) is_from &= cells[q][a] == from[a], is_to &= cells[q][a] == to[a];
    if (is_from) q_from = q;
    if (is_to) q_to = q;
  }
  return lower_inside ? q_to == (q_from + 1) % 4 : q_to == (q_from + 3) % 4;
}

// The cube edge at face-local place `k` of face `face` (2 * axis + side).
int edge_at(int face, int k) {
  int axis = face / 2, side = face % 2, p0 = axis == 0 ? 1 : 0, p1 = axis == 2 ? 1 : 2;
  int along = k < 2 ? p0 : p1, across = k < 2 ? p1 : p0;
  int c = side << axis | (k & 1) << across;
  return cube_edge(c, c | 1 << along);
}

class Recorder {
 public:
  Recorder(const BlockGrid& grid, Block& b) : grid_(grid), b_(b) {}

  // The corners of cell l (block-local, any cell of the lattice).
  unsigned mask(const int l[3]) const {
    bool here = true;
    for (int a = 0; a < 3; ++a) here &= l[a] >= 0 && l[a] < b_.m[a];
    if (here) {
      unsigned m = 0;
      for (int q = 0; q < 8; ++q) m |= static_cast<unsigned>(b_.inside(l[0] + (q & 1), l[1] + (q >> 1 & 1), l[2] + (q >> 2 & 1))) << q;
      return m;
    }
    int cell[3] = {b_.s0[0] + l[0], b_.s0[1] + l[1], b_.s0[2] + l[2]};
    return grid_.mask(cell);
  }
  uint8_t tubes(const int l[3], unsigned inside) const {
    if (!ambiguous_faces(inside)) return 0;
    unsigned around[6] = {};
    for (int f = 0; f < 6; ++f) {
      int o[3] = {l[0], l[1], l[2]};
      o[f / 2] += f % 2 ? 1 : -1;
      around[f] = mask(o);
    }
    return tube_faces(inside, around);
  }
  // Whether cell l cuts its loops (tube faces, or a joined middle).
  bool cuts(const int l[3]) const {
    unsigned m = mask(l);
    return joins_middle(m) || tubes(l, m);
  }
  bool here(const int l[3]) const {
    for (int a = 0; a < 3; ++a)
      if (l[a] < 0 || l[a] >= b_.m[a]) return false;
    return true;
  }

  // Every segment cut on the faces of cell l (in the block), by it or by the cell across, recorded
  // with its pieces; and its own loops' middles.
  void cell(const int l[3]) {
    const Block::CellInfo& info = b_.cells[Block::cell(l[0], l[1], l[2])];
    if (info.first == kNone) return;
    uint8_t segments[6] = {};  // per face: the segments cut there, a bit per pair of face edges
    auto add = [&](const CellCuts& cc, int face_of_mine, bool across) {
      for (int i = 0; i < cc.n_cuts; ++i) {
        const LoopCut& c = cc.cuts[i];
        int face = across ? (c.face ^ 1) : c.face;
        if (across && face != face_of_mine) continue;
        int axis = face / 2, k0 = face_edge(c.from, axis), k1 = face_edge(c.to, axis);
        segments[face] |= static_cast<uint8_t>(1u << segment_index(k0, k1));
      }
    };
    bool cut_here = (info.flips & Block::kTubes) || joins_middle(info.mask);
    if (cut_here) add(cell_cuts(info.mask, info.flips & Block::kTubes), -1, false);
    for (int f = 0; f < 6; ++f) {
      int o[3] = {l[0], l[1], l[2]};
      o[f / 2] += f % 2 ? 1 : -1;
      unsigned there = mask(o);
      uint8_t t = tubes(o, there);
      if (t || joins_middle(there)) add(cell_cuts(there, t), f, true);
    }
    for (int f = 0; f < 6; ++f)
      for (int s = 0; s < 6; ++s)
        if (segments[f] >> s & 1u) record(l, info, f, s);
    if (cut_here) own_triangles(info);
  }

 private:
  // The six pairs of a face's four edges, numbered.
  static int segment_index(int k0, int k1) {
    static constexpr int index[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};
    return index[k0][k1];
  }
  static void segment_edges(int s, int& k0, int& k1) {
    static constexpr int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    k0 = pairs[s][0], k1 = pairs[s][1];
  }

  void record(const int l[3], const Block::CellInfo& info, int face, int s) {
    int axis = face / 2, side = face % 2, k0, k1;
    segment_edges(s, k0, k1);
    TubeCut cut;
    for (int a = 0; a < 3; ++a) cut.face[a] = b_.s0[a] + l[a] + (a == axis ? side : 0);
    cut.axis = static_cast<uint8_t>(axis), cut.segment = static_cast<uint8_t>(1u << k0 | 1u << k1);
    cut.high = static_cast<uint8_t>(!side);
    int other[3] = {l[0], l[1], l[2]};
    other[axis] += side ? 1 : -1;
    const int* low = side ? l : other;
    const int* high = side ? other : l;
    uint32_t sheet[2];
    for (int k = 0; k < 2; ++k) {
      int e = edge_at(face, k ? k1 : k0), c = edge_corner(e), d = c | 1 << (e / 4);
      int in = (info.mask >> c) & 1u ? c : d;
      sheet[k] = b_.sheet(info, in, in ^ (c ^ d));
      if (k == 0) {
        int lower[3] = {l[0] + (c & 1), l[1] + (c >> 1 & 1), l[2] + (c >> 2 & 1)};
        cut.forward = winds(lower, e / 4, (info.mask >> c) & 1u, low, high);
      }
    }
    if (sheet[0] == kNone || sheet[1] == kNone) return;
    cut.first = sheet[0], cut.second = sheet[1];
    b_.cuts.push_back(cut);
  }

  // The triangles among the cell's own pieces (cell_cuts).
  void own_triangles(const Block::CellInfo& info) {
    CellCuts cc = cell_cuts(info.mask, info.flips & Block::kTubes);
    for (int t = 0; t < cc.n_tris; ++t) {
      std::array<uint32_t, 3> tri;
      for (int k = 0; k < 3; ++k) {
        int e = cc.tris[t][static_cast<size_t>(k)], c = edge_corner(e), d = c | 1 << (e / 4);
        int in = (info.mask >> c) & 1u ? c : d;
        tri[static_cast<size_t>(k)] = b_.sheet(info, in, in ^ (c ^ d));
      }
      if (tri[0] != kNone && tri[1] != kNone && tri[2] != kNone) b_.fans.push_back(tri);
    }
  }

  const BlockGrid& grid_;
  Block& b_;
};

}  // namespace

void record_cuts(const BlockGrid& grid, Block& b, const std::vector<size_t>& tube_cells) {
  b.cuts.clear(), b.fans.clear();
  Recorder r(grid, b);
  // The cells that may meet a cut: those with tube faces, the block's cells beside them, and every
  // cell on the block's faces (the cell across may be another block's).
  std::vector<size_t> cells;
  auto position = [](size_t c, int l[3]) {
    l[0] = static_cast<int>(c % kBlock), l[1] = static_cast<int>(c / kBlock % kBlock), l[2] = static_cast<int>(c / kBlock / kBlock);
  };
  for (size_t c : tube_cells) {
    cells.push_back(c);
    int l[3];
    position(c, l);
    for (int f = 0; f < 6; ++f) {
      int o[3] = {l[0], l[1], l[2]};
      o[f / 2] += f % 2 ? 1 : -1;
      if (r.here(o)) cells.push_back(Block::cell(o[0], o[1], o[2]));
    }
  }
  for (int k = 0; k < b.m[2]; ++k)
    for (int j = 0; j < b.m[1]; ++j)
      for (int i = 0; i < b.m[0]; ++i) {
        bool rim = i == 0 || j == 0 || k == 0 || i == b.m[0] - 1 || j == b.m[1] - 1 || k == b.m[2] - 1;
        if (!rim) {
          i = std::max(i, b.m[0] - 2);  // jump across the block's inside
          continue;
        }
        size_t c = Block::cell(i, j, k);
        if (b.cells[c].first == kNone) continue;
        int l[3] = {i, j, k};
        bool near_tube = false;
        for (int f = 0; f < 6 && !near_tube; ++f) {
          int o[3] = {l[0], l[1], l[2]};
          o[f / 2] += f % 2 ? 1 : -1;
          near_tube = !r.here(o) && r.cuts(o);
        }
        if (near_tube) cells.push_back(c);
      }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  for (size_t c : cells) {
    int l[3];
    position(c, l);
    r.cell(l);
  }
}

void close_tubes(std::vector<TubeCut> cuts, Mesh& out) {
  auto key = [](const TubeCut& c) { return std::make_tuple(c.face[2], c.face[1], c.face[0], c.axis, c.segment, c.high); };
  std::sort(cuts.begin(), cuts.end(), [&](const TubeCut& x, const TubeCut& y) { return key(x) < key(y); });
  auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    if (a != b && b != c && a != c) out.triangles.push_back({a, b, c});
  };
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const TubeCut &lo = cuts[i], &hi = cuts[i + 1];
    if (!lo.same_segment(hi) || lo.high || !hi.high) continue;
    // The first crossing's polygon has the edge lo.first -> hi.first (forward) or back, the second's
    // the other way between the second pieces: the triangles hold both edges reversed.
    if (lo.forward) {
      add(hi.first, lo.first, lo.second);
      add(hi.first, lo.second, hi.second);
    } else {
      add(lo.first, hi.first, hi.second);
      add(lo.first, hi.second, lo.second);
    }
    ++i;
  }
}

}  // namespace fscript::mesh
