// textDocument/semanticTokens/full: every token of a .fs document classified by what the compiler
// knows (a keyword, a built-in or user function, a parameter, a variable, a number, a comment),
// in LSP's relative encoding. Multi-line comments are sent line by line.
#include <map>

#include "frontend/fscript/lexer.h"
#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

enum TokenType { kKeyword, kFunction, kParameter, kVariable, kNumber, kComment, kOperator, kString };
enum Modifier { kDeclaration = 1, kDefaultLibrary = 2 };

struct Classified {
  int type, modifiers;
};

// What each name occurrence is, by its byte offset, from the AST the features share.
std::map<uint32_t, Classified> names(const Analysis& a) {
  std::map<uint32_t, Classified> out;
  const auto& sema = a.script.sema;
  auto symbol_type = [&](int sym) {
    const auto& s = sema.symbols[static_cast<size_t>(sym)];
    return s.is_param ? kParameter : kVariable;
  };
  for (const auto& st : a.script.prog->stmt_arena) {
    if (st->kind == frontend::StmtKind::Function) out[st->name_span.begin] = {kFunction, kDeclaration};
    for (const auto& d : st->decls)
      if (d.sym >= 0) out[d.span.begin] = {symbol_type(d.sym), kDeclaration};
  }
  for (const auto& ex : a.script.prog->expr_arena) {
    if (ex->kind == frontend::ExprKind::Call)
      out[ex->name_span.begin] = {kFunction, frontend::find_builtin(ex->name) >= 0 ? kDefaultLibrary : 0};
    else if (ex->sym >= 0 && !out.count(ex->name_span.begin))
      out[ex->name_span.begin] = {symbol_type(ex->sym), 0};
  }
  return out;
}

}  // namespace

json semantic_tokens_legend() {
  return {{"tokenTypes", {"keyword", "function", "parameter", "variable", "number", "comment", "operator", "string"}},
          {"tokenModifiers", {"declaration", "defaultLibrary"}}};
}

json semantic_tokens(const Document& d) {
  json data = json::array();
  if (d.scene) return {{"data", data}};
  auto a = analyze_document(d);
  frontend::DiagnosticSink ignored;
  frontend::SourceFile file(d.uri, d.text);
  frontend::LexResult lexed = frontend::lex(file, ignored);
  std::map<uint32_t, Classified> by_offset = names(*a);
  struct Item {
    uint32_t begin, end;
    Classified c;
  };
  std::vector<Item> items;
  for (const auto& t : lexed.tokens) {
    if (t.kind == frontend::Tok::Eof || t.kind == frontend::Tok::Error) continue;
    Classified c{kOperator, 0};
    if (frontend::is_keyword(t.kind)) c = {kKeyword, 0};
    else if (t.kind == frontend::Tok::Number) c = {kNumber, 0};
    else if (t.kind == frontend::Tok::String) c = {kString, 0};
    else if (t.kind == frontend::Tok::Ident) {
      auto it = by_offset.find(t.span.begin);
      if (it == by_offset.end()) continue;  // a name the analysis could not place
      c = it->second;
    }
    items.push_back({t.span.begin, t.span.end, c});
  }
  for (const auto& cm : lexed.comments) {
    uint32_t b = cm.span.begin;
    while (b < cm.span.end) {  // one token per line of the comment
      size_t nl = d.text.find('\n', b);
      uint32_t e = nl == std::string::npos || nl >= cm.span.end ? cm.span.end : static_cast<uint32_t>(nl);
      if (e > b) items.push_back({b, e, {kComment, 0}});
      b = e + 1;
    }
  }
  std::sort(items.begin(), items.end(), [](const Item& x, const Item& y) { return x.begin < y.begin; });
  Position prev;
  for (const auto& it : items) {
    Position p = position_of(d.text, it.begin), q = position_of(d.text, it.end);
    if (q.line != p.line) continue;  // a token across lines (none but comments, split above)
    uint32_t dl = p.line - prev.line, dc = dl ? p.character : p.character - prev.character;
    data.insert(data.end(), {dl, dc, q.character - p.character, it.c.type, it.c.modifiers});
    prev = p;
  }
  return {{"data", data}};
}

}  // namespace fscript::lsp
