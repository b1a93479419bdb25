// textDocument/references, rename, signatureHelp, foldingRange and codeAction (quick fixes for
// the letter-case slip and a missing ';').
#include <regex>
#include <set>

#include "frontend/fscript/sema.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

namespace {

bool valid_name(const std::string& n) {
  static const std::regex ident("^[A-Za-z_$][A-Za-z0-9_$]*$");
  if (!std::regex_match(n, ident) || frontend::find_builtin(n) >= 0) return false;
  for (const Keyword& k : kKeywords)
    if (n == k.word) return false;
  return true;
}

}  // namespace

json references(const Document& d, const json& params) {
  json list = json::array();
  if (d.scene) return list;
  auto a = analyze_document(d);
  for (const auto& s : occurrences(*a, d.text, offset_of(d.text, position_param(params))))
    list.push_back({{"uri", d.uri}, {"range", range_of_span(d.text, s.begin, s.end)}});
  return list;
}

json rename(const Document& d, const json& params) {
  std::string name = params.at("newName").get<std::string>();
  if (!valid_name(name))
    return {{"__error", kInvalidParams}, {"message", "'" + name + "' is not a name a script can use"}};
  if (d.scene)
    return {{"__error", kRequestFailed}, {"message", "rename works on names inside the scene's FScript strings"}};
  auto a = analyze_document(d);
  size_t at = offset_of(d.text, position_param(params));
  SymbolRef r = symbol_at(*a, d.text, at);
  if (r.kind == SymbolRef::Kind::Builtin)
    return {{"__error", kRequestFailed},
            {"message", "'" + r.word + "' is a built-in; only names the script defines can be renamed"}};
  json edits = json::array();
  for (const auto& s : occurrences(*a, d.text, at))
    edits.push_back({{"range", range_of_span(d.text, s.begin, s.end)}, {"newText", name}});
  if (edits.empty()) return {{"__error", kRequestFailed}, {"message", "there is no name here that the script defines"}};
  return {{"changes", {{d.uri, edits}}}};
}

// The call around the cursor: the callee before the innermost open '(' and the commas since.
json signature_help(const Document& d, const json& params) {
  size_t at = offset_of(d.text, position_param(params));
  int depth = 0, commas = 0;
  size_t open = std::string::npos;
  for (size_t i = at; i-- > 0;) {
    char c = d.text[i];
    if (c == ')' || c == ']') ++depth;
    else if (c == '[') --depth;
    else if (c == '(' && depth-- == 0) {
      open = i;
      break;
    } else if (c == ',' && depth == 0) ++commas;
    else if (c == ';' || c == '{' || c == '}') break;
  }
  if (open == std::string::npos) return nullptr;
  size_t b, e;
  size_t end = open;
  while (end > 0 && d.text[end - 1] == ' ') --end;
  if (end == 0 || !word_at(d.text, end - 1, b, e)) return nullptr;
  // The callee, as hover and definition see it (a user function shadows the built-in).
  SymbolRef r;
  std::shared_ptr<const Analysis> a;
  if (!d.scene) {
    a = analyze_document(d);
    r = symbol_at(*a, d.text, b);
  } else if (int k = frontend::find_builtin(d.text.substr(b, e - b)); k >= 0) {
    r.kind = SymbolRef::Kind::Builtin;
    r.index = k;
  }
  std::string label;
  std::vector<std::string> params_list;
  if (r.kind == SymbolRef::Kind::Builtin) {
    label = frontend::kBuiltins[r.index].signature;
    std::string inside = label.substr(label.find('(') + 1);
    inside = inside.substr(0, inside.find(')'));
    for (size_t p = 0; !inside.empty() && p != std::string::npos;) {
      size_t q = inside.find(',', p);
      std::string one = inside.substr(p, q == std::string::npos ? std::string::npos : q - p);
      params_list.push_back(one.substr(one.find_first_not_of(' ')));
      p = q == std::string::npos ? q : q + 1;
    }
  } else if (r.kind == SymbolRef::Kind::Function) {
    const auto& fi = a->script.sema.functions[static_cast<size_t>(r.index)];
    for (int p : fi.params) params_list.push_back(a->script.sema.symbols[static_cast<size_t>(p)].name);
    label = fi.name + "(";
    for (size_t i = 0; i < params_list.size(); ++i) label += (i ? ", " : "") + params_list[i];
    label += ")";
  } else {
    return nullptr;
  }
  json ps = json::array();
  for (const auto& p : params_list) ps.push_back({{"label", p}});
  return {{"signatures", json::array({{{"label", label}, {"parameters", ps}}})},
          {"activeSignature", 0},
          {"activeParameter", commas}};
}

json folding_ranges(const Document& d) {
  if (d.scene) return scene_folding(d);
  json list = json::array();
  auto a = analyze_document(d);
  std::set<std::pair<uint32_t, uint32_t>> seen;
  auto add = [&](uint32_t begin, uint32_t end, const char* kind) {
    Position p = position_of(d.text, begin), q = position_of(d.text, end > begin ? end - 1 : begin);
    if (q.line > p.line && seen.insert({p.line, q.line}).second) {
      json r = {{"startLine", p.line}, {"endLine", q.line}};
      if (kind) r["kind"] = kind;
      list.push_back(r);
    }
  };
  for (const auto& st : a->script.prog->stmt_arena)
    if (st->kind == frontend::StmtKind::Block || st->kind == frontend::StmtKind::Function)
      add(st->span.begin, st->span.end, nullptr);
  for (const auto& c : a->script.prog->comments) add(c.span.begin, c.span.end, "comment");
  return list;
}

json code_actions(const Document& d, const json& params) {
  json actions = json::array();
  static const std::regex slip("'([^']+)' is not defined; using '([^']+)'");
  static const std::regex semicolon("^expected ';'");
  for (const json& diag : params.at("context").at("diagnostics")) {
    std::string message = diag.value("message", "");
    const json& r = diag.at("range");
    Position start{r.at("start").at("line").get<uint32_t>(), r.at("start").at("character").get<uint32_t>()};
    std::smatch m;
    json edit;
    std::string title;
    if (diag.contains("data") && diag["data"].is_object() &&
        diag["data"].contains("edits")) {  // a shape diagnostic's fix
      actions.push_back({{"title", diag["data"].value("title", "Fix the shape")},
                         {"kind", "quickfix"},
                         {"diagnostics", json::array({diag})},
                         {"isPreferred", true},
                         {"edit", {{"changes", {{d.uri, diag["data"]["edits"]}}}}}});
      continue;
    }
    if (std::regex_search(message, m, slip)) {
      title = "Change '" + m[1].str() + "' to '" + m[2].str() + "'";
      edit = {{"range", r}, {"newText", m[2].str()}};
    } else if (std::regex_search(message, semicolon)) {
      size_t at = offset_of(d.text, start);  // after the last character before the unexpected token
      while (at > 0 && std::isspace(static_cast<unsigned char>(d.text[at - 1]))) --at;
      Position p = position_of(d.text, at);
      json here = {{"line", p.line}, {"character", p.character}};
      title = "Insert ';'";
      edit = {{"range", {{"start", here}, {"end", here}}}, {"newText", ";"}};
    } else {
      continue;
    }
    actions.push_back({{"title", title},
                       {"kind", "quickfix"},
                       {"diagnostics", json::array({diag})},
                       {"isPreferred", true},
                       {"edit", {{"changes", {{d.uri, json::array({edit})}}}}}});
  }
  return actions;
}

}  // namespace fscript::lsp
