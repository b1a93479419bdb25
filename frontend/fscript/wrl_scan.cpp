// .wrl scan: VRML comments (#) and strings ("..." with \" and \\) are skipped correctly; a
// string right after an FVRML script field name is returned with its position.
#include "frontend/fscript/wrl_scan.h"

#include <cctype>

namespace fscript::frontend {

bool is_fscript_field(const std::string& n) {
  static const char* kFields[] = {"definition",    "diffuseColor", "ambientIntensity", "emissiveColor",
                                  "shininess",     "specularColor", "transparency",    "operation",
                                  "center",        "rotation",      "scale",           "scaleOrientation",
                                  "translation"};
  for (const char* f : kFields)
    if (n == f) return true;
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

std::vector<EmbeddedScript> scan_wrl(const std::string& s) {
  std::vector<EmbeddedScript> out;
  uint32_t line = 1, col = 1;
  std::string last_word;
  size_t i = 0;
  auto step = [&] {
    if (s[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
    ++i;
  };
  while (i < s.size()) {
    char c = s[i];
    if (c == '#') {
      while (i < s.size() && s[i] != '\n') step();
    } else if (c == '"') {
      step();
      EmbeddedScript e;
      e.field = last_word;
      e.line = line;
      e.col = col;
      while (i < s.size() && s[i] != '"') {
        if (s[i] == '\\' && i + 1 < s.size()) step();
        e.text += s[i];
        step();
      }
      if (i < s.size()) step();
      if (is_fscript_field(last_word) && e.text.find_first_not_of(" \t\r\n") != std::string::npos)
        out.push_back(std::move(e));
      last_word.clear();
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t b = i;
      while (i < s.size() && (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_')) step();
      last_word = s.substr(b, i - b);
    } else {
      if (!std::isspace(static_cast<unsigned char>(c)) && c != ',') last_word.clear();
      step();
    }
  }
  return out;
}

}  // namespace fscript::frontend
