#pragma once
// Adaptive dual contouring: the cells of the uniform grid merged upward, eight at a time, into one
// vertex while that vertex stays within a tolerance of its tangent planes and the merge cannot change
// the surface's topology (the coarse cell holds one sheet, no ambiguous face, and the midpoints of its
// edges, faces and body each agree in sign with a corner they lie between: Ju et al., "Dual
// Contouring of Hermite Data", 2002, section 4.2). A merged cell's edges then change sign at most
// once along their length, so the polygons of the fine crossings, their duplicate vertices dropped,
// are the octree's polygons and the mesh stays closed.
#include <array>
#include <cstdint>
#include <vector>

#include "runtime/mesh/dc_cells.h"
#include "runtime/mesh/qef.h"

namespace fscript::mesh {

// One vertex of the uniform mesh: a sheet of surface in a dual cell.
struct SheetVertex {
  int cell[3];
  Qef qef;  // the planes of its crossings
};

struct MergedVertices {
  std::vector<uint32_t> of_sheet;                 // the output vertex of each sheet
  std::vector<std::array<double, 3>> positions;   // output vertices, in the order sheets first name them
  std::vector<double> rms;                        // and their distances to their planes
  size_t merged = 0;                              // output vertices that stand for more than one cell
};

// How far (in cells) a vertex may leave its cell, inside the box: a sharp corner whose tip pokes
// into a cell without a sample inside is placed by its neighbours' planes, just outside them
// (unit_dual_contour: corners of a turned cube within 0.1 of a cell; 1 cell away when kept in).
constexpr double kReach = 0.5;

// The vertex of `qef` in the lattice's cells [c0, c0 + size) per axis, widened by kReach cells.
Qef::Solution solve_in_cells(const Lattice& g, const Qef& qef, const int c0[3], int size);

// Merges while the root-mean-square plane distance stays within `tolerance` cells (0: never).
MergedVertices merge_cells(const Lattice& g, const std::vector<SheetVertex>& sheets, double tolerance);

}  // namespace fscript::mesh
