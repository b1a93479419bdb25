#pragma once
// PROTO instantiation: a copy of a PROTO's body in which every `IS` takes the instance's value
// of that interface field (or the interface default). Nested PROTO instances expand when the
// scene layer walks into them, so a copy is made only for what is used.
#include <vector>

#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

// The body of the user PROTO that `instance` instantiates (empty for EXTERNPROTOs and built-ins).
std::vector<NodePtr> instantiate(const Node& instance);

}  // namespace fscript::vrml
