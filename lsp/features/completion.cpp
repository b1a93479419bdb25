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

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// How well `label` fits what was typed: 0 starts with it as written, 1 starts with it in another
// letter case ("Sq": sqrt, "sQ": Sq3), -1 not at all.
int rank(const std::string& label, const std::string& typed) {
  if (label.compare(0, typed.size(), typed) == 0) return 0;
  return lower(label).compare(0, typed.size(), lower(typed)) == 0 ? 1 : -1;
}

// What a client matches the typed word against: the label, with the typed letters where they
// differ only in case ("Sq" + "rt"), so a client that filters by prefix keeps what the server found.
std::string filter_text(const std::string& label, const std::string& typed, int rank) {
  return rank == 0 ? label : typed + label.substr(typed.size());
}

}  // namespace

json completion(const Document& d, const json& params) {
  size_t b, e;
  size_t at = offset_of(d.text, position_param(params));
  std::string prefix = word_at(d.text, at, b, e) ? d.text.substr(b, at - b) : "";
  json items = json::array();
  std::set<std::string> seen;
  // Every name that fits the word typed so far, in any letter case, ranked (sortText) so the best
  // fits come first; the item replaces the typed word (textEdit), so "Sq" becomes "sqrt".
  Position from = position_of(d.text, at - prefix.size()), to = position_of(d.text, at);
  json replaced = {{"start", {{"line", from.line}, {"character", from.character}}},
                   {"end", {{"line", to.line}, {"character", to.character}}}};
  auto add = [&](const std::string& label, int kind, const std::string& detail, const std::string& doc = "") {
    int r = label.empty() || label[0] == '$' ? -1 : rank(label, prefix);
    if (r < 0 || !seen.insert(label).second) return;
    items.push_back({{"label", label},
                     {"kind", kind},
                     {"detail", detail},
                     {"sortText", std::to_string(r) + lower(label)},
                     {"filterText", filter_text(label, prefix, r)},
                     {"textEdit", {{"range", replaced}, {"newText", label}}}});
    if (!doc.empty()) items.back()["documentation"] = {{"kind", "markdown"}, {"value", doc}};
  };
  std::string node;
  if (d.scene && !scene_context(d.text, at, node)) {  // VRML: node types, and the enclosing node's fields
    constexpr int kFieldKind = 5, kClassKind = 7;
    if (const vrml::Interface* iface = node.empty() ? nullptr : vrml::standard_interface(node))
      for (const auto& f : iface->fields) add(f.name, kFieldKind, vrml::declaration_text(f), field_doc(node, f));
    for (const auto& n : vrml::standard_node_types())
      add(n, kClassKind, vrml::is_fvrml_node(n) ? "FVRML node" : "VRML97 node",
          node_doc(n, *vrml::standard_interface(n)));
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
