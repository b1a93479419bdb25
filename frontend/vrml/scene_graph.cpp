// Scene graph helpers: field type tables, lookups with defaults, the built-in node interfaces.
#include "frontend/vrml/scene_graph.h"

#include <algorithm>

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
