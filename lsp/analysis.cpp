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

bool scene_context(const std::string& text, size_t at, std::string& node) {
  bool in_string = false;
  std::vector<size_t> opens;
  for (size_t i = 0; i < at && i < text.size(); ++i) {
    char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '#') {
      size_t nl = text.find('\n', i);
      i = nl == std::string::npos ? text.size() : nl;
    } else if (c == '{') {
      opens.push_back(i);
    } else if (c == '}' && !opens.empty()) {
      opens.pop_back();
    }
  }
  if (in_string || opens.empty()) return in_string;
  size_t b, e, end = opens.back();
  while (end > 0 && std::isspace(static_cast<unsigned char>(text[end - 1]))) --end;
  if (end > 0 && word_at(text, end - 1, b, e)) node = text.substr(b, e - b);
  return false;
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
    script.first_line = s.script.line - 1;
    base = start;
    return true;
  }
  return false;
}

// A call of the user function `name` (Math.NAME always calls the built-in).
static bool calls(const frontend::Expr& ex, const std::string& name) {
  return ex.kind == frontend::ExprKind::Call && ex.name == name && !ex.builtin_only;
}

SymbolRef symbol_at(const Analysis& a, const std::string& text, size_t offset) {
  SymbolRef r;
  size_t b, e;
  if (!word_at(text, offset, b, e)) return r;
  r.word = text.substr(b, e - b);
  r.name = {static_cast<uint32_t>(b), static_cast<uint32_t>(e)};
  const auto& sema = a.script.sema;
  const auto& prog = *a.script.prog;
  auto covers = [&](const frontend::Span& s) { return s.begin <= b && b < std::max(s.end, s.begin + 1); };
  auto found = [&](SymbolRef::Kind k, int index) {
    r.kind = k;
    r.index = index;
    return r;
  };
  // A user function's declaration or one of its calls; Math.NAME always names the built-in.
  int f = sema.function_index(r.word, false);
  bool user = f >= 0 && sema.functions[static_cast<size_t>(f)].decl;
  if (user && covers(sema.functions[static_cast<size_t>(f)].decl->name_span))
    return found(SymbolRef::Kind::Function, f);
  for (const auto& ex : prog.expr_arena) {
    if (ex->kind != frontend::ExprKind::Call || ex->name != r.word || !covers(ex->name_span)) continue;
    if (user && !ex->builtin_only) return found(SymbolRef::Kind::Function, f);
    if (ex->sym <= -2) return found(SymbolRef::Kind::Builtin, -2 - ex->sym);  // also `Sin`, read as `sin`
    if (ex->sym >= 0 && sema.symbols[static_cast<size_t>(ex->sym)].kind == frontend::SymKind::Function)
      return found(SymbolRef::Kind::Function, sema.symbols[static_cast<size_t>(ex->sym)].slot);
    int k = frontend::find_builtin(r.word);
    return k >= 0 ? found(SymbolRef::Kind::Builtin, k) : r;
  }
  // A variable: an occurrence sema resolved, a declaration, or a parameter.
  for (const auto& ex : prog.expr_arena)
    if (ex->sym >= 0 && ex->name == r.word && covers(ex->name_span)) return found(SymbolRef::Kind::Variable, ex->sym);
  for (const auto& st : prog.stmt_arena)
    for (const auto& d : st->decls)
      if (d.sym >= 0 && d.name == r.word && covers(d.span)) return found(SymbolRef::Kind::Variable, d.sym);
  for (size_t k = 0; k < sema.symbols.size(); ++k)
    if (sema.symbols[k].name == r.word && sema.symbols[k].decl.begin == b)
      return found(SymbolRef::Kind::Variable, static_cast<int>(k));
  if (user) return found(SymbolRef::Kind::Function, f);
  if (int k = frontend::find_builtin(r.word); k >= 0) return found(SymbolRef::Kind::Builtin, k);
  return r;
}

std::vector<frontend::Span> occurrences(const Analysis& a, const std::string& text, size_t offset) {
  std::vector<frontend::Span> out;
  SymbolRef r = symbol_at(a, text, offset);
  const auto& sema = a.script.sema;
  const auto& prog = *a.script.prog;
  if (r.kind == SymbolRef::Kind::Function) {
    out.push_back(sema.functions[static_cast<size_t>(r.index)].decl->name_span);
    for (const auto& ex : prog.expr_arena)
      if (calls(*ex, r.word)) out.push_back(ex->name_span);
    return out;
  }
  if (r.kind != SymbolRef::Kind::Variable) return out;
  for (const auto& st : prog.stmt_arena)
    for (const auto& d : st->decls)
      if (d.sym == r.index) out.push_back({d.span.begin, d.span.begin + static_cast<uint32_t>(d.name.size())});
  for (const auto& ex : prog.expr_arena)
    if (ex->sym == r.index && ex->name == r.word) out.push_back(ex->name_span);
  const frontend::Symbol& s = sema.symbols[static_cast<size_t>(r.index)];
  if (out.empty() || s.kind == frontend::SymKind::Global) {
    bool have = false;
    for (const auto& o : out) have |= o.begin == s.decl.begin;
    if (!have && s.decl.end > s.decl.begin)
      out.push_back({s.decl.begin, s.decl.begin + static_cast<uint32_t>(r.word.size())});
  }
  return out;
}

}  // namespace fscript::lsp
