#pragma once
// Tubes too thin for the grid in dual contouring (dc_cells.h, "Tube faces"): the cut of each
// segment a sheet has on a tube face, recorded by each of the face's two cells, and the triangles
// that close the tube's wall across the face once both cells' pieces have their vertices.
#include <cstdint>
#include <vector>

#include "engine/mesh/dc_block.h"
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

// The block's sides of every cut segment on its cells' faces, and the middles of its cells' loops
// of three or more pieces (`tube_cells`: its cells that cut their loops). A segment its cell cuts
// across a face of the block gets a request for the other side (resolve_requests); one cut by a
// cell of another block is seen from here only across the faces `look_across` names (bit
// 2 * axis + side: the faces of a shard's slab, whose other side another process works). Every
// crossing of the block has its sheets by now.
void record_cuts(const BlockGrid& grid, Block& b, const std::vector<size_t>& tube_cells, uint8_t look_across);

// The other sides of the requests of every block, once all of them have their vertices: recorded
// in the blocks whose layers are [first, end) (a shard's slab), dropped for the others.
void resolve_requests(BlockGrid& grid, int first, int end);

// The triangles between both sides of every cut segment: its two crossings' polygons each hold an
// edge between the two cells' pieces there; the gap between those edges is closed by two triangles,
// or one where a cell has one piece at both crossings. A side without its other (only where two
// blocks disagreed on a sample's sign) is left alone.
void close_tubes(std::vector<TubeCut> cuts, Mesh& out);

}  // namespace fscript::mesh
