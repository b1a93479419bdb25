#pragma once
// PROTO instantiation: a copy of a PROTO's body in which every `IS` takes the instance's value
// of that interface field (or the interface default). Nested PROTO instances expand when the
// scene layer walks into them, so a copy is made only for what is used.
#include <vector>

#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

// The body of the user PROTO that `instance` instantiates (for an EXTERNPROTO, the PROTO read from
// its file by load_inlines; empty when it was not read, and for built-ins).
std::vector<NodePtr> instantiate(const Node& instance);

}  // namespace fscript::vrml
