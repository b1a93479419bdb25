// Diagnostic sink and gcc-style rendering.
#include "frontend/diagnostics.h"

namespace fscript::frontend {

Diagnostic located(Severity sev, std::string path, LineCol pos, std::string line_text, std::string message) {
  Diagnostic d;
  d.severity = sev;
  d.path = std::move(path);
  d.pos = pos;
  d.message = std::move(message);
  d.line_text = std::move(line_text);
  for (char& c : d.line_text)  // binary input must not reach the terminal
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) c = '?';
  d.caret_col = d.pos.col;
  // A very long line (a megabyte expression, a minified scene) is shown as a window around the caret.
  constexpr uint32_t kWindow = 160;
  if (d.line_text.size() > 2 * kWindow) {
    uint32_t from = d.caret_col > kWindow ? d.caret_col - kWindow : 1;
    d.line_text = d.line_text.substr(from - 1, 2 * kWindow);
    d.caret_col -= from - 1;
  }
  return d;
}

void DiagnosticSink::report(const SourceFile& file, Severity sev, Span span, std::string message) {
  Diagnostic d = located(sev, file.path(), file.position(span.begin), file.line_text(span.begin), std::move(message));
  LineCol end = file.position(span.end > span.begin ? span.end : span.begin + 1);
  d.length = end.line == d.pos.line && end.col > d.pos.col ? end.col - d.pos.col : 1;
  if (sev == Severity::Error) ++errors_;
  diags_.push_back(std::move(d));
}

void DiagnosticSink::plain_error(const std::string& path, std::string message) {
  Diagnostic d;
  d.path = path;
  d.pos = {0, 0};
  d.message = std::move(message);
  ++errors_;
  diags_.push_back(std::move(d));
}

static const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

std::string render(const Diagnostic& d) {
  std::string out = d.path;
  if (d.pos.line > 0) out += ":" + std::to_string(d.pos.line) + ":" + std::to_string(d.pos.col);
  out += std::string(": ") + severity_name(d.severity) + ": " + d.message + "\n";
  if (d.pos.line == 0) return out;
  out += d.line_text + "\n";
  std::string caret;
  for (uint32_t i = 1; i < d.caret_col && i <= d.line_text.size(); ++i)
    caret += d.line_text[i - 1] == '\t' ? '\t' : ' ';
  caret += '^';
  uint32_t room = d.line_text.size() >= d.caret_col ? uint32_t(d.line_text.size()) - d.caret_col + 1 : 1;
  for (uint32_t i = 1; i < d.length && i < room; ++i) caret += '~';
  out += caret + "\n";
  return out;
}

std::string render_all(const DiagnosticSink& sink) {
  std::string out;
  for (const auto& d : sink.all()) out += render(d);
  return out;
}

}  // namespace fscript::frontend
