// Scene graph helpers: field type tables, lookups with defaults, the built-in node interfaces.
#include "frontend/vrml/scene_graph.h"

#include <algorithm>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include "frontend/vrml/vrml_parser.h"

namespace fscript::vrml {

namespace {
struct TypeInfo {
  const char* name;
  int numbers;
  bool multi;
};
constexpr TypeInfo kTypes[] = {
#define FS_FIELD_TYPE(N, K, MF) {#N, K, MF},
#include "frontend/vrml/field_types.def"
};

const char kStandardNodes[] =
#include "nodes_vrml97.inc"
    ;

// The "##" lines before a node or field declaration of the table document it (the declarations
// themselves were read by parse_interfaces; this only pairs the comments with them).
void attach_docs(const std::string& text, std::unordered_map<std::string, Interface>& table) {
  std::string pending;
  Interface* node = nullptr;
  size_t at = 0;
  while (at < text.size()) {
    size_t nl = text.find('\n', at);
    std::string line = text.substr(at, nl == std::string::npos ? std::string::npos : nl - at);
    at = nl == std::string::npos ? text.size() : nl + 1;
    size_t b = line.find_first_not_of(' ');
    if (b == std::string::npos) continue;
    if (line.compare(b, 2, "##") == 0) {
      std::string part = line.substr(std::min(line.size(), b + 3));
      pending += pending.empty() ? part : " " + part;
      continue;
    }
    std::vector<std::string> words;
    for (size_t i = b; i < line.size();) {
      size_t e = std::min(line.find(' ', i), line.size());
      words.push_back(line.substr(i, e - i));
      i = line.find_first_not_of(' ', e);
      if (i == std::string::npos) break;
    }
    if (b == 0 && words.size() == 2 && words[1] == "[") {
      auto it = table.find(words[0]);
      node = it == table.end() ? nullptr : &it->second;
      if (node) node->doc = pending;
    } else if (node && b > 0 && words.size() >= 3) {
      for (auto& f : node->fields)
        if (f.name == words[2]) f.doc = pending;
    }
    pending.clear();
  }
}

const std::unordered_map<std::string, Interface>& standard_table() {
  static const auto table = [] {
    std::unordered_map<std::string, Interface> t;
    frontend::SourceFile f("nodes_vrml97.wrl", kStandardNodes);
    frontend::DiagnosticSink d;
    std::vector<Interface> list;
    if (!parse_interfaces(f, d, list)) {
      std::fputs(frontend::render_all(d).c_str(), stderr);
      std::abort();  // the built-in table is part of the program: a broken one is a bug
    }
    for (auto& i : list) t.emplace(i.name, std::move(i));
    attach_docs(kStandardNodes, t);
    return t;
  }();
  return table;
}
}  // namespace

const char* type_name(FieldType t) { return kTypes[static_cast<int>(t)].name; }
int numbers_per_element(FieldType t) { return kTypes[static_cast<int>(t)].numbers; }
bool is_multi(FieldType t) { return kTypes[static_cast<int>(t)].multi; }

bool type_from_name(const std::string& name, FieldType& out) {
  for (size_t i = 0; i < sizeof kTypes / sizeof kTypes[0]; ++i)
    if (name == kTypes[i].name) {
      out = static_cast<FieldType>(i);
      return true;
    }
  return false;
}

FieldType single_of(FieldType t) {
  if (!is_multi(t)) return t;
  std::string n = type_name(t);
  n[0] = 'S';
  FieldType s = t;
  type_from_name(n, s);
  return s;
}

const char* access_name(Access a) {
  switch (a) {
    case Access::Field: return "field";
    case Access::ExposedField: return "exposedField";
    case Access::EventIn: return "eventIn";
    case Access::EventOut: return "eventOut";
  }
  return "field";
}

size_t Value::elements() const {
  if (!is_multi(type)) return 1;
  if (type == FieldType::MFString) return strs.size();
  if (type == FieldType::MFNode) return nodes.size();
  int k = numbers_per_element(type);
  return k ? nums.size() / k : 0;
}

const FieldDecl* Interface::find(const std::string& field) const {
  for (const auto& f : fields)
    if (f.name == field) return &f;
  return nullptr;
}

const FieldSlot* Node::slot(const std::string& field) const {
  for (const auto& s : fields)
    if (s.name == field) return &s;
  return nullptr;
}

const Value* Node::get(const std::string& field) const {
  if (const FieldSlot* s = slot(field); s && s->is_ref.empty()) return &s->value;
  if (iface)
    if (const FieldDecl* d = iface->find(field); d && d->has_default) return &d->default_value;
  for (const auto& d : script_decls)
    if (d.name == field && d.has_default) return &d.default_value;
  return nullptr;
}

std::string declaration_text(const FieldDecl& f) {
  std::string out = std::string(access_name(f.access)) + " " + type_name(f.type) + " " + f.name;
  if (!f.has_default) return out;
  const Value& v = f.default_value;
  std::vector<std::string> items;
  if (f.type == FieldType::SFBool) {
    items.push_back(!v.nums.empty() && v.nums[0] != 0 ? "TRUE" : "FALSE");
  } else if (f.type == FieldType::SFNode) {
    items.push_back("NULL");
  } else if (f.type == FieldType::SFString || f.type == FieldType::MFString) {
    for (const auto& s : v.strs) items.push_back("\"" + s + "\"");
  } else {
    for (double d : v.nums) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9g", d);
      items.push_back(buf);
    }
  }
  std::string joined;
  for (const auto& s : items) joined += (joined.empty() ? "" : " ") + s;
  return out + " " + (is_multi(f.type) ? "[" + joined + "]" : joined);
}

const Interface* standard_interface(const std::string& node_type) {
  const auto& t = standard_table();
  auto it = t.find(node_type);
  return it == t.end() ? nullptr : &it->second;
}

std::vector<std::string> standard_node_types() {
  std::vector<std::string> out;
  for (const auto& [name, iface] : standard_table()) out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

bool is_fvrml_node(const std::string& n) {
  return n == "FGeometry" || n == "FMaterial" || n == "FTexture3D" || n == "FAppearance" || n == "FShape" ||
      n == "FTransform";
}

}  // namespace fscript::vrml
