#pragma once
// The sampled lattice of dual contouring and the topology of its cells: which crossings of a cell
// belong to the same sheet of surface (manifold dual contouring), shared by the uniform mesher and
// the octree that merges its cells (dc_octree.h).
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

// Whether the ambiguous face (axis, side) of a cell with corners `inside` is decided the other way,
// given the corners `there` of the cell across it (face_flips of the old whole-grid mesher).
bool face_flipped(unsigned inside, unsigned there, int axis, int side);

// The sheet (0 .. 63) of a cell with corners `inside` and face choices `flips` that the crossing
// between its corners `in` and `out` lies on.
inline int sheet_key(unsigned inside, unsigned flips, int in, int out) {
  const CellSigns& s = signs_of(inside, flips & 63);
  return s.in_group[in] * 8 + s.out_group[out];
}

}  // namespace fscript::mesh
