#pragma once
// Adaptive dual contouring: the cells of the uniform grid merged upward, eight at a time, into one
// vertex while that vertex stays within a tolerance of its tangent planes and the merge cannot change
// the surface's topology (the coarse cell holds one sheet, no ambiguous face, and the midpoints of its
// edges, faces and body each agree in sign with a corner they lie between: Ju et al., "Dual
// Contouring of Hermite Data", 2002, section 4.2). A merged cell's edges then change sign at most
// once along their length, so the polygons of the fine crossings, their duplicate vertices dropped,
// are the octree's polygons and the mesh stays closed. The levels inside a block merge on the
// block's dense arrays; blocks merged whole go on merging across blocks.
#include <array>
#include <cstdint>
#include <vector>

#include "engine/mesh/dc_block.h"
#include "engine/mesh/dual_contour.h"
#include "engine/mesh/qef.h"

namespace fscript::mesh {

// How far (in cells) a vertex may leave its cell, inside the box: a sharp corner whose tip pokes
// into a cell without a sample inside is placed by its neighbours' planes, just outside them
// (unit_dual_contour: corners of a turned cube within 0.1 of a cell; 1 cell away when kept in).
constexpr double kReach = 0.5;

// The vertex of `qef` in the lattice's cells [c0, c0 + size) per axis, widened by kReach cells.
Qef::Solution solve_in_cells(const Lattice& g, const Qef& qef, const int c0[3], int size);

// Merges the block's cells (qefs: their sheets' planes, from cell_sheets) while the root-mean-square plane distance stays within `tolerance`
// cells (0: never), and gives every sheet its block vertex (Block::vertex, positions, rms, root).
void merge_block(const Lattice& g, Block& b, const std::vector<Qef>& qefs, double tolerance);

// A vertex standing for several whole blocks.
struct BlockGroup {
  uint64_t node = 0;  // the octree node, the same for every block of the group
  std::array<double, 3> x{};
  double rms = 0;
};

// Blocks whose root merged, merged further with their neighbours under the same tests: per block,
// the group that takes all its sheets, or none (index -1: the block keeps its own vertices).
std::vector<int32_t> merge_blocks(const BlockGrid& grid, double tolerance, std::vector<BlockGroup>& groups);

// The output vertices, blocks in order: a block's own positions from base[i] on, or, where the
// block merged into a group (grouped[i]), the group's one vertex base[i], made when first named.
// Blocks without positions (no surface) get none. Also the stats' cells, merged and max_error.
void number_blocks(const BlockGrid& grid, const std::vector<int32_t>& group, const std::vector<BlockGroup>& groups,
                   Mesh& out, DualContourStats& stats, std::vector<uint32_t>& base, std::vector<bool>& grouped);

}  // namespace fscript::mesh
