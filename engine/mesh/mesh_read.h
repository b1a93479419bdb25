#pragma once
// Mesh readers for fvrml-meshdiff: PLY (ascii, binary little and big endian), OBJ (polygons are
// fanned into triangles), STL (binary or ascii; its corners are welded by exact position).
#include <string>

#include "engine/mesh/mesh.h"

namespace fscript::mesh {

bool read_mesh(const std::string& path, Mesh& out, std::string& error);
bool parse_mesh(const std::string& bytes, const std::string& name, Mesh& out, std::string& error);

}  // namespace fscript::mesh
