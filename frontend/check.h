#pragma once
// Diagnostics of a whole file, as `fscript check` and the language server give them: a .fs script
// (parse, analysis, lowering warnings), or every FScript text inside a .wrl scene (with the VRML
// errors, positions in the .wrl).
#include <string>

#include "frontend/diagnostics.h"

namespace fscript::frontend {

// Returns false when any error was reported.
bool check_script(const std::string& path, const std::string& text, DiagnosticSink& diag);
// A scene's scripts; with `read_inlines` (a file on disk, not an editor's buffer) its Inlines are
// read too, so a missing one is warned about as fvrml-run does (vrml::load_inlines).
// `scripts`, when given, gets the number of scripts checked.
bool check_scene(const std::string& path, const std::string& text, DiagnosticSink& diag, bool read_inlines = false,
                 size_t* scripts = nullptr);

// The warnings lowering adds to a script that analysed without errors (check_script's last step).
struct Script;
void lowering_warnings(const Script& s, DiagnosticSink& diag);

// The set operations FTransform's `operation` field names instead of a formula.
bool is_set_operation(const std::string& text);

}  // namespace fscript::frontend
