// textDocument/formatting: the whole document as `fscript fmt` lays it out (only when it parses).
#include "frontend/fscript/formatter.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

json formatting(const Document& d) {
  if (d.scene) return json::array();
  auto a = analyze_document(d);
  if (a->diag.has_errors()) {  // said, not a silent null: the editor shows the message
    frontend::Diagnostic first;
    for (const auto& dg : a->diag.all())
      if (dg.severity == frontend::Severity::Error) {
        first = dg;
        break;
      }
    return {{"__error", kRequestFailed},
            {"message",
             "cannot format while the script has errors (line " + std::to_string(first.pos.line) + ": " +
                 first.message + ")"}};
  }
  std::string text = frontend::format_program(*a->script.prog, d.text);
  if (text == d.text) return json::array();
  return json::array({{{"range", range_of_span(d.text, 0, static_cast<uint32_t>(d.text.size()))}, {"newText", text}}});
}

}  // namespace fscript::lsp
