// textDocument/completion: keywords, built-ins, the document's functions and variables.
#include <set>

#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

// CompletionItemKind values of LSP 3.17.
constexpr int kFunctionKind = 3, kVariableKind = 6, kKeywordKind = 14, kConstantKind = 21;

const char* const kKeywords[] = {
#define FS_KEYWORD(N, S) S,
#include "frontend/fscript/tokens.def"
};

}  // namespace

json completion(const Document& d, const json& params) {
  size_t b, e;
  size_t at = offset_of(d.text, position_param(params));
  std::string prefix = word_at(d.text, at, b, e) ? d.text.substr(b, at - b) : "";
  json items = json::array();
  std::set<std::string> seen;
  auto add = [&](const std::string& label, int kind, const std::string& detail) {
    if (label.empty() || label[0] == '$' || label.compare(0, prefix.size(), prefix) != 0 || !seen.insert(label).second)
      return;
    items.push_back({{"label", label}, {"kind", kind}, {"detail", detail}});
  };
  for (const char* k : kKeywords) add(k, kKeywordKind, "keyword");
  for (int i = 0; i < frontend::kNumBuiltins; ++i)
    add(frontend::kBuiltins[i].name, kFunctionKind, frontend::kBuiltins[i].signature);
  if (!d.scene) {
    auto a = analyze(d);
    for (const auto& f : a->script.sema.functions) add(f.name, kFunctionKind, "user function");
    for (const auto& s : a->script.sema.symbols) {
      if (s.kind == frontend::SymKind::Function || s.kind == frontend::SymKind::Builtin) continue;
      add(s.name, s.kind == frontend::SymKind::Constant ? kConstantKind : kVariableKind,
          s.kind == frontend::SymKind::Local ? "local" : "global");
    }
  }
  for (const char* g : frontend::kStandardGlobals) add(g, kVariableKind, "input/output global");
  return {{"isIncomplete", false}, {"items", items}};
}

}  // namespace fscript::lsp
