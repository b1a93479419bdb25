#pragma once
// Adaptive manifold dual contouring (fvrml-run --mesher dc, the default): Hermite data on every sign-change edge of the padded,
// cell-centred grid (crossings by regula falsi on the real function, normals from its gradient; the
// box faces close a cut solid with their own planes), one vertex per sheet of surface in each dual
// cell at the minimum of its QEF (qef.h), ambiguous cells decided as marching tetrahedra decides
// them and tubes thinner than a cell kept (dc_cells.h, dc_tubes.h), cells merged up an octree while
// the tolerance and the topology allow (dc_cell_merge.h), one polygon per sign-change edge, vertex
// normals from the gradient split at sharp features (dc_normals.h). Worked in blocks (dc_block.h)
// on every thread; the same bytes for any count. Sharp CSG edges and corners are kept. Known
// limits: a vertex may leave its cell by half a cell (so sharp corners are reached), which can fold
// a triangle where features are closer than a cell.
#include "backends/backend.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

struct DualContourStats {
  size_t cells = 0;  // output vertices: sheets of dual cells, or merged cells
  size_t merged = 0;  // of those, merged cells (more than one dual cell)
  size_t triangles = 0;
  double max_error = 0;  // the largest root-mean-square distance of a vertex to its planes, in cells
  size_t jobs = 0;  // implicit shapes meshed (in totals)
  // Crossings whose normal (and Newton step) came from the function's own gradient, and those that
  // took central differences (no gradient, or not a finite one there). Not counted for shards'
  // slabs (fvrml-run --shard): their crossings are worked in the shards' processes.
  size_t gradient_normals = 0, difference_normals = 0;
  void add(const DualContourStats& o);
};

// The figures of every dual contouring job since the process started (fvrml-run --stats).
DualContourStats dual_contour_totals();

// The job's field over its box and samples, pruned by its bounds (job.prune), on job.threads.
bool dual_contour(const ImplicitJob& job, Mesh& out, DualContourStats& stats, backends::RuntimeError& err);

}  // namespace fscript::mesh
