// fscript fmt: the canonical layout of a script, or of every script inside a .wrl scene (the rest
// of the scene byte for byte).
#include <algorithm>
#include <fstream>
#include <iostream>

#include "frontend/check.h"
#include "frontend/fscript/formatter.h"
#include "frontend/fscript/parser.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"
#include "runtime/support/files.h"
#include "tools/fscript/commands.h"

namespace fscript::cli {
namespace {

// Byte offset of 1-based (line, col) in `text`.
size_t offset_of(const std::string& text, uint32_t line, uint32_t col) {
  size_t at = 0;
  for (uint32_t l = 1; l < line && at != std::string::npos; ++l) {
    at = text.find('\n', at);
    if (at != std::string::npos) ++at;
  }
  return at == std::string::npos ? text.size() : at + col - 1;
}

// The end of the VRML string whose contents start at `begin`: its closing quote.
size_t string_end(const std::string& text, size_t begin) {
  for (size_t i = begin; i < text.size(); ++i) {
    if (text[i] == '\\') ++i;
    else if (text[i] == '"') return i;
  }
  return std::string::npos;
}

std::string vrml_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

// The script's formatted text, its leading and trailing white space kept; a script on one line
// stays on one line, without a ';' it did not have (a definition "1 - x*x" is an expression);
// one that starts on a line of its own is indented as that line is.
bool format_embedded(const std::string& path, const std::string& text, std::string& out,
                     frontend::DiagnosticSink& diag) {
  size_t b = text.find_first_not_of(" \t\r\n"), e = text.find_last_not_of(" \t\r\n");
  if (b == std::string::npos) return out = text, true;
  std::string body = text.substr(b, e - b + 1);
  frontend::SourceFile src(path, body);
  auto prog = frontend::parse(src, diag);
  if (diag.has_errors()) return false;
  std::string formatted = frontend::format_program(*prog, body);
  while (!formatted.empty() && formatted.back() == '\n') formatted.pop_back();
  if (body.find('\n') == std::string::npos) {
    std::string line;
    for (char c : formatted) line += c == '\n' ? ' ' : c;
    size_t lead = line.find_first_not_of(' ');
    line = lead == std::string::npos ? "" : line.substr(lead);
    for (size_t at; (at = line.find("  ")) != std::string::npos;) line.erase(at, 1);
    if (body.back() != ';' && !line.empty() && line.back() == ';') line.pop_back();
    formatted = line;
  } else if (size_t nl = text.rfind('\n', b); nl != std::string::npos) {
    // A script that starts on a line of its own keeps that line's indentation for all of it.
    std::string indent = text.substr(nl + 1, b - nl - 1), indented;
    for (size_t at = 0; at < formatted.size(); ++at) {
      indented += formatted[at];
      if (formatted[at] == '\n' && at + 1 < formatted.size() && formatted[at + 1] != '\n') indented += indent;
    }
    formatted = indented;
  }
  out = text.substr(0, b) + formatted + text.substr(e + 1);
  return true;
}

// The scene with each of its scripts formatted; false (diagnostics printed) when a script does not
// parse or the result would not check as the original does.
bool format_scene(const std::string& path, const std::string& text, std::string& out) {
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  if (!vrml::parse_scene(std::make_unique<frontend::SourceFile>(path, text), diag, scene)) {
    print_diagnostics(diag);
    return false;
  }
  struct Edit {
    size_t begin, end;
    std::string text;
  };
  std::vector<Edit> edits;
  for (const auto& s : vrml::scene_scripts(scene)) {
    if (frontend::is_affine_field(s.script.field) || s.script.field == "operation") continue;
    size_t begin = offset_of(text, s.script.line, s.script.col), end = string_end(text, begin);
    if (begin == 0 || begin > text.size() || text[begin - 1] != '"' || end == std::string::npos) continue;
    std::string formatted;
    frontend::DiagnosticSink d;
    if (!format_embedded(path, s.script.text, formatted, d)) {
      frontend::DiagnosticSink placed;  // the error again, at the scene's own line and column
      frontend::check_scene(path, text, placed);
      print_diagnostics(placed.has_errors() ? placed : d);
      return false;
    }
    edits.push_back({begin, end, vrml_escaped(formatted)});
  }
  // In file order, each string once (a node USEd again, or a PROTO's body, lists a script twice).
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin < b.begin; });
  edits.erase(std::unique(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.begin == b.begin; }),
              edits.end());
  out.clear();
  size_t at = 0;
  for (const Edit& e : edits) out += text.substr(at, e.begin - at) + e.text, at = e.end;
  out += text.substr(at);
  frontend::DiagnosticSink before, after;
  if (frontend::check_scene(path, text, before) && !frontend::check_scene(path, out, after)) {
    std::cerr << path << ": error: formatting its scripts would break the scene (a formatter bug): left as it is\n";
    print_diagnostics(after);
    return false;
  }
  return true;
}

// The script's own formatting (a .fs file or standard input).
bool format_script(const std::string& path, const std::string& text, std::string& out) {
  frontend::SourceFile src(path, text);
  frontend::DiagnosticSink diag;
  auto prog = frontend::parse(src, diag);
  if (diag.has_errors()) {  // never rewrite what does not parse
    print_diagnostics(diag);
    return false;
  }
  out = frontend::format_program(*prog, text);
  return true;
}

}  // namespace

int cmd_fmt(const std::string& file, bool in_place, bool check_only) {
  if (in_place && file == "-") {
    std::cerr << "error: fmt -i rewrites a file; standard input has none (drop -i)\n";
    return kExitUsage;
  }
  bool scene = file != "-" && is_scene_path(file);
  std::string text, error, formatted;
  if (scene ? !vrml::read_scene_text(file, text, error) : !read_source(file, text)) {
    if (scene) std::cerr << file << ":1:1: error: " << error << "\n";
    return kExitInput;
  }
  char magic[2] = {};
  if (scene && in_place && std::ifstream(file, std::ios::binary).read(magic, 2) && magic[0] == '\x1f' &&
      magic[1] == '\x8b') {
    std::cerr << "error: " << file << " is gzipped: fmt prints it formatted, and -i would write it uncompressed\n";
    return kExitUsage;
  }
  std::string name = file == "-" ? "<stdin>" : file;
  if (!(scene ? format_scene(name, text, formatted) : format_script(name, text, formatted))) return kExitInput;
  if (check_only) {
    if (formatted == text) return kExitOk;
    std::cerr << name << ": not formatted (fscript fmt -i " << name << " formats it)\n";
    return kExitInput;
  }
  if (!in_place) {
    std::cout << formatted;
    return kExitOk;
  }
  if (formatted != text && !support::write_file_atomic(file, formatted, error)) {
    std::cerr << "error: " << error << "\n";
    return kExitInput;
  }
  return kExitOk;
}

}  // namespace fscript::cli
