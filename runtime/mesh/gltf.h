#pragma once
// glTF 2.0 binary (.glb): one mesh, positions, unit normals, per-vertex colours (COLOR_0), 32-bit
// indices; triangles, or lines for curves.
#include <string>

#include "runtime/mesh/mesh.h"

namespace fscript::mesh {

std::string encode_glb(const Mesh& m);

}  // namespace fscript::mesh
