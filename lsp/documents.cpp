// UTF-8 text addressed in UTF-16 code units per line.
#include "lsp/documents.h"

namespace fscript::lsp {

namespace {

// Bytes of the UTF-8 sequence that starts with `lead` (1 for a stray continuation byte).
size_t sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if ((lead >> 5) == 0x6) return 2;
  if ((lead >> 4) == 0xE) return 3;
  if ((lead >> 3) == 0x1E) return 4;
  return 1;
}

size_t line_start(const std::string& text, uint32_t line) {
  size_t at = 0;
  for (uint32_t l = 0; l < line; ++l) {
    size_t nl = text.find('\n', at);
    if (nl == std::string::npos) return text.size();
    at = nl + 1;
  }
  return at;
}

}  // namespace

size_t offset_of(const std::string& text, Position p) {
  size_t at = line_start(text, p.line);
  uint32_t units = 0;
  while (at < text.size() && text[at] != '\n' && units < p.character) {
    size_t n = sequence_length(static_cast<unsigned char>(text[at]));
    units += n == 4 ? 2 : 1;
    at = std::min(text.size(), at + n);
  }
  return at;
}

Position position_of(const std::string& text, size_t offset) {
  offset = std::min(offset, text.size());
  Position p;
  size_t at = 0;
  for (;;) {
    size_t nl = text.find('\n', at);
    if (nl == std::string::npos || nl >= offset) break;
    ++p.line;
    at = nl + 1;
  }
  while (at < offset) {
    size_t n = sequence_length(static_cast<unsigned char>(text[at]));
    p.character += n == 4 ? 2 : 1;
    at += n;
  }
  return p;
}

Position position_of_line_col(const std::string& text, uint32_t line, uint32_t col) {
  size_t at = line_start(text, line > 0 ? line - 1 : 0);
  size_t end = text.find('\n', at);
  if (end == std::string::npos) end = text.size();
  return position_of(text, std::min(end, at + (col > 0 ? col - 1 : 0)));
}

Document& Documents::open(const std::string& uri, const std::string& text, int64_t version) {
  Document& d = docs_[uri];
  d.uri = uri;
  d.text = text;
  d.version = version;
  d.scene = is_scene_uri(uri);
  ++d.revision;
  return d;
}

Document* Documents::find(const std::string& uri) {
  auto it = docs_.find(uri);
  return it == docs_.end() ? nullptr : &it->second;
}

void Documents::edit(Document& d, Position from, Position to, const std::string& text) {
  size_t a = offset_of(d.text, from), b = offset_of(d.text, to);
  if (b < a) std::swap(a, b);
  d.text.replace(a, b - a, text);
  ++d.revision;
}

bool is_scene_uri(const std::string& uri) {
  auto ends = [&](const std::string& e) {
    return uri.size() >= e.size() && uri.compare(uri.size() - e.size(), e.size(), e) == 0;
  };
  return ends(".wrl") || ends(".WRL") || ends(".wrz");
}

}  // namespace fscript::lsp
