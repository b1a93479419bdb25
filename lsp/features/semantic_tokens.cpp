// textDocument/semanticTokens/full: every token of a .fs document classified by what the compiler
// knows (a keyword, a built-in or user function, a parameter, a variable, a number, a comment),
// in LSP's relative encoding; a .wrl's from scene_outline.cpp. Multi-line comments are sent line
// by line.
#include <algorithm>
#include <map>

#include "frontend/fscript/lexer.h"
#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

struct Classified {
  SemanticType type;
  int modifiers;
};

// What each name occurrence is, by its byte offset, from the AST the features share.
std::map<uint32_t, Classified> names(const Analysis& a) {
  std::map<uint32_t, Classified> out;
  const auto& sema = a.script.sema;
  auto symbol_type = [&](int sym) {
    const auto& s = sema.symbols[static_cast<size_t>(sym)];
    return s.is_param ? SemanticType::Parameter : SemanticType::Variable;
  };
  for (const auto& st : a.script.prog->stmt_arena) {
    if (st->kind == frontend::StmtKind::Function)
      out[st->name_span.begin] = {SemanticType::Function, kDeclarationModifier};
    for (const auto& d : st->decls)
      if (d.sym >= 0) out[d.span.begin] = {symbol_type(d.sym), kDeclarationModifier};
  }
  for (const auto& ex : a.script.prog->expr_arena) {
    if (ex->kind == frontend::ExprKind::Call)
      out[ex->name_span.begin] = {SemanticType::Function,
                                  frontend::find_builtin(ex->name) >= 0 ? kDefaultLibraryModifier : 0};
    else if (ex->sym >= 0 && !out.count(ex->name_span.begin)) out[ex->name_span.begin] = {symbol_type(ex->sym), 0};
  }
  return out;
}

// LSP's relative encoding; a token across lines is dropped (the lists split those line by line).
json encode(const std::string& text, const std::vector<SemanticToken>& items) {
  json data = json::array();
  Position prev;
  for (const auto& it : items) {
    Position p = position_of(text, it.begin), q = position_of(text, it.end);
    if (q.line != p.line) continue;
    uint32_t dl = p.line - prev.line, dc = dl ? p.character : p.character - prev.character;
    data.insert(
        data.end(),
        {dl, dc, q.character - p.character, static_cast<uint32_t>(it.type), static_cast<uint32_t>(it.modifiers)});
    prev = p;
  }
  return {{"data", data}};
}

}  // namespace

json semantic_tokens_legend() {
  return {
      {"tokenTypes",
       {"keyword", "function", "parameter", "variable", "number", "comment", "operator", "string", "type", "property"}},
      {"tokenModifiers", {"declaration", "defaultLibrary"}}};
}

std::vector<SemanticToken> script_token_list(const Document& d) {
  auto a = analyze_document(d);
  frontend::DiagnosticSink ignored;
  frontend::SourceFile file(d.uri, d.text);
  frontend::LexResult lexed = frontend::lex(file, ignored);
  std::map<uint32_t, Classified> by_offset = names(*a);
  std::vector<SemanticToken> items;
  for (const auto& t : lexed.tokens) {
    if (t.kind == frontend::Tok::Eof || t.kind == frontend::Tok::Error) continue;
    Classified c{SemanticType::Operator, 0};
    if (frontend::is_keyword(t.kind)) c = {SemanticType::Keyword, 0};
    else if (t.kind == frontend::Tok::Number) c = {SemanticType::Number, 0};
    else if (t.kind == frontend::Tok::String) c = {SemanticType::String, 0};
    else if (t.kind == frontend::Tok::Ident) {
      auto it = by_offset.find(t.span.begin);
      if (it == by_offset.end()) continue;  // a name the analysis could not place
      c = it->second;
    }
    items.push_back({t.span.begin, t.span.end, c.type, c.modifiers});
  }
  for (const auto& cm : lexed.comments) {
    uint32_t b = cm.span.begin;
    while (b < cm.span.end) {  // one token per line of the comment
      size_t nl = d.text.find('\n', b);
      uint32_t e = nl == std::string::npos || nl >= cm.span.end ? cm.span.end : static_cast<uint32_t>(nl);
      if (e > b) items.push_back({b, e, SemanticType::Comment, 0});
      b = e + 1;
    }
  }
  std::sort(items.begin(), items.end(),
            [](const SemanticToken& x, const SemanticToken& y) { return x.begin < y.begin; });
  return items;
}

json semantic_tokens(const Document& d) { return encode(d.text, d.scene ? scene_token_list(d) : script_token_list(d)); }

}  // namespace fscript::lsp
