// Analysis of a document for the language features.
#include "lsp/analysis.h"

#include <cctype>

#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"

namespace fscript::lsp {

std::shared_ptr<const Analysis> analyze_document(const Document& d) {
  if (d.analysis && d.analysed_revision == d.revision) return d.analysis;
  auto a = std::make_shared<Analysis>();
  frontend::load_script(std::make_unique<frontend::SourceFile>(d.uri, d.text), a->diag, a->script);
  d.analysis = a;
  d.analysed_revision = d.revision;
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

bool embedded_script_at(const Document& scene, size_t offset, Document& script, size_t& base) {
  frontend::DiagnosticSink ignored;
  vrml::Scene parsed;
  vrml::parse_scene(std::make_unique<frontend::SourceFile>(scene.uri, scene.text), ignored, parsed);
  for (const auto& s : vrml::scene_scripts(parsed)) {
    size_t start = offset_of(scene.text, position_of_line_col(scene.text, s.script.line, s.script.col));
    if (offset < start || offset > start + s.script.text.size()) continue;
    if (scene.text.compare(start, s.script.text.size(), s.script.text) != 0) return false;  // escapes
    script.uri = scene.uri;
    script.text = s.script.text;
    script.scene = false;
    script.revision = 0;
    base = start;
    return true;
  }
  return false;
}

int find_function(const frontend::SemaResult& sema, const std::string& name) {
  int i = sema.function_index(name, false);
  return i >= 0 ? i : sema.function_index(name, true);
}

// A call of the user function `name` (Math.NAME always calls the built-in).
static bool calls(const frontend::Expr& ex, const std::string& name) {
  return ex.kind == frontend::ExprKind::Call && ex.name == name && !ex.builtin_only;
}

std::vector<frontend::Span> occurrences(const Analysis& a, const std::string& text, size_t offset) {
  size_t b, e;
  std::vector<frontend::Span> out;
  if (!word_at(text, offset, b, e)) return out;
  std::string word = text.substr(b, e - b);
  const auto& sema = a.script.sema;
  const auto& prog = *a.script.prog;
  auto covers = [&](const frontend::Span& s) { return s.begin <= b && b < s.end; };
  // A function: its declaration or one of its calls is under the cursor.
  int f = sema.function_index(word, false);
  bool on_function = false;
  if (f >= 0 && sema.functions[static_cast<size_t>(f)].decl) {
    on_function = covers(sema.functions[static_cast<size_t>(f)].decl->name_span);
    for (const auto& ex : prog.expr_arena)
      on_function |= calls(*ex, word) && covers(ex->name_span);
  }
  if (on_function) {
    out.push_back(sema.functions[static_cast<size_t>(f)].decl->name_span);
    for (const auto& ex : prog.expr_arena)
      if (calls(*ex, word)) out.push_back(ex->name_span);
    return out;
  }
  // A variable: the symbol of the name under the cursor, then everything that resolves to it.
  int sym = -1;
  for (const auto& ex : prog.expr_arena)
    if (ex->sym >= 0 && ex->name == word && covers(ex->name_span)) sym = ex->sym;
  for (const auto& st : prog.stmt_arena)
    for (const auto& d : st->decls)
      if (d.sym >= 0 && d.name == word && covers(d.span)) sym = d.sym;
  if (sym < 0) return out;
  for (const auto& st : prog.stmt_arena)
    for (const auto& d : st->decls)
      if (d.sym == sym) out.push_back({d.span.begin, d.span.begin + static_cast<uint32_t>(d.name.size())});
  for (const auto& ex : prog.expr_arena)
    if (ex->sym == sym && ex->name == word) out.push_back(ex->name_span);
  const frontend::Symbol& s = sema.symbols[static_cast<size_t>(sym)];
  if (out.empty() || s.kind == frontend::SymKind::Global) {
    bool have = false;
    for (const auto& o : out) have |= o.begin == s.decl.begin;
    if (!have && s.decl.end > s.decl.begin) out.push_back({s.decl.begin, s.decl.begin + static_cast<uint32_t>(word.size())});
  }
  return out;
}

}  // namespace fscript::lsp
