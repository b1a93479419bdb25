// Shared helpers of the fscript commands.
#include "tools/fscript/common.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <sstream>

#include "runtime/support/files.h"

namespace fscript::cli {

bool read_source(const std::string& path, std::string& text) {
  if (path == "-") {
    text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    return true;
  }
  std::string err;
  if (support::read_file(path, text, err, support::kMaxInputBytes)) return true;
  std::cerr << path << ":1:1: error: cannot read the file: " << err << "\n";
  return false;
}

void print_diagnostics(const frontend::DiagnosticSink& sink) { std::cerr << frontend::render_all(sink); }

bool refuse_scene(const std::string& path) {
  if (!is_scene_path(path)) return false;  // not a script: no parse errors about VRML syntax
  std::cerr << path << ": error: this is a VRML scene; fscript's commands take .fs scripts (fvrml-run " << path
            << " runs a scene, fscript check " << path << " checks its scripts)\n";
  return true;
}

int compile_file(const std::string& path, const std::string& entry, const Options& opts, Compiled& out,
                 bool want_kernel) {
  if (refuse_scene(path)) return kExitInput;
  std::string text;
  if (!read_source(path, text)) return kExitInput;
  frontend::DiagnosticSink diag;
  auto file = std::make_unique<frontend::SourceFile>(path == "-" ? "<stdin>" : path, std::move(text));
  Options o = opts;
  o.want_kernel = want_kernel;
  driver::Outcome r = driver::compile(std::move(file), driver::named_entry(entry), o, diag, out);
  print_diagnostics(diag);
  switch (r.stage) {
    case driver::Stage::Done: return kExitOk;
    case driver::Stage::Source: return kExitInput;
    case driver::Stage::Entry:
      std::cerr << out.script.file->path() << ": error: " << r.error << "\n";
      return kExitInput;
    case driver::Stage::Internal: std::cerr << "internal error: " << r.error << "\n"; return kExitInput;
    case driver::Stage::NoBackend: std::cerr << "error: " << r.error << "\n"; return kExitUsage;
    case driver::Stage::Backend: std::cerr << "error: " << r.error << "\n"; return kExitInput;
  }
  return kExitInput;
}

bool is_scene_path(const std::string& p) {
  auto ends = [&](const char* e) {
    return p.size() >= std::strlen(e) && p.compare(p.size() - std::strlen(e), std::string::npos, e) == 0;
  };
  return ends(".wrl") || ends(".wrl.gz") || ends(".wrz") || ends(".WRL");
}

std::string format_number(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
}

bool parse_number(const std::string& text, float& out) {
  size_t b = text.find_first_not_of(" \t\r");
  size_t e = text.find_last_not_of(" \t\r");
  if (b == std::string::npos) return false;
  std::string t = text.substr(b, e - b + 1);
  char* end = nullptr;
  out = std::strtof(t.c_str(), &end);
  return end && *end == '\0';
}

void print_runtime_error(const frontend::SourceFile& file, const backends::RuntimeError& err) {
  if (err.line == 0) {
    std::cerr << file.path() << ": error: " << err.message << "\n";
    return;
  }
  frontend::LineCol at{err.line, std::max(err.col, 1u)};
  std::cerr << frontend::render(
      frontend::located(frontend::Severity::Error, file.path(), at, file.line_at(err.line), err.message));
}

bool parse_size(const std::string& s, uint32_t& w, uint32_t& h) {
  size_t x = s.find_first_of("xX");
  char* end;
  unsigned long a = std::strtoul(s.c_str(), &end, 10);
  if (end == s.c_str()) return false;
  unsigned long b = a;
  if (x != std::string::npos) {
    const char* p = s.c_str() + x + 1;
    b = std::strtoul(p, &end, 10);
    if (end == p) return false;
  } else if (*end) {
    return false;
  }
  if (*end || a < 1 || b < 1 || a > 32768 || b > 32768) return false;
  w = static_cast<uint32_t>(a);
  h = static_cast<uint32_t>(b);
  return true;
}

bool parse_numbers(const std::string& s, size_t n, float* out) {
  std::stringstream ss(s);
  std::string cell;
  size_t k = 0;
  while (std::getline(ss, cell, ',')) {
    if (k >= n || !parse_number(cell, out[k]) || !std::isfinite(out[k])) return false;
    ++k;
  }
  return k == n;
}

}  // namespace fscript::cli
