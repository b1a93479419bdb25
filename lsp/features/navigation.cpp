// textDocument/definition and textDocument/documentSymbol: where a name is defined (functions,
// parameters, variables), and the document's functions and globals as an outline.
#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

json definition(const Document& d, const json& params) {
  if (d.scene) return nullptr;
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  SymbolRef r = symbol_at(*a, d.text, offset_of(d.text, position_param(params)));
  frontend::Span target{0, 0};
  switch (r.kind) {
    case SymbolRef::Kind::None:
    case SymbolRef::Kind::Builtin: return nullptr;
    case SymbolRef::Kind::Function: target = sema.functions[static_cast<size_t>(r.index)].decl->name_span; break;
    case SymbolRef::Kind::Variable: target = sema.symbols[static_cast<size_t>(r.index)].decl; break;
  }
  return {{"uri", d.uri}, {"range", range_of_span(d.text, target.begin, target.end)}};
}

json document_symbols(const Document& d) {
  if (d.scene) return scene_symbols(d);
  json list = json::array();
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  constexpr int kFunctionKind = 12, kVariableKind = 13;
  for (const auto& f : sema.functions) {
    if (!f.decl) continue;
    list.push_back({{"name", f.name},
                    {"kind", kFunctionKind},
                    {"range", range_of_span(d.text, f.decl->span.begin, f.decl->span.end)},
                    {"selectionRange", range_of_span(d.text, f.decl->name_span.begin, f.decl->name_span.end)}});
  }
  for (const auto& s : sema.symbols) {
    if (s.kind != frontend::SymKind::Global || s.decl.end <= s.decl.begin) continue;
    json r = range_of_span(d.text, s.decl.begin, s.decl.end);
    list.push_back({{"name", s.name}, {"kind", kVariableKind}, {"range", r}, {"selectionRange", r}});
  }
  return list;
}

}  // namespace fscript::lsp
