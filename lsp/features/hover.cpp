// textDocument/hover: a built-in's signature and documentation, a user function's signature, or
// where a variable is defined.
#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

std::string signature(const frontend::SemaResult& sema, const frontend::FunctionInfo& f) {
  std::string s = "function " + f.name + "(";
  for (size_t i = 0; i < f.params.size(); ++i) s += (i ? ", " : "") + sema.symbols[static_cast<size_t>(f.params[i])].name;
  return s + ")";
}

json markdown(const std::string& text) { return {{"contents", {{"kind", "markdown"}, {"value", text}}}}; }

}  // namespace

json hover(const Document& d, const json& params) {
  size_t b, e;
  std::string word;
  if (!name_at(d, params, b, e, word)) return nullptr;
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  json result;
  if (int f = find_function(sema, word); f >= 0) {
    result = markdown("```fscript\n" + signature(sema, sema.functions[static_cast<size_t>(f)]) + "\n```\nuser function");
  } else if (int k = frontend::find_builtin(word); k >= 0) {
    const auto& bi = frontend::kBuiltins[k];
    result = markdown("```fscript\n" + std::string(bi.signature) + "\n```\n" + bi.doc);
  } else {
    // The symbol this occurrence resolves to (sema annotated the names), else one by name.
    const frontend::Symbol* sym = nullptr;
    for (const auto& ex : a->script.prog->expr_arena)
      if (ex->sym >= 0 && ex->name == word && ex->name_span.begin <= b && b < std::max(ex->name_span.end, ex->name_span.begin + 1))
        sym = &sema.symbols[static_cast<size_t>(ex->sym)];
    for (const auto& s : sema.symbols)
      if (!sym && s.name == word && s.decl.begin == b) sym = &s;
    if (!sym) return nullptr;
    Position at = position_of(d.text, sym->decl.begin);
    const char* kind = sym->is_param ? "parameter" : sym->kind == frontend::SymKind::Local ? "local variable"
                       : sym->kind == frontend::SymKind::Constant                         ? "constant"
                                                                                          : "global variable";
    result = markdown("```fscript\n" + word + (sym->is_array ? "[]" : "") + "\n```\n" + kind + ", defined at line " +
                      std::to_string(at.line + 1));
  }
  result["range"] = range_of_span(d.text, static_cast<uint32_t>(b), static_cast<uint32_t>(e));
  return result;
}

}  // namespace fscript::lsp
