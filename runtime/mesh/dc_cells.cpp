// Cell topology for manifold dual contouring: corner regions by union-find, a table over the 256 sign
// patterns and 64 face choices, and the face choice that keeps thin tubes from doubling an edge.
#include "runtime/mesh/dc_cells.h"

#include <algorithm>
#include <array>
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
    s.in_group[c] = static_cast<uint8_t>(find(in_parent, c)), s.out_group[c] = static_cast<uint8_t>(find(out_parent, c));
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

// A face whose two inside corners lie on a diagonal, and are joined through the rest of the cell on
// both of its sides, is crossed by a tube of outside too thin for the grid: cut the usual way, the
// two cells' sheets would meet along both of the face's segments and share an edge four triangles
// use. Flipped, the tube is closed off on each side instead.
bool face_flipped(unsigned inside, unsigned there, int axis, int side) {
  int on_face[2];
  diagonal_pair(inside, axis, side, on_face);
  int p = on_face[0] ^ (1 << axis), q = on_face[1] ^ (1 << axis);  // the same samples, seen from there
  const CellSigns &a = signs_of(inside, 0), &b = signs_of(there, 0);
  return a.in_group[on_face[0]] == a.in_group[on_face[1]] && b.in_group[p] == b.in_group[q];
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
