#pragma once
// Tubes too thin for the grid in dual contouring (dc_cells.h, "Tube faces"): the cut of each
// segment a sheet has on a tube face, recorded by each of the face's two cells, and the triangles
// that close the tube's wall across the face once both cells' pieces have their vertices.
#include <cstdint>
#include <vector>

#include "runtime/mesh/dc_block.h"
#include "runtime/mesh/mesh.h"

namespace fscript::mesh {


// The block's sides of every cut segment on its cells' faces (cut by the cell or by the one across
// the face), and the middles of its cells' loops of three or more pieces; `tube_cells`: its cells
// with tube faces. Every crossing of the block has its sheets by now.
void record_cuts(const BlockGrid& grid, Block& b, const std::vector<size_t>& tube_cells);

// The triangles between both sides of every cut segment: its two crossings' polygons each hold an
// edge between the two cells' pieces there; the gap between those edges is closed by two triangles,
// or one where a cell has one piece at both crossings. A side without its other (only where two
// blocks disagreed on a sample's sign) is left alone.
void close_tubes(std::vector<TubeCut> cuts, Mesh& out);

}  // namespace fscript::mesh
