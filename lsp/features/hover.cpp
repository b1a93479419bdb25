// textDocument/hover: a built-in's signature and documentation (also when written in another
// letter case), a user function's signature, where a variable is defined, what a keyword does;
// in a .wrl, FVRML and VRML97 node types and their fields (from the one node table).
#include "frontend/fscript/sema.h"
#include "frontend/vrml/scene_graph.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

std::string signature(const frontend::SemaResult& sema, const frontend::FunctionInfo& f) {
  std::string s = "function " + f.name + "(";
  for (size_t i = 0; i < f.params.size(); ++i)
    s += (i ? ", " : "") + sema.symbols[static_cast<size_t>(f.params[i])].name;
  return s + ")";
}

json markdown(const std::string& text) { return {{"contents", {{"kind", "markdown"}, {"value", text}}}}; }

json keyword_hover(const std::string& text, size_t offset) {
  size_t b, e;
  if (!word_at(text, offset, b, e)) return nullptr;
  std::string w = text.substr(b, e - b);
  for (const Keyword& k : kKeywords)
    if (w == k.word) {
      json r = markdown("```fscript\n" + w + "\n```\nkeyword: " + k.doc);
      r["range"] = range_of_span(text, static_cast<uint32_t>(b), static_cast<uint32_t>(e));
      return r;
    }
  return nullptr;
}

std::string builtin_hover(const std::string& written, int index) {
  const auto& bi = frontend::kBuiltins[index];
  std::string out = "```fscript\n" + std::string(bi.signature) + "\n```\n" + bi.doc;
  if (written != bi.name)
    out += "\n\n`" + written + "` is read as `" + bi.name + "`: names are case-sensitive, so write `" + bi.name + "`.";
  return out;
}

}  // namespace

std::string node_doc(const std::string& type, const vrml::Interface& iface) {
  std::string out = "**" + type + "**: " + (vrml::is_fvrml_node(type) ? "FVRML node" : "VRML97 node");
  if (!iface.doc.empty()) out += "\n\n" + iface.doc;
  out += "\n\nFields:";
  for (const auto& f : iface.fields) out += " `" + f.name + "`";
  return out;
}

std::string field_doc(const std::string& type, const vrml::FieldDecl& f) {
  return "```vrml\n" + vrml::declaration_text(f) + "\n```\n" + (f.doc.empty() ? type + " field" : f.doc);
}

json hover(const Document& d, const json& params) {
  if (d.scene) return nullptr;
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  size_t offset = offset_of(d.text, position_param(params));
  SymbolRef r = symbol_at(*a, d.text, offset);
  json result;
  switch (r.kind) {
    case SymbolRef::Kind::None: return keyword_hover(d.text, offset);
    case SymbolRef::Kind::Function:
      result = markdown("```fscript\n" + signature(sema, sema.functions[static_cast<size_t>(r.index)]) +
                        "\n```\nuser function");
      break;
    case SymbolRef::Kind::Builtin: result = markdown(builtin_hover(r.word, r.index)); break;
    case SymbolRef::Kind::Variable: {
      const frontend::Symbol& sym = sema.symbols[static_cast<size_t>(r.index)];
      Position at = position_of(d.text, sym.decl.begin);
      const char* kind = sym.is_param               ? "parameter"
          : sym.kind == frontend::SymKind::Local    ? "local variable"
          : sym.kind == frontend::SymKind::Constant ? "constant"
                                                    : "global variable";
      result = markdown("```fscript\n" + r.word + (sym.is_array ? "[]" : "") + "\n```\n" + kind + ", defined at line " +
                        std::to_string(d.first_line + at.line + 1));
      break;
    }
  }
  result["range"] = range_of_span(d.text, r.name.begin, r.name.end);
  return result;
}

json scene_hover(const Document& d, const json& params) {
  size_t at = offset_of(d.text, position_param(params)), b, e;
  std::string node;
  if (scene_context(d.text, at, node) || !word_at(d.text, at, b, e)) return nullptr;
  std::string w = d.text.substr(b, e - b);
  json result;
  if (const vrml::Interface* iface = vrml::standard_interface(w)) {
    result = markdown(node_doc(w, *iface));
  } else {
    const vrml::Interface* outer = node.empty() ? nullptr : vrml::standard_interface(node);
    const vrml::FieldDecl* f = outer ? outer->find(w) : nullptr;
    if (!f) return nullptr;
    result = markdown(field_doc(node, *f));
  }
  result["range"] = range_of_span(d.text, static_cast<uint32_t>(b), static_cast<uint32_t>(e));
  return result;
}

}  // namespace fscript::lsp
