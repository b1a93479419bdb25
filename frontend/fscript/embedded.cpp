// Embedded FScript helpers.
#include "frontend/fscript/embedded.h"

#include <cctype>

namespace fscript::frontend {

bool is_fscript_field(const std::string& node_type, const std::string& n) {
  if (node_type == "FGeometry" || node_type == "FTexture3D") return n == "definition";
  if (node_type == "FMaterial")
    return n == "diffuseColor" || n == "ambientIntensity" || n == "emissiveColor" || n == "shininess" ||
        n == "specularColor" || n == "transparency";
  if (node_type == "FTransform")
    return n == "operation" || n == "center" || n == "rotation" || n == "scale" || n == "scaleOrientation" ||
        n == "translation";
  return false;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  for (size_t i = 0; i <= text.size(); ++i)
    if (i == text.size() || text[i] == '\n') {
      std::string l = text.substr(start, i - start);
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines.push_back(l);
      start = i + 1;
    }
  return lines;
}

bool is_affine_field(const std::string& n) {
  return n == "translation" || n == "scale" || n == "center" || n == "rotation" || n == "scaleOrientation";
}

namespace {

// A component [b, e) of e.text, with its position advanced from the string's start.
EmbeddedScript component(const EmbeddedScript& e, size_t b, size_t end) {
  EmbeddedScript c;
  c.field = e.field;
  c.text = e.text.substr(b, end - b);
  c.line = e.line;
  c.col = e.col;
  for (size_t i = 0; i < b; ++i) {
    if (e.text[i] == '\n') {
      ++c.line;
      c.col = 1;
    } else {
      ++c.col;
    }
  }
  return c;
}

bool single_token(const std::string& t) {
  if (t.empty()) return false;
  for (size_t i = 0; i < t.size(); ++i) {
    char ch = t[i];
    bool ok =
        std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.' || ((ch == '-' || ch == '+') && i == 0);
    if (!ok) return false;
  }
  return true;
}

}  // namespace

std::vector<EmbeddedScript> split_components(const EmbeddedScript& e) {
  std::vector<EmbeddedScript> out;
  int depth = 0;
  size_t start = 0;
  bool commas = false;
  for (size_t i = 0; i <= e.text.size(); ++i) {
    char ch = i < e.text.size() ? e.text[i] : ',';
    if (ch == '(' || ch == '[') ++depth;
    if (ch == ')' || ch == ']') --depth;
    if (ch == ',' && depth == 0) {
      commas |= i < e.text.size();
      out.push_back(component(e, start, i));
      start = i + 1;
    }
  }
  if (commas) return out;
  // No commas: white-space separated single tokens, or one expression.
  std::vector<EmbeddedScript> words;
  size_t i = 0;
  while (i < e.text.size()) {
    while (i < e.text.size() && std::isspace(static_cast<unsigned char>(e.text[i]))) ++i;
    size_t b = i;
    while (i < e.text.size() && !std::isspace(static_cast<unsigned char>(e.text[i]))) ++i;
    if (b < i) words.push_back(component(e, b, i));
  }
  for (const auto& w : words)
    if (!single_token(w.text)) return {e};
  return words;
}

}  // namespace fscript::frontend
