#pragma once
// The VRML97 reader: header check, every field type, DEF/USE, PROTO with IS, EXTERNPROTO (URL
// kept, not fetched: a warning), ROUTE checking, the standard node set with field types and
// defaults, and the six FVRML nodes built in. Reports every error of a file in one run.
#include <memory>

#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::vrml {

constexpr int kMaxNodeNesting = 1000;  // deeper nesting is refused with an error, not a stack overflow

// Parses `file` into `out`. Returns false when an error was reported (the scene then holds what
// could be read).
bool parse_scene(std::unique_ptr<frontend::SourceFile> file, frontend::DiagnosticSink& diag, Scene& out);

// Reads node interfaces written as "Name [ field SFFloat x 1 ... ]" (the built-in node table).
bool parse_interfaces(const frontend::SourceFile& file, frontend::DiagnosticSink& diag, std::vector<Interface>& out);

}  // namespace fscript::vrml
