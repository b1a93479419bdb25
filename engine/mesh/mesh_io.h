#pragma once
// Mesh files: PLY (binary little-endian, with normals and colours), OBJ (with normals), STL
// (binary). Written to a temporary file and renamed, so a failure never leaves half a file.
#include <string>

#include "engine/mesh/mesh.h"

namespace fscript::mesh {

enum class MeshFormat { Ply, Obj, Stl, Glb };

bool write_mesh(const Mesh& m, MeshFormat f, const std::string& path, std::string& error);
std::string encode_mesh(const Mesh& m, MeshFormat f);  // the file's bytes

}  // namespace fscript::mesh
