#pragma once
// Inline nodes of local files: each Inline whose URL names a file (relative to the file that holds
// it, or file:) has that file read, parsed and kept, its root nodes hung under the Inline node
// (Node::inlined), recursively; remote URLs stay references (the parser warns), missing files too.
#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

constexpr int kMaxInlineDepth = 16;  // Inlines within Inlines, deeper is refused with an error

// Whether a URL names something on a network (a scheme other than file:).
bool is_remote_url(const std::string& url);

// Loads the scene's local Inlines (and theirs): an Inline takes the first of its URLs that reads,
// as VRML97 browsers do. One that none reads (missing, unreadable, only remote URLs) is listed in
// Scene::missing_inlines and drawn as nothing, with a warning at its URL naming what was tried
// (the remote ones were warned about by the parser); with `strict`, an error. Broken or circular
// files, and EXTERNPROTOs that do not read, are errors. `files`, when given, receives the path of
// every file read. False when an error was reported.
bool load_inlines(Scene& scene, frontend::DiagnosticSink& diag, std::vector<std::string>* files = nullptr,
                  bool strict = false);

}  // namespace fscript::vrml
