#pragma once
// Parametric shapes sampled on their (u, v, w) domain through Kernel batches: a curve is a
// polyline of N+1 samples, a surface an (N+1) x (M+1) grid of two triangles per cell, a solid the
// six faces of its (u, v, w) box. Coincident grid points along seams and poles are welded.
#include <array>

#include "backends/backend.h"
#include "runtime/mesh/mesh.h"

namespace fscript::mesh {

enum class ParametricKind { Curve, Surface, Solid };

struct ParametricJob {
  const backend::Kernel* kernel = nullptr;  // inputs (u, v, w, t), outputs (x, y, z)
  ParametricKind kind = ParametricKind::Surface;
  std::array<double, 6> domain{};           // u0 u1 v0 v1 w0 w1
  std::array<int, 3> intervals{50, 50, 50};
  float t = 0;
};

bool polygonize_parametric(const ParametricJob& job, Mesh& out, backend::RuntimeError& err);

// Merges vertices closer than `tolerance` (relative to the mesh size) and drops degenerate
// triangles: welds seams and poles. Normals are recomputed from the faces.
void weld(Mesh& m, float tolerance);
void face_normals_to_vertices(Mesh& m);

}  // namespace fscript::mesh
