#pragma once
// The FScript texts of a parsed scene: every FVRML node's script fields, with positions in the
// .wrl (each shared node once). Used by `fscript check`, the corpus tests and the scene layer.
#include <functional>
#include <vector>

#include "frontend/fscript/embedded.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

struct SceneScript {
  const Node* node = nullptr;
  frontend::EmbeddedScript script;
};

std::vector<SceneScript> scene_scripts(const Scene& scene);

// Calls `visit` once for every node reachable from the roots and PROTO bodies.
void for_each_node(const Scene& scene, const std::function<void(const Node&)>& visit);

}  // namespace fscript::vrml
