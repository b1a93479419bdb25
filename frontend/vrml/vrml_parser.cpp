// VRML97 parser. Grammar (ISO/IEC 14772-1 annex A), simplified where it does not matter:
//   scene     -> statement*          statement -> node | 'PROTO' ... | 'EXTERNPROTO' ... | route
//   node      -> ('DEF' id)? type '{' (field value | field 'IS' id | route | proto | decl)* '}' | 'USE' id
//   route     -> 'ROUTE' id '.' id 'TO' id '.' id
// Each PROTO body has its own DEF names; PROTO names are visible after their definition, so a
// PROTO cannot instantiate itself and a node cannot USE itself.
#include "frontend/vrml/vrml_parser.h"

#include <algorithm>
#include <cstdlib>
#include <unordered_map>

#include "frontend/vrml/inline.h"
#include "frontend/vrml/vrml_lexer.h"
#include "runtime/support/suggest.h"

namespace fscript::vrml {
namespace {

using frontend::Span;

// Where names live: the file, or one PROTO body (its interface gives IS targets).
struct Scope {
  Scope* parent = nullptr;
  const ProtoDef* proto = nullptr;  // inside a PROTO body
  std::unordered_map<std::string, NodePtr> defs;
  std::unordered_map<std::string, const ProtoDef*> protos;
};

class Parser {
 public:
  Parser(const frontend::SourceFile& f, frontend::DiagnosticSink& d, Scene& out) : f_(f), d_(d), out_(out) {}

  // The built-in node table: a sequence of "Name [ declarations ]".
  bool interfaces(std::vector<Interface>& out) {
    size_t before = d_.error_count();
    toks_ = lex_vrml(f_, 0, d_);
    Scope sc;
    while (at(VTok::Id)) {
      Interface iface;
      iface.name = advance().text;
      interface(sc, iface, true);
      out.push_back(std::move(iface));
    }
    if (!at(VTok::Eof)) error(cur().span, "expected a node interface");
    return d_.error_count() == before;
  }

  bool run() {
    size_t before = d_.error_count();
    size_t start = 0;
    if (!header(start)) return false;
    toks_ = lex_vrml(f_, start, d_);
    Scope top;
    while (!at(VTok::Eof)) {
      size_t p = pos_;
      size_t nodes = out_.roots.size(), protos = out_.protos.size(), routes = out_.routes.size();
      statement(top, &out_.roots, &out_.routes);
      for (size_t k = protos; k < out_.protos.size(); ++k) out_.order.push_back({Scene::Kind::Proto, k});
      for (size_t k = nodes; k < out_.roots.size(); ++k) out_.order.push_back({Scene::Kind::Node, k});
      for (size_t k = routes; k < out_.routes.size(); ++k) out_.order.push_back({Scene::Kind::Route, k});
      if (p == pos_) skip_one();
    }
    for (auto& [name, node] : top.defs) out_.defs[name] = node;
    return d_.error_count() == before;
  }

 private:
  // ---- tokens ----
  const VToken& cur() const { return toks_[pos_]; }
  const VToken& peek(size_t k = 1) const { return toks_[std::min(pos_ + k, toks_.size() - 1)]; }
  bool at(VTok k) const { return cur().kind == k; }
  bool at_id(const char* word) const { return at(VTok::Id) && cur().text == word; }
  const VToken& advance() {
    const VToken& t = cur();
    if (!at(VTok::Eof)) ++pos_;
    return t;
  }
  void skip_one() {
    if (!at(VTok::Eof)) ++pos_;
  }
  void error(Span s, const std::string& m) {
    if (!fatal_) d_.error(f_, s, m);
  }
  std::string describe(const VToken& t) const {
    switch (t.kind) {
      case VTok::Eof: return "end of file";
      case VTok::String: return "a string";
      case VTok::Error: return "an invalid character";
      default: return "'" + f_.text().substr(t.span.begin, t.span.end - t.span.begin) + "'";
    }
  }
  bool expect(VTok k, const char* what) {
    if (at(k)) {
      advance();
      return true;
    }
    error(cur().span, std::string("expected ") + what + ", found " + describe(cur()));
    return false;
  }

