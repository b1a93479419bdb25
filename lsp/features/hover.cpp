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
  if (d.scene) return nullptr;
  auto a = analyze_document(d);
  const auto& sema = a->script.sema;
  SymbolRef r = symbol_at(*a, d.text, offset_of(d.text, position_param(params)));
  json result;
  switch (r.kind) {
    case SymbolRef::Kind::None: return nullptr;
    case SymbolRef::Kind::Function:
      result = markdown("```fscript\n" + signature(sema, sema.functions[static_cast<size_t>(r.index)]) +
                        "\n```\nuser function");
      break;
    case SymbolRef::Kind::Builtin: {
      const auto& bi = frontend::kBuiltins[r.index];
      result = markdown("```fscript\n" + std::string(bi.signature) + "\n```\n" + bi.doc);
      break;
    }
    case SymbolRef::Kind::Variable: {
      const frontend::Symbol& sym = sema.symbols[static_cast<size_t>(r.index)];
      Position at = position_of(d.text, sym.decl.begin);
      const char* kind = sym.is_param ? "parameter" : sym.kind == frontend::SymKind::Local ? "local variable"
                         : sym.kind == frontend::SymKind::Constant                        ? "constant"
                                                                                          : "global variable";
      result = markdown("```fscript\n" + r.word + (sym.is_array ? "[]" : "") + "\n```\n" + kind +
                        ", defined at line " + std::to_string(at.line + 1));
      break;
    }
  }
  result["range"] = range_of_span(d.text, r.name.begin, r.name.end);
  return result;
}

}  // namespace fscript::lsp
