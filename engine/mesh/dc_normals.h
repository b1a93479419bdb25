#pragma once
// Vertex normals of dual-contoured meshes: the function's gradient where the surface is smooth, and
// at a sharp feature (a crease the QEF found, a box face closing a cut solid) each side of it with
// its own normal, the vertex split so every format can carry them (PLY, OBJ, glTF, VRML97).
#include <array>

#include "backends/backend.h"
#include "engine/mesh/field.h"
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

// Gives `m` (a closed mesh without normals) a normal per vertex: minus the gradient of `f` (its
// own, else central differences `step` apart), normalised, for every triangle corner whose face
// is within half of `crease` radians of it; another corner takes the gradient of its triangle's
// vertex that fits the face best where that one is within the angle, else the face's normal; and
// a vertex whose corners differ is split into one per normal (the vertex keeps its gradient where
// a corner takes it, else the first other normal; the others are appended, Mesh::split_from naming
// the vertex).
// First, a vertex farther from the surface than `beyond` (f over the gradient's length), and no
// farther than `most`, steps onto it along the gradient (one Newton step): the QEF's vertex can
// leave the surface where planes meet at a grazing angle. Vertices on a face of `box` (within
// box_eps), where a cut solid is closed by the box, stay.
struct Projection {
  double beyond = 0, most = 0, box_eps = 0;
  std::array<double, 6> box{};
};
bool gradient_vertex_normals(const Field& f, double step, double crease, int threads, const Projection& onto, Mesh& m,
                             backends::RuntimeError& err);

}  // namespace fscript::mesh
