#pragma once
// Vertex normals of dual-contoured meshes: the function's gradient where the surface is smooth, and
// at a sharp feature (a crease the QEF found, a box face closing a cut solid) each side of it with
// its own normal, the vertex split so every format can carry them (PLY, OBJ, glTF, VRML97).
#include "backends/backend.h"
#include "runtime/mesh/field.h"
#include "runtime/mesh/mesh.h"

namespace fscript::mesh {

// Gives `m` (a closed mesh without normals) a normal per vertex: minus the gradient of `f` (its
// own, else central differences `step` apart), normalised, for every triangle corner whose face
// is within half of `crease` radians of it; another corner takes the gradient of its triangle's
// vertex that fits the face best where that one is within the angle, else the face's normal; and
// a vertex whose corners differ is split into one per normal (the first keeps its index, the
// others are appended, Mesh::split_from naming the first).
bool gradient_vertex_normals(const Field& f, double step, double crease, int threads, Mesh& m, backends::RuntimeError& err);

}  // namespace fscript::mesh
