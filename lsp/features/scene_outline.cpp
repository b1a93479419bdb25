// The outline of a .wrl for the editor: document symbols (nodes with their DEF names, PROTOs and
// EXTERNPROTOs, and the functions of the FScript inside), folding ranges (node bodies, lists,
// multi-line strings, and the scripts' own blocks) and semantic tokens (VRML keywords, node types,
// fields, DEF/USE names, numbers, strings, comments, and the scripts' own tokens). All from the
// VRML lexer's tokens, so a scene with errors still gets an outline of what it has.
#include <algorithm>
#include <memory>
#include <set>

#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_lexer.h"
#include "frontend/vrml/vrml_parser.h"
#include "lsp/features/features.h"

namespace fscript::lsp {
namespace {

using vrml::VTok;
using vrml::VToken;

// LSP SymbolKind values.
constexpr int kClassKind = 5, kInterfaceKind = 11;

struct Lexed {
  std::vector<VToken> tokens;
  size_t start = 0;  // the first byte after the header line
};

Lexed lex_scene(const Document& d) {
  Lexed out;
  if (d.text.rfind("#VRML", 0) == 0) {
    size_t nl = d.text.find('\n');
    out.start = nl == std::string::npos ? d.text.size() : nl + 1;
  }
  frontend::SourceFile file(d.uri, d.text);
  frontend::DiagnosticSink ignored;
  out.tokens = vrml::lex_vrml(file, out.start, ignored);
  return out;
}

// The scene's FScript strings whose text is the file's own bytes (no escapes), as documents of
// their own, with the byte where each starts in the .wrl.
struct Script {
  Document doc;
  size_t base;
};

std::vector<Script> scripts_of(const Document& d) {
  frontend::DiagnosticSink ignored;
  vrml::Scene parsed;
  vrml::parse_scene(std::make_unique<frontend::SourceFile>(d.uri, d.text), ignored, parsed);
  std::vector<Script> out;
  for (const auto& s : vrml::scene_scripts(parsed)) {
    size_t start = offset_of(d.text, position_of_line_col(d.text, s.script.line, s.script.col));
    if (d.text.compare(start, s.script.text.size(), s.script.text) != 0) continue;  // escaped: positions differ
    Script sc{Document{}, start};
    sc.doc.uri = d.uri, sc.doc.text = s.script.text;
    out.push_back(std::move(sc));
  }
  return out;
}

bool is(const VToken& t, const char* id) { return t.kind == VTok::Id && t.text == id; }

// A symbol with byte offsets until it is written out.
struct Symbol {
  std::string name;
  int kind;
  uint32_t begin, end, name_begin, name_end;
  std::vector<std::unique_ptr<Symbol>> children;
  json scripts = json::array();  // symbols of scripts inside it, already in .wrl positions
};

json to_json(const Document& d, const Symbol& s) {
  json children = s.scripts;
  for (const auto& c : s.children) children.push_back(to_json(d, *c));
  json out = {{"name", s.name},
              {"kind", s.kind},
              {"range", range_of_span(d.text, s.begin, s.end)},
              {"selectionRange", range_of_span(d.text, s.name_begin, s.name_end)}};
  if (!children.empty()) out["children"] = children;
  return out;
}

// Moves every range of `result` (positions in `script`) by the script's place in the .wrl.
void shift_ranges(json& result, const Script& script, const Document& scene) {
  if (result.is_array()) {
    for (json& item : result) shift_ranges(item, script, scene);
    return;
  }
  if (!result.is_object()) return;
  for (auto& [key, value] : result.items()) {
    if (key != "range" && key != "selectionRange") {
      shift_ranges(value, script, scene);
      continue;
    }
    for (const char* end : {"start", "end"}) {
      Position q{value[end]["line"].get<uint32_t>(), value[end]["character"].get<uint32_t>()};
      Position out = position_of(scene.text, script.base + offset_of(script.doc.text, q));
      value[end] = {{"line", out.line}, {"character", out.character}};
    }
  }
}

}  // namespace

json scene_symbols(const Document& d) {
  Lexed lx = lex_scene(d);
  const std::vector<VToken>& t = lx.tokens;
  Symbol root{"", 0, 0, 0, 0, 0, {}, json::array()};
  // Per open brace: the symbol it belongs to (a node, a PROTO's body) or none (kept for balance).
  std::vector<Symbol*> open;
  std::vector<Symbol*> all;  // every symbol, for placing the scripts
  Symbol* pending_proto = nullptr;
  auto parent = [&]() -> Symbol& {
    for (auto it = open.rbegin(); it != open.rend(); ++it)
      if (*it) return **it;
    return root;
  };
  for (size_t i = 0; i < t.size(); ++i) {
    const VToken& k = t[i];
    if ((is(k, "PROTO") || is(k, "EXTERNPROTO")) && i + 1 < t.size() && t[i + 1].kind == VTok::Id) {
      auto s = std::make_unique<Symbol>(Symbol{t[i + 1].text,
                                               kInterfaceKind,
                                               k.span.begin,
                                               t[i + 1].span.end,
                                               t[i + 1].span.begin,
                                               t[i + 1].span.end,
                                               {},
                                               json::array()});
      Symbol* p = s.get();
      parent().children.push_back(std::move(s));
      all.push_back(p);
      if (is(k, "PROTO")) pending_proto = p;
      ++i;
      continue;
    }
    if (k.kind == VTok::RBracket && pending_proto == nullptr && !all.empty() && all.back()->kind == kInterfaceKind &&
        all.back()->end < k.span.end && open.size() == 0)
      all.back()->end = k.span.end;  // an EXTERNPROTO's interface and urls end it
    if (k.kind == VTok::LBrace) {
      Symbol* owner = nullptr;
      if (i > 0 && t[i - 1].kind == VTok::Id && !is(t[i - 1], "PROTO")) {  // TYPE { : a node
        const VToken& type = t[i - 1];
        bool def = i >= 3 && is(t[i - 3], "DEF") && t[i - 2].kind == VTok::Id;
        std::string name = def ? t[i - 2].text + " " + type.text : type.text;
        uint32_t begin = def ? t[i - 3].span.begin : type.span.begin;
        auto s = std::make_unique<Symbol>(Symbol{name,
                                                 kClassKind,
                                                 begin,
                                                 k.span.end,
                                                 def ? t[i - 2].span.begin : type.span.begin,
                                                 def ? t[i - 2].span.end : type.span.end,
                                                 {},
                                                 json::array()});
        owner = s.get();
        parent().children.push_back(std::move(s));
        all.push_back(owner);
      } else if (pending_proto) {  // the PROTO's body
        owner = pending_proto;
        pending_proto = nullptr;
      }
      open.push_back(owner);
    } else if (k.kind == VTok::RBrace && !open.empty()) {
      if (open.back()) open.back()->end = k.span.end;
      open.pop_back();
    }
  }
  // The scripts' functions and globals, under the innermost symbol that holds each script.
  for (Script& s : scripts_of(d)) {
    json inner = document_symbols(s.doc);
    shift_ranges(inner, s, d);
    Symbol* holder = &root;
    for (Symbol* c : all)
      if (c->begin <= s.base && s.base < c->end &&
          (holder == &root || c->end - c->begin <= holder->end - holder->begin))
        holder = c;
    for (json& x : inner) holder->scripts.push_back(x);
  }
  json list = root.scripts;
  for (const auto& c : root.children) list.push_back(to_json(d, *c));
  return list;
}

json scene_folding(const Document& d) {
  Lexed lx = lex_scene(d);
  json list = json::array();
  std::set<std::pair<uint32_t, uint32_t>> seen;
  auto add = [&](size_t begin, size_t end) {
    Position p = position_of(d.text, begin), q = position_of(d.text, end > begin ? end - 1 : begin);
    if (q.line > p.line && seen.insert({p.line, q.line}).second)
      list.push_back({{"startLine", p.line}, {"endLine", q.line}});
  };
  std::vector<uint32_t> braces, brackets;
  for (const VToken& k : lx.tokens) {
    if (k.kind == VTok::LBrace) braces.push_back(k.span.begin);
    if (k.kind == VTok::LBracket) brackets.push_back(k.span.begin);
    if (k.kind == VTok::RBrace && !braces.empty()) add(braces.back(), k.span.end), braces.pop_back();
    if (k.kind == VTok::RBracket && !brackets.empty()) add(brackets.back(), k.span.end), brackets.pop_back();
    if (k.kind == VTok::String) add(k.span.begin, k.span.end);
  }
  for (Script& s : scripts_of(d))
    for (const json& r : folding_ranges(s.doc)) {  // the script's lines, moved to the .wrl's
      uint32_t first = position_of(d.text, s.base).line;
      json moved = r;
      moved["startLine"] = r["startLine"].get<uint32_t>() + first;
      moved["endLine"] = r["endLine"].get<uint32_t>() + first;
      if (seen.insert({moved["startLine"].get<uint32_t>(), moved["endLine"].get<uint32_t>()}).second)
        list.push_back(moved);
    }
  return list;
}

std::vector<SemanticToken> scene_token_list(const Document& d) {
  Lexed lx = lex_scene(d);
  const std::vector<VToken>& t = lx.tokens;
  std::vector<Script> scripts = scripts_of(d);
  static const std::set<std::string> kKeywords = {"DEF",      "USE",  "PROTO", "EXTERNPROTO",  "ROUTE",
                                                  "TO",       "IS",   "field", "exposedField", "eventIn",
                                                  "eventOut", "TRUE", "FALSE", "NULL"};
  std::vector<SemanticToken> out;
  auto split_lines = [&](uint32_t b, uint32_t e, SemanticType type) {  // a token per line
    while (b < e) {
      size_t nl = d.text.find('\n', b);
      uint32_t stop = nl == std::string::npos || nl >= e ? e : static_cast<uint32_t>(nl);
      if (stop > b) out.push_back({b, stop, type, 0});
      b = stop + 1;
    }
  };
  // Comments live in the gaps between tokens (the lexer takes them as white space).
  size_t gap = lx.start;
  auto comments_before = [&](size_t end) {
    for (size_t at = gap; at < end; ++at) {
      if (d.text[at] != '#') continue;
      size_t nl = d.text.find('\n', at);
      size_t stop = std::min(nl == std::string::npos ? d.text.size() : nl, end);
      out.push_back({static_cast<uint32_t>(at), static_cast<uint32_t>(stop), SemanticType::Comment, 0});
      at = stop;
    }
  };
  for (size_t i = 0; i < t.size(); ++i) {
    const VToken& k = t[i];
    if (k.kind == VTok::Eof) break;
    comments_before(k.span.begin);
    gap = k.span.end;
    const VToken* prev = i > 0 ? &t[i - 1] : nullptr;
    const VToken* next = i + 1 < t.size() ? &t[i + 1] : nullptr;
    switch (k.kind) {
      case VTok::Number: out.push_back({k.span.begin, k.span.end, SemanticType::Number, 0}); break;
      case VTok::String: {
        auto script =
            std::find_if(scripts.begin(), scripts.end(), [&](const Script& s) { return s.base == k.span.begin + 1u; });
        if (script == scripts.end()) {
          split_lines(k.span.begin, k.span.end, SemanticType::String);
          break;
        }
        out.push_back({k.span.begin, k.span.begin + 1, SemanticType::String, 0});  // the quotes stay strings
        for (const SemanticToken& s : script_token_list(script->doc))
          out.push_back({static_cast<uint32_t>(s.begin + script->base), static_cast<uint32_t>(s.end + script->base),
                         s.type, s.modifiers});
        out.push_back({k.span.end - 1, k.span.end, SemanticType::String, 0});
        break;
      }
      case VTok::Id: {
        SemanticType type = SemanticType::Property;  // a field name, by default
        int modifiers = 0;
        if (kKeywords.count(k.text)) type = SemanticType::Keyword;
        else if (prev && (is(*prev, "DEF") || is(*prev, "USE") || is(*prev, "ROUTE") || is(*prev, "TO")))
          type = SemanticType::Variable, modifiers = is(*prev, "DEF") ? kDeclarationModifier : 0;
        else if (prev && (is(*prev, "PROTO") || is(*prev, "EXTERNPROTO")))
          type = SemanticType::Type, modifiers = kDeclarationModifier;
        else if (next && next->kind == VTok::LBrace) type = SemanticType::Type;
        else if (k.text.size() > 2 && (k.text.rfind("SF", 0) == 0 || k.text.rfind("MF", 0) == 0) && prev &&
                 (is(*prev, "field") || is(*prev, "exposedField") || is(*prev, "eventIn") || is(*prev, "eventOut")))
          type = SemanticType::Type;  // a field type in an interface declaration
        out.push_back({k.span.begin, k.span.end, type, modifiers});
        break;
      }
      case VTok::Period: out.push_back({k.span.begin, k.span.end, SemanticType::Operator, 0}); break;
      case VTok::Eof:
      case VTok::LBracket:
      case VTok::RBracket:
      case VTok::LBrace:
      case VTok::RBrace:
      case VTok::Error: break;
    }
  }
  comments_before(d.text.size());
  std::sort(out.begin(), out.end(), [](const SemanticToken& a, const SemanticToken& b) { return a.begin < b.begin; });
  return out;
}

}  // namespace fscript::lsp
