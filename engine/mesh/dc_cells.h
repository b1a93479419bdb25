#pragma once
// The sampled lattice of dual contouring and the topology of its cells: which crossings of a cell
// belong to the same sheet of surface (manifold dual contouring), shared by the uniform mesher and
// the octree that merges its cells (dc_cell_merge.h).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fscript::mesh {

// The sample lattice's geometry: samples at cell centres, indices -1 .. n per axis (the outer layer
// is padding, always outside). Dual cells are the cubes between samples c .. c + 1, c from -1 to
// n - 1 per axis. The samples themselves live in blocks (dc_block.h).
struct Lattice {
  int n[3];
  double lo[3], h[3];

  double coord(int a, int i) const { return lo[a] + (i + 0.5) * h[a]; }
  double end(int a) const { return lo[a] + n[a] * h[a]; }
  bool padding(const int s[3]) const {
    for (int a = 0; a < 3; ++a)
      if (s[a] < 0 || s[a] >= n[a]) return true;
    return false;
  }
};

// Corner c of a cube is at offset (c & 1, c >> 1 & 1, c >> 2 & 1); `inside` has bit c set where it is.
struct CellSigns {
  uint8_t in_group[8], out_group[8];  // the region of each corner, named by its lowest corner
  uint8_t regions_in = 0, regions_out = 0;
};
// `flips`: bit 2 * axis + side set where that face is decided the other way (its inside corners
// join); only ambiguous faces (ambiguous_faces) may be flipped. A table made before main runs.
extern const CellSigns* const kCellSigns;
inline const CellSigns& signs_of(unsigned inside, unsigned flips) { return kCellSigns[inside * 64 + flips]; }

// Whether a face of the cube has its two inside corners on a diagonal.
bool ambiguous_face(unsigned inside, int axis, int side);
// Bit 2 * axis + side for each such face.
uint8_t ambiguous_faces(unsigned inside);

// How an ambiguous face is decided: as marching tetrahedra decides it on the same samples. Its Kuhn
// split cuts each face along the diagonal from the face's lowest corner to its highest, and joins
// the corners at that diagonal's ends, inside or outside (their bit in kuhn_flips set where they are
// inside). Both cells on a face see the same samples and choose alike, and dual contouring keeps the
// bridges and tunnels marching tetrahedra makes: a fixed "outside joins" rule cut every thin bridge
// along a CSG seam into specks, some of them inside-out.
uint8_t kuhn_flips(unsigned inside);

// Tube faces: where the pair of corners a face separates runs around through the rest of the cell
// on both of its sides, one sheet of each cell crosses the face twice (a tube too thin for the grid
// passes through the face: inside along a face diagonal with outside all around, or the other way).
// One vertex per sheet would give the two cells' vertices two edges in common (an edge four
// triangles use) and cut the tube off. So such a sheet's loop (its crossings in order around the
// cell, the inside on their left seen from outside the cell) is cut at the segment after each of its
// segments on a tube face, into pieces, each with a vertex of its own, and the gaps the cuts leave
// are closed by triangles (dc_tubes.h): the tube's wall then passes through the face. Marching
// tetrahedra's bridges and tunnels are kept, the mesh stays a closed 2-manifold.
// tube_faces: bit 2 * axis + side of each, given the corners of the six cells across the faces.
uint8_t tube_faces(unsigned inside, const unsigned around[6]);
// Cube edge 0 .. 11 between corners c and d (one bit apart): along axis a, 4 * a + the lower
// corner's two other bits.
int cube_edge(int c, int d);
// The lower corner of cube edge e.
int edge_corner(int e);
// Edge e's place on a face across `face_axis` it lies on: 0, 1 along the face's lower axis (at
// offset 0, 1 on the higher one), 2, 3 along the higher axis (at offset 0, 1 on the lower).
int face_edge(int e, int face_axis);

// Whether the cell's middle joins corners 0 and 7, which share a sign its faces do not join
// (marching tetrahedra's split joins them along its diagonal) and the other sign is one region.
// Then the two loops around their regions are cut at every segment and joined by a band through
// the cell (cell_cuts): a tube, as marching tetrahedra makes it.
bool joins_middle(unsigned inside);

// A cut segment of a loop: on face `face` (2 * axis + side), from crossing edge `from` to `to`.
struct LoopCut {
  uint8_t face, from, to;
};
// The pieces of a cell with tube faces or a joined middle: the piece of each crossing edge on its
// loop (0, 1, ...; all 0 without either), every cut, and the triangles among the cell's own pieces
// (each named by a crossing edge on it): the middles of loops cut into three pieces or more, and
// the band of a joined middle.
struct CellCuts {
  std::array<uint8_t, 12> piece{};
  uint8_t n_cuts = 0, n_tris = 0;
  LoopCut cuts[12];
  std::array<uint8_t, 3> tris[24];
};
CellCuts cell_cuts(unsigned inside, uint8_t tubes);

// The sheet (0 .. 63) of a cell with corners `inside` and face choices `flips` that the crossing
// between its corners `in` and `out` lies on.
inline int sheet_key(unsigned inside, unsigned flips, int in, int out) {
  const CellSigns& s = signs_of(inside, flips & 63);
  return s.in_group[in] * 8 + s.out_group[out];
}

}  // namespace fscript::mesh