  bool header(size_t& start) {
    const std::string& s = f_.text();
    size_t eol = s.find('\n');
    std::string first = s.substr(0, eol);
    if (s.rfind("BSCRYPT", 0) == 0) {
      error({0, 7},
            "this file is encrypted with Bitmanagement's BS Contact scheme (BSCRYPT), which no open tool "
            "can read; the plain-text .wrl is needed");
      return false;
    }
    if (first.rfind("#VRML V2.0 utf8", 0) != 0) {
      error({0, static_cast<uint32_t>(std::min<size_t>(first.size(), 15))},
            "not a VRML97 file: the first line must start with '#VRML V2.0 utf8'");
      return false;
    }
    start = eol == std::string::npos ? s.size() : eol + 1;
    return true;
  }

  // ---- statements ----
  void statement(Scope& sc, std::vector<NodePtr>* nodes, std::vector<Route>* routes) {
    if (at_id("PROTO")) return proto(sc);
    if (at_id("EXTERNPROTO")) return externproto(sc);
    if (at_id("ROUTE")) return route(sc, routes);
    if (NodePtr n = node(sc, 0)) nodes->push_back(n);
  }

  // ---- interfaces ----
  // decl -> ('field'|'exposedField') type id value | ('eventIn'|'eventOut') type id
  bool declaration(Scope& sc, bool with_defaults, FieldDecl& d) {
    const VToken& kw = advance();
    d.span = kw.span;
    d.access = kw.text == "field"   ? Access::Field
        : kw.text == "exposedField" ? Access::ExposedField
        : kw.text == "eventIn"      ? Access::EventIn
                                    : Access::EventOut;
    if (!at(VTok::Id) || !type_from_name(cur().text, d.type)) {
      error(cur().span, "expected a field type (SFFloat, MFNode, ...), found " + describe(cur()));
      return false;
    }
    advance();
    if (!at(VTok::Id)) {
      error(cur().span, "expected a field name, found " + describe(cur()));
      return false;
    }
    d.name = advance().text;
    bool takes_value = d.access == Access::Field || d.access == Access::ExposedField;
    if (takes_value && with_defaults) {
      d.has_default = true;
      if (at_id("IS")) return true;  // a Script declaration inside a PROTO: 'IS' handled by caller
      return value(sc, d.type, d.default_value, 1);
    }
    return true;
  }

  bool is_declaration_keyword() const {
    return at_id("field") || at_id("exposedField") || at_id("eventIn") || at_id("eventOut");
  }

  // interface -> '[' decl* ']'
  void interface(Scope& sc, Interface& iface, bool with_defaults) {
    if (!expect(VTok::LBracket, "'[' to open the interface")) return;
    while (!at(VTok::RBracket) && !at(VTok::Eof)) {
      if (!is_declaration_keyword()) {
        error(cur().span, "expected field, exposedField, eventIn or eventOut, found " + describe(cur()));
        skip_one();
        continue;
      }
      FieldDecl d;
      if (declaration(sc, with_defaults, d)) {
        if (iface.find(d.name)) error(d.span, "'" + d.name + "' is declared twice in '" + iface.name + "'");
        iface.fields.push_back(std::move(d));
      } else {
        while (!at(VTok::RBracket) && !at(VTok::Eof) && !is_declaration_keyword()) skip_one();
      }
    }
    expect(VTok::RBracket, "']' to close the interface");
  }

  // The keyword, the name and the interface, shared by PROTO (with defaults) and EXTERNPROTO.
  std::unique_ptr<ProtoDef> proto_header(Scope& sc, bool external) {
    auto def = std::make_unique<ProtoDef>();
    def->external = external;
    def->span = advance().span;
    if (!at(VTok::Id)) {
      error(cur().span,
            std::string("expected ") + (external ? "an EXTERNPROTO" : "a PROTO") + " name, found " + describe(cur()));
      return nullptr;
    }
    def->iface.name = advance().text;
    interface(sc, def->iface, !external);
    return def;
  }

  // proto -> 'PROTO' id '[' decl* ']' '{' statement* '}'
  void proto(Scope& sc) {
    auto def = proto_header(sc, false);
    if (!def) return;
    Scope body;
    body.parent = &sc;
    body.proto = def.get();
    if (expect(VTok::LBrace, "'{' to open the PROTO body")) {
      while (!at(VTok::RBrace) && !at(VTok::Eof)) {
        size_t p = pos_;
        statement(body, &def->body, &def->routes);
        if (p == pos_) skip_one();
      }
      expect(VTok::RBrace, "'}' to close the PROTO body");
    }
    sc.protos[def->iface.name] = def.get();
    out_.protos.push_back(std::move(def));
  }

