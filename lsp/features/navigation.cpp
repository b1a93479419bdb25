// textDocument/definition and textDocument/documentSymbol: where a name is defined (functions,
// parameters, variables), and the document's functions and globals as an outline.
#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

json definition(const Document& d, const json& params) {
  size_t b, e;
  std::string word;
  if (!name_at(d, params, b, e, word)) return nullptr;
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  frontend::Span target{0, 0};
  bool found = false;
  if (int f = find_function(sema, word); f >= 0 && sema.functions[static_cast<size_t>(f)].decl) {
    target = sema.functions[static_cast<size_t>(f)].decl->name_span;
    found = true;
  }
  for (const auto& ex : a->script.prog->expr_arena)  // the symbol this very occurrence resolves to
    if (!found && ex->sym >= 0 && ex->name == word && ex->name_span.begin <= b && b < ex->name_span.end) {
      target = sema.symbols[static_cast<size_t>(ex->sym)].decl;
      found = true;
    }
  if (!found) return nullptr;
  return {{"uri", d.uri}, {"range", range_of_span(d.text, target.begin, target.end)}};
}

json document_symbols(const Document& d) {
  json list = json::array();
  if (d.scene) return list;
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
