// Whole-file checking shared by `fscript check` and the language server.
#include "frontend/check.h"

#include "frontend/fscript/embedded.h"
#include "frontend/fscript/entry.h"
#include "frontend/fscript/lower.h"
#include "frontend/fscript/script.h"
#include "frontend/vrml/inline.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"

namespace fscript::frontend {

// Lowering too, for its warnings (checking only: nothing is optimised or compiled).
void lowering_warnings(const Script& s, DiagnosticSink& diag) {
  KernelSpec spec;
  std::string err;
  if (!default_spec(s.sema, spec, err)) spec = {};
  lower_to_ir(*s.prog, s.sema, spec, *s.file, diag);
}

namespace {

// One FScript text embedded in a .wrl; false if it has errors.
bool check_embedded(const std::string& path, const std::vector<std::string>& lines, const EmbeddedScript& e,
                    DiagnosticSink& diag) {
  size_t b = e.text.find_first_not_of(" \t\r\n"), end = e.text.find_last_not_of(" \t\r\n");
  std::string trimmed = b == std::string::npos ? "" : e.text.substr(b, end - b + 1);
  std::vector<std::string> extra;
  if (e.field == "operation") {
    if (is_set_operation(trimmed)) return true;
    extra = {"f", "g"};
    for (int k = 1; k <= 16; ++k) extra.push_back("f" + std::to_string(k));
  }
  auto file = std::make_unique<SourceFile>(path, e.text, e.line, e.col);
  file->set_outer_lines(lines);
  Script s;
  size_t before = diag.error_count();
  load_script(std::move(file), diag, s, extra);
  if (diag.error_count() != before) return false;
  lowering_warnings(s, diag);
  return true;
}

}  // namespace

bool is_set_operation(const std::string& t) {
  for (const char* k : {"union", "intersection", "subtraction", "difference", "blend_union", "blend_intersection"})
    if (t == k) return true;
  return false;
}

bool check_script(const std::string& path, const std::string& text, DiagnosticSink& diag) {
  Script s;
  if (!load_script(std::make_unique<SourceFile>(path, text), diag, s)) return false;
  lowering_warnings(s, diag);
  return !diag.has_errors();
}

bool check_scene(const std::string& path, const std::string& text, DiagnosticSink& diag, bool read_inlines,
                 size_t* scripts) {
  vrml::Scene scene;
  bool ok = vrml::parse_scene(std::make_unique<SourceFile>(path, text), diag, scene);
  if (ok && read_inlines) ok = vrml::load_inlines(scene, diag);
  std::vector<std::string> lines = split_lines(text);
  auto all = vrml::scene_scripts(scene);
  if (scripts) *scripts = all.size();
  for (const auto& s : all) {
    if (!is_affine_field(s.script.field)) {
      ok &= check_embedded(path, lines, s.script, diag);
      continue;
    }
    for (const auto& c : split_components(s.script)) ok &= check_embedded(path, lines, c, diag);
  }
  return ok;
}

}  // namespace fscript::frontend