  // externproto -> 'EXTERNPROTO' id '[' decl* ']' mfstring
  void externproto(Scope& sc) {
    auto def = proto_header(sc, true);
    if (!def) return;
    Span start = def->span;
    Value urls;
    if (value(sc, FieldType::MFString, urls, 1)) def->urls = urls.strs;
    bool local = std::any_of(def->urls.begin(), def->urls.end(),
                             [](const std::string& u) { return !u.empty() && !is_remote_url(u); });
    if (!is_fvrml_node(def->iface.name) && !local)  // a local file is read by load_inlines (fvrml-run)
      d_.warning(f_, start,
                 "EXTERNPROTO '" + def->iface.name +
                     "' is not fetched (no network); its instances keep "
                     "their fields but have no body");
    sc.protos[def->iface.name] = def.get();
    out_.protos.push_back(std::move(def));
  }

  // ---- nodes ----
  const ProtoDef* find_proto(const Scope& sc, const std::string& name) const {
    for (const Scope* s = &sc; s; s = s->parent) {
      auto it = s->protos.find(name);
      if (it != s->protos.end()) return it->second;
    }
    return nullptr;
  }
  NodePtr find_def(const Scope& sc, const std::string& name) const {
    auto it = sc.defs.find(name);  // DEF names do not cross PROTO bodies
    return it == sc.defs.end() ? nullptr : it->second;
  }

  NodePtr node(Scope& sc, int depth) {
    if (depth > kMaxNodeNesting) {
      error(cur().span, "nodes nested deeper than " + std::to_string(kMaxNodeNesting) + " levels");
      pos_ = toks_.size() - 1;  // give up on the rest of the file, silently
      fatal_ = true;
      return nullptr;
    }
    if (at_id("USE")) {
      advance();
      if (!at(VTok::Id)) {
        error(cur().span, "expected a name after USE, found " + describe(cur()));
        return nullptr;
      }
      const VToken& name = advance();
      NodePtr n = find_def(sc, name.text);
      if (!n) error(name.span, "USE of '" + name.text + "', which no DEF before it names");
      return n;
    }
    std::string def_name;
    if (at_id("DEF")) {
      advance();
      if (!at(VTok::Id)) {
        error(cur().span, "expected a name after DEF, found " + describe(cur()));
        return nullptr;
      }
      def_name = advance().text;
    }
    if (!at(VTok::Id)) {
      error(cur().span, "expected a node, found " + describe(cur()));
      return nullptr;
    }
    const VToken& type = advance();
    auto n = std::make_shared<Node>();
    n->type = type.text;
    n->span = type.span;
    n->file = &f_;
    n->def_name = def_name;
    resolve_type(sc, *n, type.span);
    node_body(sc, *n, depth);
    if (n->type == "Inline")  // a local file is read by load_inlines (fvrml-run), a remote one never
      if (const Value* url = n->get("url");
          url && !url->strs.empty() && std::all_of(url->strs.begin(), url->strs.end(), is_remote_url))
        d_.warning(f_, url->str_spans.empty() ? n->span : url->str_spans[0],
                   "Inline '" + url->strs[0] +
                       "' is not fetched (no network): the scene is drawn without it, and its "
                       "VRML97 output keeps the reference (to draw a copy of the file, name it first: url [\"" +
                       url->strs[0].substr(url->strs[0].find_last_of('/') + 1) + "\" \"" + url->strs[0] + "\"])");
    if (!def_name.empty()) sc.defs[def_name] = n;  // after the body: a node cannot USE itself
    return n;
  }

  // FVRML names are the built-in nodes even when the file declares them (the course files do,
  // with EXTERNPROTO; the plug-in's own file with PROTO): the declaration only fixes field types.
  void resolve_type(Scope& sc, Node& n, Span at) {
    const ProtoDef* p = find_proto(sc, n.type);
    n.fvrml = is_fvrml_node(n.type);
    if (p) {
      n.iface = &p->iface;
      if (!n.fvrml) n.proto = p;
      return;
    }
    n.iface = standard_interface(n.type);
    if (!n.iface)
      error(at, "unknown node type '" + n.type + "' (not a VRML97 or FVRML node, and no PROTO declares it)");
  }

