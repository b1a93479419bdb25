#pragma once
// The VRML97 writer: a scene graph back to text. Re-reading the output gives the same graph
// (same nodes, field values, DEF/USE sharing, PROTOs and ROUTEs); comments and layout are not kept.
#include <string>

#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

std::string write_scene(const Scene& scene);
// One node and everything under it, as the scene's writer writes it (a USE of a node outside it
// written out in full); with `protos`, the scene's PROTO and EXTERNPROTO declarations come first.
std::string write_node(const Scene& scene, const Node& n, bool protos = false);

// Structural equality of two scenes (for round-trip tests): "" or where they differ.
std::string compare_scenes(const Scene& a, const Scene& b);

}  // namespace fscript::vrml
