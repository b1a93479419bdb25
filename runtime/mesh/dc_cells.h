#pragma once
// The sampled lattice of dual contouring and the topology of its cells: which crossings of a cell
// belong to the same sheet of surface (manifold dual contouring), shared by the uniform mesher and
// the octree that merges its cells (dc_octree.h).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fscript::mesh {

// Samples at cell centres, indices -1 .. n per axis (the outer layer is padding, always outside).
struct Lattice {
  int n[3];
  double lo[3], h[3];
  std::vector<float> f;  // the field at every sample, padding included (-1 there)

  double coord(int a, int i) const { return lo[a] + (i + 0.5) * h[a]; }
  double end(int a) const { return lo[a] + n[a] * h[a]; }
  size_t at(int i, int j, int k) const {
    return (static_cast<size_t>(k + 1) * (n[1] + 2) + static_cast<size_t>(j + 1)) * (n[0] + 2) + static_cast<size_t>(i + 1);
  }
  bool inside(int i, int j, int k) const { return f[at(i, j, k)] > 0; }
  bool padding(const int s[3]) const {
    for (int a = 0; a < 3; ++a)
      if (s[a] < 0 || s[a] >= n[a]) return true;
    return false;
  }
  // Dual cells: the cube between samples c .. c + 1, c from -1 to n - 1 per axis.
  size_t cell(const int c[3]) const {
    return (static_cast<size_t>(c[2] + 1) * (n[1] + 1) + static_cast<size_t>(c[1] + 1)) * (n[0] + 1) + static_cast<size_t>(c[0] + 1);
  }
};

// Corner c of a cube is at offset (c & 1, c >> 1 & 1, c >> 2 & 1); `inside` has bit c set where it is.
struct CellSigns {
  uint8_t in_group[8], out_group[8];  // the region of each corner, named by its lowest corner
  uint8_t regions_in = 0, regions_out = 0;
};
// `flips`: bit 2 * axis + side set where that face is decided the other way (its inside corners join).
const CellSigns& signs_of(unsigned inside, unsigned flips);

// Whether a face of the cube has its two inside corners on a diagonal.
bool ambiguous_face(unsigned inside, int axis, int side);

// The sheet of dual cell `cell` that the crossing between its corners `in` and `out` lies on: 0 .. 63.
int sheet_of(const Lattice& g, const int cell[3], int in, int out);

}  // namespace fscript::mesh
