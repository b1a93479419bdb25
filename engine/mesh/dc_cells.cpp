// Cell topology for manifold dual contouring: corner regions by union-find, a table over the 256 sign
// patterns and 64 face choices, marching tetrahedra's face choices, and the tube faces whose sheets
// are cut into pieces.
#include "engine/mesh/dc_cells.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace fscript::mesh {
namespace {

// Manifold dual contouring: one vertex per sheet of surface in a cell. On the cell's boundary the
// inside corners join along cube edges and the outside corners across faces too (so neighbouring
// cells, which see the same signs on their shared face, cut it the same way); the regions of inside
// and of outside corners then tile the cube's boundary like a tree, and every sheet is the loop
// between one inside region and one outside region. A crossing (its inside corner, its outside
// corner) names its sheet; a cell the surface crosses twice gets two vertices, not one pinched by
// both sheets. Regions are named by their lowest corner.
CellSigns cell_signs(unsigned inside, unsigned flips) {
  int in_parent[8], out_parent[8];
  for (int c = 0; c < 8; ++c) in_parent[c] = out_parent[c] = c;
  auto find = [](int* parent, int x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  auto join = [&](int* parent, int a, int b) {
    a = find(parent, a), b = find(parent, b);
    parent[std::max(a, b)] = std::min(a, b);
  };
  for (int c = 0; c < 8; ++c)
    for (int d = c + 1; d < 8; ++d) {
      unsigned diff = static_cast<unsigned>(c ^ d), both_in = (inside >> c) & (inside >> d) & 1u;
      bool both_out = !((inside >> c) & 1u) && !((inside >> d) & 1u);
      if (__builtin_popcount(diff) == 1) {
        if (both_in) join(in_parent, c, d);
        if (both_out) join(out_parent, c, d);
      } else if (__builtin_popcount(diff) == 2) {  // a face diagonal: the face's own choice
        int axis = __builtin_ctz(~diff & 7u), side = (c >> axis) & 1;
        bool flipped = (flips >> (2 * axis + side)) & 1u;
        if (both_in && flipped) join(in_parent, c, d);
        if (both_out && !flipped) join(out_parent, c, d);
      }
    }
  CellSigns s;
  for (int c = 0; c < 8; ++c) {
    s.in_group[c] = static_cast<uint8_t>(find(in_parent, c)),
    s.out_group[c] = static_cast<uint8_t>(find(out_parent, c));
    bool in = (inside >> c) & 1u;
    s.regions_in += in && s.in_group[c] == c;
    s.regions_out += !in && s.out_group[c] == c;
  }
  return s;
}

}  // namespace

namespace {

// The face's two inside corners when they lie on a diagonal (and only then: true).
bool diagonal_pair(unsigned inside, int axis, int side, int pair[2]) {
  int on_face[4], n = 0;
  for (int c = 0; c < 8; ++c)
    if (((c >> axis) & 1) == side && ((inside >> c) & 1u)) on_face[n++ & 3] = c;
  pair[0] = on_face[0], pair[1] = on_face[1];
  return n == 2 && __builtin_popcount(static_cast<unsigned>(on_face[0] ^ on_face[1])) == 2;
}

const std::array<uint8_t, 256>& ambiguous_table() {
  static const auto t = [] {
    std::array<uint8_t, 256> out{};
    int pair[2];
    for (unsigned m = 0; m < 256; ++m)
      for (int f = 0; f < 6; ++f) out[m] |= static_cast<uint8_t>(diagonal_pair(m, f / 2, f % 2, pair) << f);
    return out;
  }();
  return t;
}

}  // namespace

bool ambiguous_face(unsigned inside, int axis, int side) {
  int pair[2];
  return diagonal_pair(inside, axis, side, pair);
}

uint8_t ambiguous_faces(unsigned inside) { return ambiguous_table()[inside]; }

// Marching tetrahedra's Kuhn split cuts every face along the diagonal from the face's lowest corner
// to its highest: the corners at that diagonal's ends are joined across the face, inside or out.
namespace {

uint8_t kuhn_choice(unsigned inside) {
  uint8_t out = 0;
  for (unsigned faces = ambiguous_faces(inside); faces; faces &= faces - 1) {
    int face = __builtin_ctz(faces), axis = face / 2, side = face % 2;
    int low = side << axis, high = (7 & ~(1 << axis)) | low;
    if ((inside >> low & 1u) && (inside >> high & 1u)) out |= static_cast<uint8_t>(1u << face);
  }
  return out;
}

}  // namespace

uint8_t kuhn_flips(unsigned inside) {
  static const auto table = [] {
    std::array<uint8_t, 256> t{};
    for (unsigned m = 0; m < 256; ++m) t[m] = kuhn_choice(m);
    return t;
  }();
  return table[inside];
}

namespace {

// The face's corners: its inside pair and its outside pair.
void face_pairs(unsigned inside, int axis, int side, int in[2], int out[2]) {
  int n_in = 0, n_out = 0;
  for (int c = 0; c < 8; ++c)
    if (((c >> axis) & 1) == side) ((inside >> c) & 1u ? in[n_in++ & 1] : out[n_out++ & 1]) = c;
}

// The edge on face (axis, side) that leaves corner c along the face's other in-plane axis than `a`.
int other_face_edge(int c, int face_axis, int a) {
  int b = 3 - face_axis - a;
  return cube_edge(c, c ^ (1 << b));
}

}  // namespace

int edge_corner(int e) {
  int a = e / 4, u = (a + 1) % 3, w = (a + 2) % 3;
  return (e & 1) << u | (e >> 1 & 1) << w;
}

int cube_edge(int c, int d) {
  int a = __builtin_ctz(static_cast<unsigned>(c ^ d)), lo = std::min(c, d), u = (a + 1) % 3, w = (a + 2) % 3;
  return a * 4 + (lo >> u & 1) + 2 * (lo >> w & 1);
}

uint8_t tube_faces(unsigned inside, const unsigned around[6]) {
  uint8_t out = 0;
  const CellSigns& a = signs_of(inside, kuhn_flips(inside));
  for (unsigned faces = ambiguous_faces(inside); faces; faces &= faces - 1) {
    int face = __builtin_ctz(faces), axis = face / 2, side = face % 2, d = 1 << axis;
    int in[2], out_pair[2];
    face_pairs(inside, axis, side, in, out_pair);
    unsigned there = around[face];
    const CellSigns& b = signs_of(there, kuhn_flips(there));
    bool joined = kuhn_flips(inside) >> face & 1u
        ? a.out_group[out_pair[0]] == a.out_group[out_pair[1]] &&
            b.out_group[out_pair[0] ^ d] == b.out_group[out_pair[1] ^ d]
        : a.in_group[in[0]] == a.in_group[in[1]] && b.in_group[in[0] ^ d] == b.in_group[in[1] ^ d];
    if (joined) out |= static_cast<uint8_t>(1u << face);
  }
  return out;
}

int face_edge(int e, int face_axis) {
  int p0 = face_axis == 0 ? 1 : 0, p1 = face_axis == 2 ? 1 : 2, c = edge_corner(e);
  return e / 4 == p0 ? (c >> p1 & 1) : 2 + (c >> p0 & 1);
}

bool joins_middle(unsigned inside) {
  const CellSigns& s = signs_of(inside, kuhn_flips(inside));
  bool in0 = inside & 1u, in7 = inside >> 7 & 1u;
  if (in0 != in7) return false;
  return in0 ? s.in_group[0] != s.in_group[7] && s.regions_out == 1
             : s.out_group[0] != s.out_group[7] && s.regions_in == 1;
}

namespace {

// A cell's loops: their crossing edges in order, and the face each segment (edge i to edge i + 1)
// lies on.
struct Loops {
  int n = 0;
  int size[4] = {0, 0, 0, 0};
  int edges[4][12], faces[4][12];
};

Loops trace(unsigned inside) {
  uint8_t kuhn = kuhn_flips(inside);
  auto is_inside = [&](int c) { return ((inside >> c) & 1u) != 0; };
  auto crossing = [&](int e) { return is_inside(edge_corner(e)) != is_inside(edge_corner(e) | 1 << (e / 4)); };
  // The contour on face (axis, side) from crossing edge e: to the face's other crossing, or on a
  // face with four, to the other edge of the corner e's segment cuts off (the outside corners where
  // the face joins its inside ones, the inside corners otherwise).
  auto partner = [&](int e, int axis, int side) {
    int c = edge_corner(e), d = c | 1 << (e / 4);
    if (ambiguous_faces(inside) >> (2 * axis + side) & 1u) {
      bool cut_off_outside = kuhn >> (2 * axis + side) & 1u;
      return other_face_edge(is_inside(c) != cut_off_outside ? c : d, axis, e / 4);
    }
    for (int f = 0; f < 12; ++f)
      if (f != e && f / 4 != axis && (edge_corner(f) >> axis & 1) == side && crossing(f)) return f;
    return e;
  };
  // The face a loop leaves crossing edge e by: loops run with the inside on their left, seen from
  // outside the cell, so the two cells on a face run its segments in opposite directions.
  auto exit_face = [&](int e) {
    int a = e / 4, u = (a + 1) % 3, w = (a + 2) % 3, c = edge_corner(e);
    int sign = ((c >> u & 1) ? 1 : -1) * ((c >> w & 1) ? 1 : -1) * (is_inside(c | 1 << a) ? 1 : -1);
    int axis = sign > 0 ? w : u;  // entered through the u face, left through the w face, or the other way
    return 2 * axis + (c >> axis & 1);
  };
  Loops l;
  std::array<bool, 12> seen{};
  for (int start = 0; start < 12 && l.n < 4; ++start) {
    if (seen[static_cast<size_t>(start)] || !crossing(start)) continue;
    int k = l.n++, e = start;
    do {
      seen[static_cast<size_t>(e)] = true;
      int f = exit_face(e);
      l.edges[k][l.size[k]] = e, l.faces[k][l.size[k]] = f, ++l.size[k];
      e = partner(e, f / 2, f % 2);
    } while (e != start && l.size[k] < 12);
  }
  return l;
}

// The loop of a sheet whose crossing edges lie between `group` and the other sign (the region of
// corner 0 or 7 that the cell's middle joins).
int loop_of_corner(const Loops& l, unsigned inside, int corner) {
  const CellSigns& s = signs_of(inside, kuhn_flips(inside));
  bool in = inside >> corner & 1u;
  for (int k = 0; k < l.n; ++k) {
    int e = l.edges[k][0], c = edge_corner(e), d = c | 1 << (e / 4);
    int mine = ((inside >> c) & 1u) == in ? c : d;
    if ((in ? s.in_group[mine] == s.in_group[corner] : s.out_group[mine] == s.out_group[corner])) return k;
  }
  return -1;
}

// The angle of crossing edge e's middle about the cell's diagonal from corner 0 to corner 7.
double angle_about_diagonal(int e) {
  int c = edge_corner(e);
  double p[3];
  for (int a = 0; a < 3; ++a) p[a] = (c >> a & 1) + (a == e / 4 ? 0.5 : 0.0) - 0.5;
  return std::atan2(p[0] + p[1] - 2 * p[2], std::sqrt(3.0) * (p[0] - p[1]));
}

}  // namespace

CellCuts cell_cuts(unsigned inside, uint8_t tubes) {
  CellCuts out;
  bool middle = joins_middle(inside);
  if (!tubes && !middle) return out;
  Loops l = trace(inside);
  int band[2] = {middle ? loop_of_corner(l, inside, 0) : -1, middle ? loop_of_corner(l, inside, 7) : -1};
  if (band[0] < 0 || band[1] < 0 || band[0] == band[1]) band[0] = band[1] = -1;
  int first[4][12];  // per loop and piece: the piece's first edge
  for (int k = 0; k < l.n; ++k) {
    int n = l.size[k];
    const int *edges = l.edges[k], *faces = l.faces[k];
    bool all = k == band[0] || k == band[1];
    // Segment i is cut after one on a tube face (the two segments of a tube face end up on
    // different pieces, in both cells), and every segment of the loops a middle joins.
    auto cut = [&](int i) { return all || (tubes >> faces[(i + n - 1) % n] & 1u); };
    int first_cut = -1;
    for (int i = 0; i < n; ++i)
      if (cut(i)) {
        if (first_cut < 0) first_cut = i;
        out.cuts[out.n_cuts++] = {static_cast<uint8_t>(faces[i]), static_cast<uint8_t>(edges[i]),
                                  static_cast<uint8_t>(edges[(i + 1) % n])};
      }
    if (first_cut < 0) continue;
    // Piece 0 starts after the first cut; cut segment i separates edges[i] and edges[i + 1].
    int p = 0;
    for (int q = 1; q <= n; ++q) {
      int i = (first_cut + q) % n;
      out.piece[static_cast<size_t>(edges[i])] = static_cast<uint8_t>(p);
      if (q == 1 || cut((i + n - 1) % n)) first[k][p] = edges[i];
      if (cut(i)) ++p;
    }
    // A loop of three pieces or more closes its middle (the loop runs with the inside on its left:
    // the middle is wound the other way, to face out of the solid).
    if (!all && p >= 3)
      for (int q = 1; q + 1 < p; ++q)
        out.tris[out.n_tris++] = {static_cast<uint8_t>(first[k][0]), static_cast<uint8_t>(first[k][q + 1]),
                                  static_cast<uint8_t>(first[k][q])};
  }
  if (band[0] < 0) return out;
  // The tube through the middle: a band between the two loops, zipped in the order of their edges'
  // angles about the diagonal. Each loop's edge is wound against the loop, as a middle would be.
  struct At {
    double angle;
    int loop, index;
  };
  std::vector<At> around;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < l.size[band[side]]; ++i)
      around.push_back({angle_about_diagonal(l.edges[band[side]][i]), side, i});
  std::sort(around.begin(), around.end(), [](const At& x, const At& y) { return x.angle < y.angle; });
  int last[2] = {-1, -1};
  for (const At& a : around) last[a.loop] = a.index;
  for (const At& a : around) {
    int k = band[a.loop], n = l.size[k], prev = last[a.loop], apex = l.edges[band[!a.loop]][last[!a.loop]];
    int u = l.edges[k][prev], v = l.edges[k][a.index];
    bool along = a.index == (prev + 1) % n;  // the loop runs prev -> this
    out.tris[out.n_tris++] = along
        ? std::array<uint8_t, 3>{static_cast<uint8_t>(v), static_cast<uint8_t>(u), static_cast<uint8_t>(apex)}
        : std::array<uint8_t, 3>{static_cast<uint8_t>(u), static_cast<uint8_t>(v), static_cast<uint8_t>(apex)};
    last[a.loop] = a.index;
  }
  return out;
}

// Only face choices on ambiguous faces change anything, and only those are asked for: the others
// are left empty (a full table took 10 ms at start-up).
const CellSigns* const kCellSigns = [] {
  static std::vector<CellSigns> t(256 * 64);
  for (unsigned m = 0; m < 256; ++m)
    for (unsigned f = 0; f < 64; ++f)
      if (!(f & ~unsigned(ambiguous_faces(m)))) t[m * 64 + f] = cell_signs(m, f);
  return t.data();
}();

}  // namespace fscript::mesh