  void node_body(Scope& sc, Node& n, int depth) {
    if (!expect(VTok::LBrace, ("'{' after '" + n.type + "'").c_str())) return;
    while (!at(VTok::RBrace) && !at(VTok::Eof)) {
      size_t p = pos_;
      if (at_id("ROUTE")) {
        route(sc, sc.proto ? nullptr : &out_.routes);
      } else if (at_id("PROTO")) {
        proto(sc);
      } else if (at_id("EXTERNPROTO")) {
        externproto(sc);
      } else if (n.type == "Script" && is_declaration_keyword()) {
        script_declaration(sc, n);
      } else if (at(VTok::Id)) {
        field(sc, n, depth);
      } else {
        error(cur().span, "expected a field name or '}', found " + describe(cur()));
        skip_one();
      }
      if (p == pos_) skip_one();
    }
    expect(VTok::RBrace, ("'}' to close '" + n.type + "'").c_str());
  }

  void script_declaration(Scope& sc, Node& n) {
    FieldDecl d;
    if (!declaration(sc, true, d)) return;
    if (find_field(n, d.name)) {  // one name, one type: an IS or a ROUTE could not tell which
      error(d.span,
            n.iface && n.iface->find(d.name) ? "'" + d.name + "' is a field of every Script: declare another name"
                                             : "'" + d.name + "' is declared twice in 'Script'");
      if (at_id("IS")) is_reference(sc, n, d.name, d.type, cur().span);
      return;
    }
    if (at_id("IS")) {
      FieldSlot slot;
      slot.name = d.name;
      slot.span = d.span;
      slot.is_ref = is_reference(sc, n, d.name, d.type, cur().span);
      d.has_default = false;
      n.fields.push_back(std::move(slot));
    }
    n.script_decls.push_back(std::move(d));
  }

  const FieldDecl* find_field(const Node& n, const std::string& name) const {
    if (n.iface)
      if (const FieldDecl* d = n.iface->find(name)) return d;
    for (const auto& d : n.script_decls)
      if (d.name == name) return &d;
    return nullptr;
  }

