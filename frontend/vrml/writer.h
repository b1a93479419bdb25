#pragma once
// The VRML97 writer: a scene graph back to text. Re-reading the output gives the same graph
// (same nodes, field values, DEF/USE sharing, PROTOs and ROUTEs); comments and layout are not kept.
#include <string>

#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

std::string write_scene(const Scene& scene);

// Structural equality of two scenes (for round-trip tests): "" or where they differ.
std::string compare_scenes(const Scene& a, const Scene& b);

}  // namespace fscript::vrml
