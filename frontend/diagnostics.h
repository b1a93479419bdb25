#pragma once
// Diagnostics: user errors and warnings with a position, collected in a sink, never thrown.
// Rendered as `file:line:col: error: message`, the source line and a caret (gcc/clang style).
#include <string>
#include <vector>

#include "frontend/source.h"

namespace fscript::frontend {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string path;
  LineCol pos;
  std::string message;
  std::string line_text;  // the source line (a window of it when very long), for the caret
  uint32_t caret_col = 1; // column of the caret within line_text
  uint32_t length = 1;    // caret underline length
};

// A one-character diagnostic at `pos`, whose line reads `line_text` (made printable, and cut to a
// window around the caret when very long).
Diagnostic located(Severity sev, std::string path, LineCol pos, std::string line_text, std::string message);

// Collects diagnostics from every stage; the LSP publishes the same structs.
class DiagnosticSink {
 public:
  void report(const SourceFile& file, Severity sev, Span span, std::string message);
  void error(const SourceFile& file, Span span, std::string message) {
    report(file, Severity::Error, span, std::move(message));
  }
  void warning(const SourceFile& file, Span span, std::string message) {
    report(file, Severity::Warning, span, std::move(message));
  }
  // An error with no source position (a file that cannot be read).
  void plain_error(const std::string& path, std::string message);

  bool has_errors() const { return errors_ > 0; }
  size_t error_count() const { return errors_; }
  const std::vector<Diagnostic>& all() const { return diags_; }
  void clear() {
    diags_.clear();
    errors_ = 0;
  }

 private:
  std::vector<Diagnostic> diags_;
  size_t errors_ = 0;
};

// gcc-style text for one diagnostic (three lines: header, source, caret).
std::string render(const Diagnostic& d);
std::string render_all(const DiagnosticSink& sink);

}  // namespace fscript::frontend
