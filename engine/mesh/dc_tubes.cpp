// The tubes of dual contouring (dc_tubes.h): each cell's sides of cut segments recorded while its
// sheets are made, both sides paired once every block is numbered, and the gaps closed.
#include "engine/mesh/dc_tubes.h"

#include <algorithm>
#include <tuple>

#include "engine/mesh/dc_cells.h"

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
  Recorder(const BlockGrid& grid, Block& b, uint8_t look_across) : grid_(grid), b_(b), look_across_(look_across) {}

  // The corners of cell l (block-local, any cell of the lattice): the block's own samples where it
  // has them, the grid's for the others.
  unsigned mask(const int l[3]) {
    int outs = 0;
    bool near = true;
    for (int a = 0; a < 3; ++a) outs += l[a] < 0 || l[a] >= b_.m[a], near &= l[a] >= -1 && l[a] <= b_.m[a];
    if (near && outs <= 1) {  // every corner in ext_: two bits a row
      if (!ext_ready_) build_ext();
      int i = l[0] + 1, j = l[1] + 1, k = l[2] + 1;
      auto two = [&](int y, int z) { return ext_[z][y] >> i & 3u; };
      return two(j, k) | two(j + 1, k) << 2 | two(j, k + 1) << 4 | two(j + 1, k + 1) << 6;
    }
    unsigned m = 0;
    for (int q = 0; q < 8; ++q) {
      int s[3] = {l[0] + (q & 1), l[1] + (q >> 1 & 1), l[2] + (q >> 2 & 1)};
      m |= static_cast<unsigned>(inside(s)) << q;
    }
    return m;
  }
  // Sample s (block-local): the block's own or one of the layers just outside its faces (ext_), or
  // the grid's beyond.
  bool inside(const int s[3]) {
    int outs = 0;
    for (int a = 0; a < 3; ++a) outs += s[a] < 0 || s[a] > b_.m[a];
    bool near = true;
    for (int a = 0; a < 3; ++a) near &= s[a] >= -1 && s[a] <= b_.m[a] + 1;
    if (outs <= 1 && near) {
      if (!ext_ready_) build_ext();
      return ext_[s[2] + 1][s[1] + 1] >> (s[0] + 1) & 1u;
    }
    return grid_.inside(b_.s0[0] + s[0], b_.s0[1] + s[1], b_.s0[2] + s[2]);
  }
  // The block's sample rows, one wider on every side (bit x + 1 of row [z + 1][y + 1]): its own and
  // the six layers across its faces.
  void build_ext() {
    std::vector<uint8_t> layer[6];
    for (int f = 0; f < 6; ++f) fill_halo(f, layer[f]);
    auto at = [&](int f, int i, int j) {
      return static_cast<uint32_t>(layer[f][static_cast<size_t>(j * kBlockSamples + i)]);
    };
    for (auto& plane : ext_)
      for (uint32_t& row : plane) row = 0;
    int mx = b_.m[0], my = b_.m[1], mz = b_.m[2];
    for (int k = 0; k <= mz; ++k)
      for (int j = 0; j <= my; ++j)
        ext_[k + 1][j + 1] = (b_.rows[k][j] & ((2u << mx) - 1)) << 1 | at(0, j, k) | at(1, j, k) << (mx + 2);
    for (int k = 0; k <= mz; ++k)
      for (int i = 0; i <= mx; ++i)
        ext_[k + 1][0] |= at(2, i, k) << (i + 1), ext_[k + 1][my + 2] |= at(3, i, k) << (i + 1);
    for (int j = 0; j <= my; ++j)
      for (int i = 0; i <= mx; ++i)
        ext_[0][j + 1] |= at(4, i, j) << (i + 1), ext_[mz + 2][j + 1] |= at(5, i, j) << (i + 1);
    ext_ready_ = true;
  }
  // The layer of samples just outside face `face`, from the block across it: its samples there are
  // ours one block over (its sample 1 is our kBlock + 1, its kBlock - 1 our -1).
  void fill_halo(int face, std::vector<uint8_t>& layer) const {
    int a = face / 2, side = face % 2, u = a == 0 ? 1 : 0, w = a == 2 ? 1 : 2, nb[3] = {b_.b[0], b_.b[1], b_.b[2]};
    nb[a] += side ? 1 : -1;
    int32_t slot = grid_.slot_at(nb[0], nb[1], nb[2]);
    layer.assign(static_cast<size_t>(kBlockSamples * kBlockSamples), slot == BlockGrid::kAllInside);
    if (slot < 0) return;
    const Block& there = grid_.blocks()[static_cast<size_t>(slot)];
    int t[3];
    t[a] = side ? 1 : kBlock - 1;
    for (int j = 0; j <= b_.m[w]; ++j)
      for (int i = 0; i <= b_.m[u]; ++i) {
        t[u] = i, t[w] = j;
        layer[static_cast<size_t>(j * kBlockSamples + i)] = there.inside(t[0], t[1], t[2]);
      }
  }
  uint8_t tubes(const int l[3], unsigned inside) {
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
  bool cuts(const int l[3]) {
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
    uint8_t mine[6];
    for (int f = 0; f < 6; ++f) mine[f] = segments[f];
    for (int f = 0; f < 6; ++f) {
      int o[3] = {l[0], l[1], l[2]};
      o[f / 2] += f % 2 ? 1 : -1;
      if (!here(o) && !(look_across_ >> f & 1u)) continue;  // that block records its cuts' sides here
      unsigned there = mask(o);
      uint8_t t = tubes(o, there);
      if (t || joins_middle(there)) add(cell_cuts(there, t), f, true);
    }
    for (int f = 0; f < 6; ++f)
      for (int s = 0; s < 6; ++s)
        if (segments[f] >> s & 1u) {
          TubeCut cut = record(l, info, f, s);
          int o[3] = {l[0], l[1], l[2]};
          o[f / 2] += f % 2 ? 1 : -1;
          if (!(mine[f] >> s & 1u) || here(o)) continue;
          TubeRequest q{cut, {b_.s0[0] + o[0], b_.s0[1] + o[1], b_.s0[2] + o[2]}};  // the other side, later
          q.cut.high = !cut.high;
          b_.requests.push_back(q);
        }
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

  TubeCut record(const int l[3], const Block::CellInfo& info, int face, int s) {
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
    if (sheet[0] == kNone || sheet[1] == kNone) return cut;
    cut.first = sheet[0], cut.second = sheet[1];
    b_.cuts.push_back(cut);
    return cut;
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
  uint8_t look_across_;
  uint32_t ext_[kBlockSamples + 2][kBlockSamples + 2];
  bool ext_ready_ = false;
};

}  // namespace

void record_cuts(const BlockGrid& grid, Block& b, const std::vector<size_t>& tube_cells, uint8_t look_across) {
  b.cuts.clear(), b.fans.clear(), b.requests.clear();
  Recorder r(grid, b, look_across);
  // The cells that may meet a cut: those that cut, the block's cells beside them, and the cells on
  // the faces it looks across.
  std::vector<size_t> cells;
  auto position = [](size_t c, int l[3]) {
    l[0] = static_cast<int>(c % kBlock), l[1] = static_cast<int>(c / kBlock % kBlock),
    l[2] = static_cast<int>(c / kBlock / kBlock);
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
  // Across a face whose neighbouring block holds no surface its cells' far corners share one sign,
  // and then none of them cuts a segment on the shared face (no face of it beside that one can be
  // ambiguous, nor can its corners 0 and 7 be apart): those faces are not looked across.
  bool across[6];
  for (int f = 0; f < 6; ++f) {
    int nb[3] = {b.b[0], b.b[1], b.b[2]};
    nb[f / 2] += f % 2 ? 1 : -1;
    across[f] = (look_across >> f & 1u) && grid.slot_at(nb[0], nb[1], nb[2]) >= 0;
  }
  bool any = false;
  for (bool a : across) any |= a;
  for (int k = 0; k < b.m[2] && any; ++k)
    for (int j = 0; j < b.m[1]; ++j)
      for (int i = 0; i < b.m[0]; ++i) {
        int l[3] = {i, j, k};
        uint8_t faces = 0;
        for (int a = 0; a < 3; ++a) {
          if (l[a] == 0 && across[2 * a]) faces |= static_cast<uint8_t>(1u << (2 * a));
          if (l[a] == b.m[a] - 1 && across[2 * a + 1]) faces |= static_cast<uint8_t>(1u << (2 * a + 1));
        }
        if (!faces) {
          if (j > 0 && k > 0 && j < b.m[1] - 1 && k < b.m[2] - 1) i = std::max(i, b.m[0] - 2);  // across the inside
          continue;
        }
        size_t c = Block::cell(i, j, k);
        if (b.cells[c].first == kNone) continue;
        bool near_tube = false;
        for (int f = 0; f < 6 && !near_tube; ++f) {
          if (!(faces >> f & 1u)) continue;
          int o[3] = {l[0], l[1], l[2]};
          o[f / 2] += f % 2 ? 1 : -1;
          near_tube = r.cuts(o);
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

void resolve_requests(BlockGrid& grid, int first, int end) {
  std::vector<Block>& blocks = grid.blocks();
  for (const Block& from : blocks)
    for (const TubeRequest& q : from.requests) {
      int bi[3], l[3];
      for (int a = 0; a < 3; ++a) bi[a] = (q.cell[a] + 1) / kBlock;
      int32_t slot = grid.slot_at(bi[0], bi[1], bi[2]);
      if (slot < 0 || bi[2] < first || bi[2] >= end) continue;
      Block& b = blocks[static_cast<size_t>(slot)];
      for (int a = 0; a < 3; ++a) l[a] = q.cell[a] - b.s0[a];
      int face = 2 * q.cut.axis + !q.cut.high, k[2], n = 0;
      for (int e = 0; e < 4; ++e)
        if (q.cut.segment >> e & 1u) k[n++] = e;
      uint32_t vertex[2] = {kNone, kNone};
      for (int s = 0; s < 2; ++s) {
        int e = edge_at(face, k[s]), c = edge_corner(e), axis = e / 4;
        int lower[3] = {l[0] + (c & 1), l[1] + (c >> 1 & 1), l[2] + (c >> 2 & 1)};
        // The block's crossings run by z, y, x, then axis.
        auto before = [&](const Crossing& x) {
          return std::make_tuple(int(x.l[2]), int(x.l[1]), int(x.l[0]), int(x.axis)) <
              std::make_tuple(lower[2], lower[1], lower[0], axis);
        };
        auto it = std::partition_point(b.xs.begin(), b.xs.end(), before);
        if (it == b.xs.end() || it->l[0] != lower[0] || it->l[1] != lower[1] || it->l[2] != lower[2] ||
            it->axis != axis)
          break;
        size_t index = static_cast<size_t>(it - b.xs.begin());
        int cells[4][3];
        cells_of(*it, cells);
        for (int c4 = 0; c4 < 4; ++c4)
          if (cells[c4][0] == l[0] && cells[c4][1] == l[1] && cells[c4][2] == l[2]) {
            uint32_t sheet = b.id(index, static_cast<size_t>(c4));
            if (sheet != kNone) vertex[s] = b.vertex[sheet];
          }
      }
      if (vertex[0] == kNone || vertex[1] == kNone) continue;
      TubeCut cut = q.cut;
      cut.first = vertex[0], cut.second = vertex[1];
      b.cuts.push_back(cut);
    }
}

void close_tubes(std::vector<TubeCut> cuts, Mesh& out) {
  auto key = [](const TubeCut& c) {
    return std::make_tuple(c.face[2], c.face[1], c.face[0], c.axis, c.segment, c.high);
  };
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
