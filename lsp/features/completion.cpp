// textDocument/completion: keywords, built-ins, the document's functions and variables; in a .wrl,
// node types and the enclosing node's fields, with their declarations and documentation.
#include <cctype>
#include <set>

#include "frontend/fscript/sema.h"
#include "frontend/vrml/scene_graph.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

// CompletionItemKind values of LSP 3.17.
constexpr int kFunctionKind = 3, kVariableKind = 6, kKeywordKind = 14, kConstantKind = 21;


}  // namespace

json completion(const Document& d, const json& params) {
  size_t b, e;
  size_t at = offset_of(d.text, position_param(params));
  std::string prefix = word_at(d.text, at, b, e) ? d.text.substr(b, at - b) : "";
  json items = json::array();
  std::set<std::string> seen;
  auto add = [&](const std::string& label, int kind, const std::string& detail, const std::string& doc = "") {
    if (label.empty() || label[0] == '$' || label.compare(0, prefix.size(), prefix) != 0 || !seen.insert(label).second)
      return;
    items.push_back({{"label", label}, {"kind", kind}, {"detail", detail}});
    if (!doc.empty()) items.back()["documentation"] = {{"kind", "markdown"}, {"value", doc}};
  };
  std::string node;
  if (d.scene && !scene_context(d.text, at, node)) {  // VRML: node types, and the enclosing node's fields
    constexpr int kFieldKind = 5, kClassKind = 7;
    if (const vrml::Interface* iface = node.empty() ? nullptr : vrml::standard_interface(node))
      for (const auto& f : iface->fields) add(f.name, kFieldKind, vrml::declaration_text(f), field_doc(node, f));
    for (const auto& n : vrml::standard_node_types())
      add(n, kClassKind, vrml::is_fvrml_node(n) ? "FVRML node" : "VRML97 node", node_doc(n, *vrml::standard_interface(n)));
    for (const char* k : {"DEF", "USE", "PROTO", "EXTERNPROTO", "ROUTE", "TO", "IS", "TRUE", "FALSE", "NULL"})
      add(k, kKeywordKind, "VRML97");
    return {{"isIncomplete", false}, {"items", items}};
  }
  for (const Keyword& k : kKeywords) add(k.word, kKeywordKind, "keyword", k.doc);
  for (int i = 0; i < frontend::kNumBuiltins; ++i)
    add(frontend::kBuiltins[i].name, kFunctionKind, frontend::kBuiltins[i].signature, frontend::kBuiltins[i].doc);
  if (!d.scene) {
    auto a = analyze_document(d);
    // Locals only of the function the cursor is in: the variables in scope there.
    int here = -1;
    for (size_t f = 0; f < a->script.sema.functions.size(); ++f) {
      const frontend::Stmt* decl = a->script.sema.functions[f].decl;
      if (decl && decl->span.begin <= at && at <= decl->span.end) here = static_cast<int>(f);
    }
    for (const auto& f : a->script.sema.functions) add(f.name, kFunctionKind, "user function");
    for (const auto& s : a->script.sema.symbols) {
      if (s.kind == frontend::SymKind::Function || s.kind == frontend::SymKind::Builtin) continue;
      if (s.kind == frontend::SymKind::Local && s.owner != here) continue;
      add(s.name, s.kind == frontend::SymKind::Constant ? kConstantKind : kVariableKind,
          s.kind == frontend::SymKind::Local ? "local" : "global");
    }
  }
  for (const char* g : frontend::kStandardGlobals) add(g, kVariableKind, "input/output global");
  return {{"isIncomplete", false}, {"items", items}};
}

}  // namespace fscript::lsp
