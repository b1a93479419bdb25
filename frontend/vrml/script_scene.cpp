// The one-FShape scene of a script (script_scene.h): a wrapper parsed as VRML, its definition
// replaced by the script's text.
#include "frontend/vrml/script_scene.h"

#include <memory>

#include "frontend/vrml/inline.h"
#include "frontend/vrml/vrml_parser.h"

namespace fscript::vrml {

bool script_scene(const std::string& path, const std::string& text, Scene& out, frontend::DiagnosticSink& diag) {
  const std::string wrapper = "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"0\" } }\n";
  if (!parse_scene(std::make_unique<frontend::SourceFile>(path, wrapper), diag, out)) return false;
  const Value* g = out.roots.empty() ? nullptr : out.roots[0]->get("geometry");
  Node* geometry = g && !g->nodes.empty() ? g->nodes[0].get() : nullptr;
  if (geometry)
    for (FieldSlot& f : geometry->fields) {
      if (f.name != "definition" || f.value.strs.empty() || f.value.str_spans.empty()) continue;
      f.value.strs[0] = text;
      f.value.str_spans[0] = {0, static_cast<uint32_t>(text.size())};
      f.span = {0, 0};
      out.file = std::make_unique<frontend::SourceFile>(path, text);
      for (Node* n : {out.roots[0].get(), geometry}) n->file = out.file.get(), n->span = {0, 0};  // not the wrapper's
      return true;
    }
  diag.plain_error(path, "internal: the FShape wrapper of a script has no definition");
  return false;
}

bool scene_of_text(const std::string& path, const std::string& text, bool is_wrl, Scene& out,
                   frontend::DiagnosticSink& diag) {
  if (!is_wrl) return script_scene(path, text, out, diag);
  return parse_scene(std::make_unique<frontend::SourceFile>(path, text), diag, out) && load_inlines(out, diag);
}

}  // namespace fscript::vrml
