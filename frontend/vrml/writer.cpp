// VRML97 writer and structural scene comparison.
#include "frontend/vrml/writer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_map>
#include <unordered_set>

#include "runtime/support/shortest.h"

namespace fscript::vrml {
namespace {

// The shortest text that reads back as the same double (as std::to_chars: meshes write millions).
std::string number(double v) {
  if (std::isinf(v)) return v > 0 ? "1e999" : "-1e999";
  char buf[400];
  return std::string(buf, support::shortest_text(buf, sizeof buf, v));
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

class Writer {
 public:
  explicit Writer(const Scene& s) : s_(s) {}

  std::string run() {
    out_ = "#VRML V2.0 utf8\n";
    for (auto [kind, i] : s_.order) {
      switch (kind) {
        case Scene::Kind::Proto: proto(*s_.protos[i]); break;
        case Scene::Kind::Node:
          node(s_.roots[i].get(), 0);
          out_ += "\n";
          break;
        case Scene::Kind::Route: route(s_.routes[i], 0); break;
      }
    }
    return out_;
  }

  std::string one(const Node& n, bool protos) {
    if (protos)
      for (const auto& p : s_.protos) proto(*p);
    node(&n, 0);
    return out_;
  }

 private:
  void indent(int d) { out_.append(static_cast<size_t>(d) * 2, ' '); }

  void proto(const ProtoDef& p) {
    out_ += (p.external ? "EXTERNPROTO " : "PROTO ") + p.iface.name + " [\n";
    for (const auto& f : p.iface.fields) declaration(f, 1, !p.external);
    out_ += "]";
    if (p.external) {
      out_ += " [";
      for (size_t k = 0; k < p.urls.size(); ++k) out_ += (k ? " " : "") + quoted(p.urls[k]);
      out_ += "]\n";
      return;
    }
    out_ += " {\n";
    std::unordered_set<const Node*> saved = written_;
    for (const auto& n : p.body) {
      indent(1);
      node(n.get(), 1);
      out_ += "\n";
    }
    for (const auto& r : p.routes) route(r, 1);
    written_ = saved;  // DEF names inside a PROTO body are local to it
    out_ += "}\n";
  }

  void declaration(const FieldDecl& f, int d, bool with_default) {
    indent(d);
    out_ += std::string(access_name(f.access)) + " " + type_name(f.type) + " " + f.name;
    if (with_default && f.has_default && (f.access == Access::Field || f.access == Access::ExposedField)) {
      out_ += " ";
      value(f.default_value, d + 1);
    }
    out_ += "\n";
  }

  void route(const Route& r, int d) {
    indent(d);
    out_ += "ROUTE " + r.from_node + "." + r.from_field + " TO " + r.to_node + "." + r.to_field + "\n";
  }

  void node(const Node* n, int d) {
    if (!n) {
      out_ += "NULL";
      return;
    }
    if (!n->def_name.empty() && written_.count(n)) {
      out_ += "USE " + n->def_name;
      return;
    }
    if (!n->def_name.empty()) {
      out_ += "DEF " + n->def_name + " ";
      written_.insert(n);
    }
    out_ += n->type + " {\n";
    for (const auto& decl : n->script_decls) {
      const FieldSlot* is = nullptr;
      for (const auto& f : n->fields)
        if (f.name == decl.name && !f.is_ref.empty()) is = &f;
      if (is) {
        indent(d + 1);
        out_ += std::string(access_name(decl.access)) + " " + type_name(decl.type) + " " + decl.name + " IS " +
            is->is_ref + "\n";
      } else {
        declaration(decl, d + 1, true);
      }
    }
    for (const auto& f : n->fields) {
      bool declared_in_script = false;
      for (const auto& decl : n->script_decls) declared_in_script |= decl.name == f.name;
      if (declared_in_script && !f.is_ref.empty()) continue;
      indent(d + 1);
      out_ += f.name + " ";
      if (!f.is_ref.empty()) out_ += "IS " + f.is_ref;
      else value(f.value, d + 1);
      out_ += "\n";
    }
    indent(d);
    out_ += "}";
  }

  void value(const Value& v, int d) {
    bool multi = is_multi(v.type);
    if (v.type == FieldType::SFNode || v.type == FieldType::MFNode) {
      if (multi) out_ += "[\n";
      for (const auto& n : v.nodes) {
        if (multi) indent(d + 1);
        node(n.get(), multi ? d + 1 : d);
        if (multi) out_ += "\n";
      }
      if (multi) {
        indent(d);
        out_ += "]";
      } else if (v.nodes.empty()) {
        out_ += "NULL";
      }
      return;
    }
    if (multi) out_ += "[";
    if (v.type == FieldType::SFString || v.type == FieldType::MFString) {
      for (size_t k = 0; k < v.strs.size(); ++k) out_ += (k ? ", " : "") + quoted(v.strs[k]);
    } else if (v.type == FieldType::SFBool) {
      out_ += v.nums.empty() || v.nums[0] == 0 ? "FALSE" : "TRUE";
    } else {
      int k = numbers_per_element(v.type);
      if (k == 0) k = 1;  // SFImage: all numbers in a row
      bool integer = v.type == FieldType::SFInt32 || v.type == FieldType::MFInt32 || v.type == FieldType::SFImage;
      for (size_t i = 0; i < v.nums.size(); ++i) {
        if (i) out_ += (i % k == 0 && multi) ? ", " : " ";
        out_ += integer ? std::to_string(static_cast<long long>(v.nums[i])) : number(v.nums[i]);
      }
    }
    if (multi) out_ += "]";
  }

  const Scene& s_;
  std::string out_;
  std::unordered_set<const Node*> written_;
};

// ---- comparison ----
class Comparer {
 public:
  std::string nodes(const Node* a, const Node* b, const std::string& where) {
    if (!a || !b) return (a == b) ? "" : where + ": NULL on one side only";
    auto it = map_.find(a);
    if (it != map_.end()) return it->second == b ? "" : where + ": sharing (DEF/USE) differs";
    map_[a] = b;
    if (a->type != b->type) return where + ": node type " + a->type + " vs " + b->type;
    if (a->def_name != b->def_name) return where + ": DEF name differs";
    if (a->fields.size() != b->fields.size()) return where + " (" + a->type + "): field count differs";
    // Field order is not part of the graph (a Script writes its declarations first).
    for (const FieldSlot& x : a->fields) {
      std::string w = where + "." + x.name;
      const FieldSlot* y = b->slot(x.name);
      if (!y || x.is_ref != y->is_ref) return w + ": field differs";
      if (std::string e = values(x.value, y->value, w); !e.empty()) return e;
    }
    if (a->script_decls.size() != b->script_decls.size()) return where + ": Script interface differs";
    return "";
  }

  std::string values(const Value& a, const Value& b, const std::string& w) {
    if (a.type != b.type || a.nums != b.nums || a.strs != b.strs || a.nodes.size() != b.nodes.size())
      return w + ": value differs";
    for (size_t k = 0; k < a.nodes.size(); ++k)
      if (std::string e = nodes(a.nodes[k].get(), b.nodes[k].get(), w + "[" + std::to_string(k) + "]"); !e.empty())
        return e;
    return "";
  }

 private:
  std::unordered_map<const Node*, const Node*> map_;
};

}  // namespace

std::string write_scene(const Scene& scene) { return Writer(scene).run(); }

std::string write_node(const Scene& scene, const Node& n, bool protos) { return Writer(scene).one(n, protos); }

std::string compare_scenes(const Scene& a, const Scene& b) {
  if (a.roots.size() != b.roots.size()) return "number of top-level nodes differs";
  if (a.protos.size() != b.protos.size()) return "number of PROTOs differs";
  if (a.routes.size() != b.routes.size()) return "number of ROUTEs differs";
  Comparer c;
  for (size_t i = 0; i < a.roots.size(); ++i)
    if (std::string e = c.nodes(a.roots[i].get(), b.roots[i].get(), "node " + std::to_string(i)); !e.empty()) return e;
  for (size_t i = 0; i < a.protos.size(); ++i) {
    const ProtoDef &x = *a.protos[i], &y = *b.protos[i];
    if (x.iface.name != y.iface.name || x.iface.fields.size() != y.iface.fields.size() ||
        x.body.size() != y.body.size())
      return "PROTO " + x.iface.name + " differs";
    for (size_t k = 0; k < x.iface.fields.size(); ++k) {
      const FieldDecl &f = x.iface.fields[k], &g = y.iface.fields[k];
      if (f.name != g.name || f.type != g.type || f.access != g.access)
        return "PROTO " + x.iface.name + " interface differs";
      if (std::string e = c.values(f.default_value, g.default_value, "PROTO " + x.iface.name + "." + f.name);
          !e.empty())
        return e;
    }
    for (size_t k = 0; k < x.body.size(); ++k)
      if (std::string e = c.nodes(x.body[k].get(), y.body[k].get(), "PROTO " + x.iface.name); !e.empty()) return e;
  }
  for (size_t i = 0; i < a.routes.size(); ++i) {
    const Route &x = a.routes[i], &y = b.routes[i];
    if (x.from_node != y.from_node || x.from_field != y.from_field || x.to_node != y.to_node ||
        x.to_field != y.to_field)
      return "ROUTE " + std::to_string(i) + " differs";
  }
  return "";
}

}  // namespace fscript::vrml
