#pragma once
// The implicit polygonizer: marching tetrahedra on a cell-centred grid padded by one layer outside
// the box. Each cube is split into six tetrahedra around its main diagonal, the same way in every
// cube, so neighbouring cubes agree on every face diagonal: no ambiguous cases, no cracks, and a
// closed surface gives a watertight 2-manifold mesh. The padding is "outside", so a solid cut by
// the box is closed by caps lying exactly on the box faces. Vertices are refined onto the surface
// by regula falsi on the real function; normals come from its gradient. All evaluation goes through
// Kernel batches; the octree of interval bounds (sample_pruning.h) spares the samples far from the surface.
#include <array>
#include <memory>

#include "backends/backend.h"
#include "engine/mesh/field.h"
#include "engine/mesh/mesh.h"
#include "engine/mesh/sample_pruning.h"
#include "runtime/support/progress.h"

namespace fscript::mesh {

// Which mesher an implicit job runs (fvrml-run --mesher): manifold dual contouring (the default:
// dual_contour.h) or marching tetrahedra on the same grid.
enum class Mesher : uint8_t { MarchingTetrahedra, DualContouring };

class SlabSplit;     // dc_slabs.h
class Profiler;      // field_profile.h
class FieldProfile;  // field_profile.h

struct MesherOptions {
  Mesher kind = Mesher::DualContouring;
  // Dual contouring merges cells while their vertex stays within this many cells (root-mean-square)
  // of their tangent planes (fvrml-run --tolerance); 0 keeps every cell (dc_cell_merge.h).
  double tolerance = kDefaultTolerance;
  static constexpr double kDefaultTolerance = 0.02;
  // fvrml-run --shard K/M without --frames (dc_slabs.h): dual contouring makes only this shard's
  // slab of the blocks, or joins every shard's; marching tetrahedra is left to the merge.
  SlabSplit* slabs = nullptr;
  // fvrml-run --profile: each job's evaluation is profiled in the profile of its shape.
  Profiler* profiler = nullptr;
};

struct ImplicitJob {
  const Field* field = nullptr;             // f(x, y, z), inside where f > 0
  std::array<double, 6> box{};              // x0 x1 y0 y1 z0 z1
  std::array<int, 3> cells{50, 50, 50};     // samples per axis inside the box
  int refine_steps = 3;
  int threads = 1;  // z-slabs marched in parallel; the output is the same bytes for any count
  bool prune = true;  // skip the bricks the field's bounds decide (same mesh); false: sample all
  PruneStats* stats = nullptr;  // filled when given (and added to prune_totals() in any case)
  MesherOptions mesher;
  support::ProgressJob* progress = nullptr;  // when given, told how much of the grid is done
  FieldProfile* profile = nullptr;  // when given, the job's evaluation is counted there (field_profile.h)
};

// The brick map of the job's sample grid (null when job.prune is off or the field cannot bound
// itself): both meshers sample the same cell-centred points.
std::unique_ptr<BrickMap> job_bricks(const ImplicitJob& job);

// Polygonizes by marching tetrahedra; returns false with a runtime error from the kernel (budget, bounds).
bool polygonize_implicit(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err);
// By the job's mesher.
bool polygonize(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err);

}  // namespace fscript::mesh
