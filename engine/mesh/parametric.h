#pragma once
// Parametric shapes sampled on their (u, v, w) domain through Kernel batches: a curve is a
// polyline of N+1 samples, a surface an (N+1) x (M+1) grid of two triangles per cell, a solid the
// six faces of its (u, v, w) box. Coincident grid points along seams and poles are welded.
// Surface normals come from the derivatives (central differences of the map, dP/du x dP/dv), or
// from the faces where that cross product vanishes (poles) and on solids.
#include <array>

#include "backends/backend.h"
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

enum class ParametricKind { Curve, Surface, Solid };

// A map (u, v, w) -> (x, y, z) evaluated in batches: one kernel at a fixed t, or a combination
// built by the scene layer (an FTransform's per-coordinate operation).
class ParametricField {
 public:
  virtual ~ParametricField() = default;
  virtual bool eval(const float* u, const float* v, const float* w, size_t n, float* x, float* y, float* z,
                    backends::RuntimeError& err) const = 0;
  // Rows of the (u, v) grid: point r * count + i is (u[i], v[r], w[r]). The same values as eval over
  // those points; a kernel computes what does not depend on u once per row (Kernel::eval_rows).
  virtual bool eval_rows(const float* u, size_t count, const float* v, const float* w, size_t rows, float* x, float* y,
                         float* z, backends::RuntimeError& err) const;
};

// A parametric kernel: inputs (u, v, w, t), outputs (x, y, z).
class KernelParametric : public ParametricField {
 public:
  KernelParametric(const backends::Kernel& k, float t) : k_(k), t_(t) {}
  bool eval(const float* u, const float* v, const float* w, size_t n, float* x, float* y, float* z,
            backends::RuntimeError& err) const override;
  bool eval_rows(const float* u, size_t count, const float* v, const float* w, size_t rows, float* x, float* y,
                 float* z, backends::RuntimeError& err) const override;

 private:
  const backends::Kernel& k_;
  float t_;
};

struct ParametricJob {
  const ParametricField* field = nullptr;
  ParametricKind kind = ParametricKind::Surface;
  std::array<double, 6> domain{};           // u0 u1 v0 v1 w0 w1
  std::array<int, 3> intervals{50, 50, 50};
};

bool polygonize_parametric(const ParametricJob& job, Mesh& out, backends::RuntimeError& err);

// Merges vertices closer than `tolerance` (relative to the mesh size) and drops degenerate
// triangles: welds seams and poles. Normals are recomputed from the faces.
void weld(Mesh& m, float tolerance);
void face_normals_to_vertices(Mesh& m);

}  // namespace fscript::mesh
