// VRML97 export by copying the scene graph with replacements, then the ordinary writer.
#include "runtime/scene/vrml_export.h"

#include <cstdlib>
#include <unordered_map>
#include <unordered_set>

#include "frontend/fscript/formatter.h"
#include "frontend/vrml/writer.h"

namespace fscript::scene {
namespace {

using vrml::FieldType;
using vrml::Node;
using vrml::NodePtr;
using vrml::Value;

NodePtr make(const std::string& type) {
  auto n = std::make_shared<Node>();
  n->type = type;
  n->iface = vrml::standard_interface(type);
  return n;
}

void set(Node& n, const std::string& field, Value v) {
  vrml::FieldSlot s;
  s.name = field;
  s.value = std::move(v);
  n.fields.push_back(std::move(s));
}

Value numbers(FieldType t, std::vector<double> nums) {
  Value v;
  v.type = t;
  v.nums = std::move(nums);
  return v;
}

Value node_value(NodePtr n) {
  Value v;
  v.type = FieldType::SFNode;
  v.nodes = {std::move(n)};
  return v;
}

// Each float as the double of its shortest decimal text, so the file stays short and reads
// back as the same float.
Value vec3s(const std::vector<mesh::Vec3>& p, FieldType t) {
  std::vector<double> nums;
  for (const auto& v : p)
    for (float c : v) nums.push_back(std::strtod(frontend::shortest_float(c).c_str(), nullptr));
  return numbers(t, nums);
}

// A Shape for the mesh: faces (or lines for curves), colours per vertex, normals per vertex.
NodePtr shape_node(const mesh::Mesh& m, const std::string& def_name) {
  NodePtr shape = make("Shape");
  shape->def_name = def_name;
  NodePtr app = make("Appearance");
  NodePtr mat = make("Material");
  set(*mat, "diffuseColor", numbers(FieldType::SFColor, {0.8, 0.8, 0.8}));
  set(*app, "material", node_value(mat));
  set(*shape, "appearance", node_value(app));
  bool lines = m.triangles.empty() && !m.polylines.empty();
  NodePtr geo = make(lines ? "IndexedLineSet" : "IndexedFaceSet");
  NodePtr coord = make("Coordinate");
  set(*coord, "point", vec3s(m.positions, FieldType::MFVec3f));
  set(*geo, "coord", node_value(coord));
  std::vector<double> index;
  if (lines) {
    for (const auto& l : m.polylines) {
      for (uint32_t i : l) index.push_back(i);
      index.push_back(-1);
    }
  } else {
    for (const auto& t : m.triangles) index.insert(index.end(), {double(t[0]), double(t[1]), double(t[2]), -1});
  }
  set(*geo, "coordIndex", numbers(FieldType::MFInt32, index));
  if (m.colours.size() == m.positions.size() && !m.positions.empty()) {
    NodePtr col = make("Color");
    set(*col, "color", vec3s(m.colours, FieldType::MFColor));
    set(*geo, "color", node_value(col));
  }
  if (!lines && m.normals.size() == m.positions.size() && !m.positions.empty()) {
    NodePtr nor = make("Normal");
    set(*nor, "vector", vec3s(m.normals, FieldType::MFVec3f));
    set(*geo, "normal", node_value(nor));
    set(*geo, "solid", numbers(FieldType::SFBool, {0}));
  }
  set(*shape, "geometry", node_value(geo));
  return shape;
}

class Exporter {
 public:
  explicit Exporter(const std::map<const Node*, mesh::Mesh>& meshes) : meshes_(meshes) {}

  NodePtr copy(const NodePtr& n) {
    if (!n) return nullptr;
    auto it = done_.find(n.get());
    if (it != done_.end()) return it->second;
    NodePtr c;
    if (auto m = meshes_.find(n.get()); m != meshes_.end()) {
      c = shape_node(m->second, n->def_name);
      if (!n->def_name.empty()) replaced_names_.insert(n->def_name);
    } else if (n->fvrml) {
      c = make("Group");  // an FVRML node that made no mesh (an FShape inside a replaced FTransform)
      c->def_name = n->def_name;
      if (!n->def_name.empty()) replaced_names_.insert(n->def_name);
    } else {
      c = std::make_shared<Node>(*n);
      for (auto& f : c->fields)
        for (auto& child : f.value.nodes) child = copy(child);
    }
    done_[n.get()] = c;
    return c;
  }

  bool replaced(const std::string& def_name) const { return replaced_names_.count(def_name) != 0; }

 private:
  const std::map<const Node*, mesh::Mesh>& meshes_;
  std::unordered_map<const Node*, NodePtr> done_;
  std::unordered_set<std::string> replaced_names_;
};

}  // namespace

std::string export_vrml(const vrml::Scene& in, const std::map<const Node*, mesh::Mesh>& meshes) {
  vrml::Scene out;
  Exporter ex(meshes);
  for (auto [kind, i] : in.order) {
    switch (kind) {
      case vrml::Scene::Kind::Proto:
        if (vrml::is_fvrml_node(in.protos[i]->iface.name)) continue;  // the FVRML PROTOs are gone
        out.protos.push_back(std::make_unique<vrml::ProtoDef>(*in.protos[i]));
        out.order.push_back({kind, out.protos.size() - 1});
        break;
      case vrml::Scene::Kind::Node:
        out.roots.push_back(ex.copy(in.roots[i]));
        out.order.push_back({kind, out.roots.size() - 1});
        break;
      case vrml::Scene::Kind::Route: break;  // after the nodes, once replacements are known
    }
  }
  for (auto [kind, i] : in.order) {
    if (kind != vrml::Scene::Kind::Route) continue;
    const vrml::Route& r = in.routes[i];
    if (ex.replaced(r.from_node) || ex.replaced(r.to_node)) continue;
    out.routes.push_back(r);
    out.order.push_back({kind, out.routes.size() - 1});
  }
  return vrml::write_scene(out);
}

}  // namespace fscript::scene
