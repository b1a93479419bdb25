// Analysis of a document for the language features.
#include "lsp/analysis.h"

#include <cctype>

namespace fscript::lsp {

std::unique_ptr<Analysis> analyze(const Document& d) {
  auto a = std::make_unique<Analysis>();
  frontend::load_script(std::make_unique<frontend::SourceFile>(d.uri, d.text), a->diag, a->script);
  return a;
}

bool word_at(const std::string& text, size_t offset, size_t& begin, size_t& end) {
  auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$'; };
  offset = std::min(offset, text.size());
  begin = end = offset;
  while (begin > 0 && ident(text[begin - 1])) --begin;
  while (end < text.size() && ident(text[end])) ++end;
  return end > begin && !std::isdigit(static_cast<unsigned char>(text[begin]));
}

int find_function(const frontend::SemaResult& sema, const std::string& name) {
  int i = sema.function_index(name, false);
  return i >= 0 ? i : sema.function_index(name, true);
}

}  // namespace fscript::lsp