  void field(Scope& sc, Node& n, int depth) {
    const VToken& name = advance();
    const FieldDecl* decl = find_field(n, name.text);
    if (!decl) {
      if (n.iface) {
        std::vector<std::string> names;
        for (const auto& f : n.iface->fields) names.push_back(f.name);
        std::string near = support::nearest_name(name.text, names);
        error(name.span,
              "'" + n.type + "' has no field '" + name.text + "'" +
                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      }
      skip_value();
      return;
    }
    if (decl->access == Access::EventIn || decl->access == Access::EventOut) {
      if (!at_id("IS")) {
        error(name.span,
              "'" + name.text + "' of '" + n.type + "' is an " + access_name(decl->access) + " and takes no value");
        skip_value();
        return;
      }
    }
    FieldSlot slot;
    slot.name = name.text;
    slot.span = name.span;
    if (at_id("IS")) {
      slot.is_ref = is_reference(sc, n, name.text, decl->type, name.span);
    } else if (!value(sc, decl->type, slot.value, depth + 1, &n)) {
      // Skip the rest of the bad value, unless the next token already starts the next field.
      if (!at(VTok::RBrace) && !(at(VTok::Id) && find_field(n, cur().text))) skip_value();
      return;
    }
    for (auto& s : n.fields)
      if (s.name == slot.name) {
        error(name.span, "field '" + name.text + "' of '" + n.type + "' is given twice");
        return;
      }
    n.fields.push_back(std::move(slot));
  }

  // 'IS' id: only inside a PROTO body, naming an interface field of the same type.
  std::string is_reference(Scope& sc, Node&, const std::string& field, FieldType type, Span where) {
    advance();
    if (!at(VTok::Id)) {
      error(cur().span, "expected an interface name after IS, found " + describe(cur()));
      return "";
    }
    const VToken& ref = advance();
    if (!sc.proto) {
      error(where, "'IS' is only allowed inside a PROTO body");
      return "";
    }
    const FieldDecl* d = sc.proto->iface.find(ref.text);
    if (!d) error(ref.span, "the PROTO '" + sc.proto->iface.name + "' has no interface field '" + ref.text + "'");
    else if (d->type != type)
      error(ref.span, "'" + field + "' is " + type_name(type) + " but '" + ref.text + "' is " + type_name(d->type));
    return ref.text;
  }

  // ---- values ----
  bool value(Scope& sc, FieldType t, Value& v, int depth, const Node* owner = nullptr) {
    v.type = t;
    v.span = cur().span;
    bool ok;
    if (is_multi(t) && at(VTok::LBracket)) {
      advance();
      ok = true;
      while (ok && !at(VTok::RBracket) && !at(VTok::Eof)) ok = element(sc, single_of(t), v, depth, owner);
      ok = ok && expect(VTok::RBracket, "']' to close the list");
      if (!ok) skip_to_bracket();
    } else {
      ok = element(sc, single_of(t), v, depth, owner);
    }
    v.span.end = toks_[pos_ > 0 ? pos_ - 1 : 0].span.end;
    return ok;
  }

  void skip_to_bracket() {
    while (!at(VTok::RBracket) && !at(VTok::RBrace) && !at(VTok::Eof)) skip_one();
    if (at(VTok::RBracket)) advance();
  }

  // A number; with `integer`, one without a fraction or exponent from INT32_MIN to `most` (SFInt32:
  // INT32_MAX; an SFImage pixel: UINT32_MAX, 0xRRGGBBAA), so every integer field fits 32 bits.
  bool number(double& out, bool integer, double most = 2147483647.0) {
    if (!at(VTok::Number)) return false;
    const std::string& t = cur().text;
    char* end = nullptr;
    bool hex = t.find("0x") != std::string::npos || t.find("0X") != std::string::npos;
    out = hex ? static_cast<double>(std::strtoll(t.c_str(), &end, 16)) : std::strtod(t.c_str(), &end);
    if (integer && !hex && t.find_first_of(".eE") != std::string::npos) return false;
    if (integer && !(out >= -2147483648.0 && out <= most)) return false;
    advance();
    return true;
  }

  bool element(Scope& sc, FieldType t, Value& v, int depth, const Node* owner) {
    std::string what = std::string(type_name(t));
    auto fail = [&](const std::string& expected) {
      std::string field = owner ? " for a field of '" + owner->type + "'" : "";
      error(cur().span, "expected " + expected + " (" + what + ")" + field + ", found " + describe(cur()));
      return false;
    };
    switch (t) {
      case FieldType::SFBool:
        if (at_id("TRUE") || at_id("FALSE")) {
          v.nums.push_back(cur().text == "TRUE" ? 1 : 0);
          advance();
          return true;
        }
        return fail("TRUE or FALSE");
      case FieldType::SFString:
        if (!at(VTok::String)) return fail("a string in double quotes");
        v.strs.push_back(cur().text);
        v.str_spans.push_back({cur().span.begin + 1, cur().span.end > 0 ? cur().span.end - 1 : 0});
        advance();
        return true;
      case FieldType::SFNode: {
        if (at_id("NULL")) {
          advance();
          v.nodes.push_back(nullptr);
          return true;
        }
        if (!at(VTok::Id)) return fail("a node or NULL");
        NodePtr n = node(sc, depth);
        v.nodes.push_back(n);
        return true;
      }
      case FieldType::SFImage: return image(v, fail);
      default: break;
    }
    int k = numbers_per_element(t);
    bool integer = t == FieldType::SFInt32;
    for (int i = 0; i < k; ++i) {
      double d;
      if (!number(d, integer))
        return fail(k == 1 ? (integer ? "an integer from -2147483648 to 2147483647" : "a number")
                           : std::to_string(k) + " numbers");
      v.nums.push_back(d);
    }
    return true;
  }

  template <class Fail>
  bool image(Value& v, Fail fail) {
    double head[3];
    for (double& h : head)
      if (!number(h, true)) return fail("width, height and components of an image");
    if (head[0] < 0 || head[1] < 0 || head[2] < 0 || head[2] > 4 || head[0] * head[1] > 1e8)
      return fail("a valid image size");
    v.nums.assign(head, head + 3);
    for (double i = 0; i < head[0] * head[1]; ++i) {
      double px;
      if (!number(px, true, 4294967295.0)) return fail("one integer per pixel");
      v.nums.push_back(px);
    }
    return true;
  }

  // Skips one field value of unknown type: a bracketed list, a node, a word, or a run of atoms.
  void skip_value() {
    if (at(VTok::LBracket)) {
      int depth = 0;
      do {
        if (at(VTok::LBracket)) ++depth;
        if (at(VTok::RBracket)) --depth;
        skip_one();
      } while (depth > 0 && !at(VTok::Eof));
      return;
    }
    if (at_id("USE") || at_id("DEF")) skip_one(), skip_one();
    if (at(VTok::Id) && peek().kind == VTok::LBrace) {
      skip_one();
      int depth = 0;
      do {
        if (at(VTok::LBrace)) ++depth;
        if (at(VTok::RBrace)) --depth;
        skip_one();
      } while (depth > 0 && !at(VTok::Eof));
      return;
    }
    if (at(VTok::Id)) return skip_one();
    while (at(VTok::Number) || at(VTok::String)) skip_one();
  }

  // ---- routes ----
  // route -> 'ROUTE' id '.' id 'TO' id '.' id, both ends DEFed before, out -> in of equal type.
  void route(Scope& sc, std::vector<Route>* routes) {
    Span start = advance().span;
    Route r;
    r.span = start;
    auto end = [&](std::string& node, std::string& field) {
      if (!at(VTok::Id)) return false;
      node = advance().text;
      if (!at(VTok::Period)) return false;
      advance();
      if (!at(VTok::Id)) return false;
      field = advance().text;
      return true;
    };
    if (!end(r.from_node, r.from_field) || !at_id("TO") || (advance(), !end(r.to_node, r.to_field))) {
      error(cur().span, "expected 'ROUTE node.eventOut TO node.eventIn', found " + describe(cur()));
      return;
    }
    r.span.end = toks_[pos_ - 1].span.end;
    check_route(sc, r);
    if (routes) routes->push_back(r);
  }

  // The field of `n` that an event named `name` refers to, as an eventOut (or eventIn).
  const FieldDecl* event(const Node& n, const std::string& name, bool out) const {
    const FieldDecl* d = find_field(n, name);
    Access want = out ? Access::EventOut : Access::EventIn;
    if (d && (d->access == want || d->access == Access::ExposedField)) return d;
    std::string base = out
        ? (name.size() > 8 && name.substr(name.size() - 8) == "_changed" ? name.substr(0, name.size() - 8) : "")
        : (name.rfind("set_", 0) == 0 ? name.substr(4) : "");
    if (!base.empty())
      if (const FieldDecl* e = find_field(n, base); e && e->access == Access::ExposedField) return e;
    return nullptr;
  }

  void check_route(Scope& sc, const Route& r) {
    NodePtr from = find_def(sc, r.from_node), to = find_def(sc, r.to_node);
    if (!from) return error(r.span, "ROUTE from '" + r.from_node + "', which no DEF names");
    if (!to) return error(r.span, "ROUTE to '" + r.to_node + "', which no DEF names");
    if (!from->iface || !to->iface) return;  // unknown node types were reported already
    const FieldDecl* a = event(*from, r.from_field, true);
    const FieldDecl* b = event(*to, r.to_field, false);
    if (!a) return error(r.span, "'" + r.from_node + "' (" + from->type + ") has no eventOut '" + r.from_field + "'");
    if (!b) return error(r.span, "'" + r.to_node + "' (" + to->type + ") has no eventIn '" + r.to_field + "'");
    if (a->type != b->type)
      error(r.span,
            "ROUTE connects " + std::string(type_name(a->type)) + " '" + r.from_field + "' to " + type_name(b->type) +
                " '" + r.to_field + "'");
  }

  const frontend::SourceFile& f_;
  frontend::DiagnosticSink& d_;
  Scene& out_;
  std::vector<VToken> toks_;
  size_t pos_ = 0;
  bool fatal_ = false;
};

}  // namespace

bool parse_interfaces(const frontend::SourceFile& file, frontend::DiagnosticSink& diag, std::vector<Interface>& out) {
  Scene unused;
  return Parser(file, diag, unused).interfaces(out);
}

bool parse_scene(std::unique_ptr<frontend::SourceFile> file, frontend::DiagnosticSink& diag, Scene& out) {
  out.file = std::move(file);
  return Parser(*out.file, diag, out).run();
}

}  // namespace fscript::vrml
