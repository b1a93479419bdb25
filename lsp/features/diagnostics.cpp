// textDocument/publishDiagnostics: the same diagnostics as `fscript check`, for .fs and .wrl.
#include "frontend/check.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

json range_of(const std::string& text, uint32_t line, uint32_t col, uint32_t length) {
  Position a = position_of_line_col(text, line, col), b = position_of_line_col(text, line, col + std::max(1u, length));
  return {{"start", {{"line", a.line}, {"character", a.character}}},
          {"end", {{"line", b.line}, {"character", b.character}}}};
}

json range_of_span(const std::string& text, uint32_t begin, uint32_t end) {
  Position a = position_of(text, begin), b = position_of(text, end);
  return {{"start", {{"line", a.line}, {"character", a.character}}},
          {"end", {{"line", b.line}, {"character", b.character}}}};
}

Position position_param(const json& params) {
  Position p;
  const json& pos = params.at("position");
  p.line = pos.at("line").get<uint32_t>();
  p.character = pos.at("character").get<uint32_t>();
  return p;
}

json diagnostics(const Document& d) {
  frontend::DiagnosticSink sink;
  std::vector<frontend::Diagnostic> all;
  if (d.scene) {
    frontend::check_scene(d.uri, d.text, sink);
  } else {  // check_script's steps, on the analysis the other features share
    auto a = analyze_document(d);
    all = a->diag.all();
    if (!a->diag.has_errors()) frontend::lowering_warnings(a->script, sink);
  }
  all.insert(all.end(), sink.all().begin(), sink.all().end());
  json list = json::array();
  for (const auto& diag : all) {
    int severity = diag.severity == frontend::Severity::Error ? 1
        : diag.severity == frontend::Severity::Warning        ? 2
                                                              : 3;
    list.push_back({{"range", range_of(d.text, diag.pos.line, diag.pos.col, diag.length)},
                    {"severity", severity},
                    {"source", "fscript"},
                    {"message", diag.message}});
  }
  return {{"uri", d.uri}, {"version", d.version}, {"diagnostics", list}};
}

}  // namespace fscript::lsp
