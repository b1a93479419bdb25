#pragma once
// A .fs script as a scene: the script as the definition of one FShape with every other field at
// its FVRML default (fvrml-run shape.fs, fscript check shape.fs).
#include <string>

#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

// The scene's file is the script itself, the definition starting at its first character and the
// nodes placed there, so diagnostics and runtime errors name the .fs file's own lines and columns.
bool script_scene(const std::string& path, const std::string& text, Scene& out, frontend::DiagnosticSink& diag);

// A file's text as a scene: a .wrl (`is_wrl`) parsed with its Inlines and EXTERNPROTOs read, else
// the script's scene above. What the checks, the profiler and the language server load.
bool scene_of_text(const std::string& path, const std::string& text, bool is_wrl, Scene& out,
                   frontend::DiagnosticSink& diag);

}  // namespace fscript::vrml
