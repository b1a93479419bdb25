// VRML97 export by copying the scene graph with replacements, then the ordinary writer.
#include "engine/scene/vrml_export.h"

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "frontend/vrml/inline.h"
#include "frontend/vrml/writer.h"
#include "runtime/support/shortest.h"

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

double tidy(float v) {
  char buf[64];
  *support::shortest_text(buf, sizeof buf - 1, v) = '\0';
  return std::strtod(buf, nullptr);
}

// Each float as the double of its shortest decimal text, so the file stays short and reads
// back as the same float.
Value vec3s(const std::vector<mesh::Vec3>& p, FieldType t) {
  std::vector<double> nums;
  nums.reserve(3 * p.size());
  for (const auto& v : p)
    for (float c : v) nums.push_back(tidy(c));
  return numbers(t, nums);
}

NodePtr material_node(const mesh::Material& v) {
  NodePtr mat = make("Material");
  auto colour = [](const mesh::Vec3& c) { return numbers(FieldType::SFColor, {tidy(c[0]), tidy(c[1]), tidy(c[2])}); };
  set(*mat, "diffuseColor", colour(v.diffuse));
  set(*mat, "ambientIntensity", numbers(FieldType::SFFloat, {tidy(v.ambient_intensity)}));
  set(*mat, "emissiveColor", colour(v.emissive));
  set(*mat, "specularColor", colour(v.specular));
  set(*mat, "shininess", numbers(FieldType::SFFloat, {tidy(v.shininess)}));
  set(*mat, "transparency", numbers(FieldType::SFFloat, {tidy(v.transparency)}));
  return mat;
}

// A Shape for the mesh: faces (or lines for curves), colours per vertex, normals per vertex.
NodePtr shape_node(const mesh::Mesh& m, const std::string& def_name) {
  NodePtr shape = make("Shape");
  shape->def_name = def_name;
  NodePtr app = make("Appearance");
  set(*app, "material", node_value(material_node(m.material.value_or(mesh::Material{}))));
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
  } else if (!lines) {  // no normals (dual contouring): the browser smooths all but the sharp edges
    set(*geo, "creaseAngle", numbers(FieldType::SFFloat, {mesh::kCreaseAngle}));
  }
  set(*shape, "geometry", node_value(geo));
  return shape;
}

Value strings(std::vector<std::string> strs) {
  Value v;
  v.type = FieldType::MFString;
  v.strs = std::move(strs);
  v.str_spans.resize(v.strs.size());
  return v;
}

vrml::FieldDecl decl(const std::string& name, FieldType type, vrml::Access access, std::optional<Value> value = {}) {
  vrml::FieldDecl d;
  d.name = name, d.type = type, d.access = access;
  if (value) d.has_default = true, d.default_value = std::move(*value);
  return d;
}

// The Script that turns a fraction into a frame: JavaScript for most browsers, CastleScript for
// view3dscene (a browser uses the first url it can run, VRML97 6.40).
NodePtr frame_script(int frames) {
  NodePtr script = make("Script");
  script->script_decls.push_back(decl("set_fraction", FieldType::SFFloat, vrml::Access::EventIn));
  script->script_decls.push_back(decl("frame_changed", FieldType::SFInt32, vrml::Access::EventOut));
  script->script_decls.push_back(
      decl("frames", FieldType::SFInt32, vrml::Access::Field, numbers(FieldType::SFInt32, {double(frames)})));
  set(*script, "url",
      strings({"javascript:\n"
               "function set_fraction(f, t) {\n"
               "  var i = Math.floor(f * frames);\n"
               "  frame_changed = i < 0 ? 0 : (i >= frames ? frames - 1 : i);\n"
               "}",
               "castlescript:\n"
               "function set_fraction(f, t)\n"
               "  frame_changed := max(0, min(frames - 1, floor(f * frames)))"}));
  return script;
}

// A relative URL of a file read beside the scene (in `from`), as seen from the output's folder
// `to`: an Inline's "parts/axes.wrl" stays the same file when the output is written elsewhere.
// Remote URLs, "file:" and absolute ones, and "#viewpoint" alone are left as they are.
std::string rebased(const std::string& url, const std::filesystem::path& from, const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  if (url.empty() || url[0] == '#' || url[0] == '/' || vrml::is_remote_url(url) || url.rfind("file:", 0) == 0)
    return url;
  size_t hash = url.find('#');
  std::string path = url.substr(0, hash), fragment = hash == std::string::npos ? "" : url.substr(hash);
  std::error_code ec;
  fs::path target = fs::weakly_canonical(fs::absolute(from / path, ec), ec);
  fs::path here = ec ? fs::path() : fs::weakly_canonical(fs::absolute(to, ec), ec);
  if (ec || target.empty() || here.empty()) return url;
  fs::path rel = target.lexically_relative(here);
  return rel.empty() ? url : rel.generic_string() + fragment;
}

class Exporter {
 public:
  Exporter(const vrml::Scene& in, const std::map<const Node*, mesh::Mesh>& meshes,
           const std::map<const Node*, Animation>& animations)
      : in_(in), meshes_(meshes), animations_(animations) {}

  std::optional<std::filesystem::path> output_dir;  // set: relative URLs are rebased onto it
  std::string rebase(const std::string& url, const Node* n) const {
    if (!output_dir) return url;
    const frontend::SourceFile& file = n && n->file ? *n->file : *in_.file;
    return rebased(url, std::filesystem::path(file.path()).parent_path(), *output_dir);
  }

  std::vector<vrml::Route> routes;  // those of the animations

  NodePtr copy(const NodePtr& n) {
    if (!n) return nullptr;
    auto it = done_.find(n.get());
    if (it != done_.end()) return it->second;
    NodePtr c;
    if (auto a = animations_.find(n.get()); a != animations_.end()) {
      c = animated(a->second, n->def_name);
      if (!n->def_name.empty()) replaced_names_.insert(n->def_name);
    } else if (auto m = meshes_.find(n.get()); m != meshes_.end()) {
      c = shape_node(m->second, n->def_name);
      if (!n->def_name.empty()) replaced_names_.insert(n->def_name);
    } else if (n->fvrml) {
      c = make("Group");  // an FVRML node that made no mesh (an FShape inside a replaced FTransform)
      c->def_name = n->def_name;
      if (!n->def_name.empty()) replaced_names_.insert(n->def_name);
    } else {
      c = std::make_shared<Node>(*n);
      for (auto& f : c->fields) {
        for (auto& child : f.value.nodes) child = copy(child);
        if (f.name == "url")  // Inline, ImageTexture, Anchor...: the same files from the output's folder
          for (auto& u : f.value.strs) u = rebase(u, n.get());
      }
    }
    done_[n.get()] = c;
    return c;
  }

  bool replaced(const std::string& def_name) const { return replaced_names_.count(def_name) != 0; }
  // A ROUTE into an animated node's set_fraction now reaches its Script, which has its name.
  bool kept(const vrml::Route& r) const {
    return r.to_field == "set_fraction" && scripts_.count(r.to_node) && !replaced(r.from_node);
  }

 private:
  // Group { Switch { frames } TimeSensor Script } and the ROUTEs between them.
  NodePtr animated(const Animation& a, const std::string& def_name) {
    std::string base = def_name.empty() ? fresh("FVRML") : def_name;
    NodePtr sw = make("Switch");
    sw->def_name = fresh(base + "_frames");
    set(*sw, "whichChoice", numbers(FieldType::SFInt32, {double(a.initial)}));
    Value choice;
    choice.type = FieldType::MFNode;
    for (size_t i = 0; i < a.frames->size(); ++i) {
      mesh::Mesh m;
      choice.nodes.push_back(a.frames->peek(i, m) ? shape_node(m, "") : make("Group"));
    }
    set(*sw, "choice", choice);
    NodePtr script = frame_script(static_cast<int>(a.frames->size()));
    script->def_name = def_name.empty() ? fresh(base + "_player") : def_name;
    scripts_.insert(script->def_name);
    NodePtr group = make("Group");
    Value children;
    children.type = FieldType::MFNode;
    children.nodes = {sw, script};
    if (!a.external) {
      NodePtr clock = make("TimeSensor");
      clock->def_name = fresh(base + "_clock");
      set(*clock, "startTime", numbers(FieldType::SFTime, {a.timing.start_time}));
      set(*clock, "stopTime", numbers(FieldType::SFTime, {a.timing.stop_time}));
      set(*clock, "cycleInterval", numbers(FieldType::SFTime, {a.timing.cycle_interval}));
      set(*clock, "loop", numbers(FieldType::SFBool, {a.timing.loop ? 1.0 : 0.0}));
      set(*clock, "enabled", numbers(FieldType::SFBool, {a.timing.enabled ? 1.0 : 0.0}));
      children.nodes.push_back(clock);
      routes.push_back({clock->def_name, "fraction_changed", script->def_name, "set_fraction", {}});
    }
    routes.push_back({script->def_name, "frame_changed", sw->def_name, "set_whichChoice", {}});
    set(*group, "children", children);
    return group;
  }

  // A DEF name used nowhere in the input or the output so far.
  std::string fresh(const std::string& want) {
    std::string name = want;
    for (int k = 2; in_.defs.count(name) || used_.count(name); ++k) name = want + "_" + std::to_string(k);
    used_.insert(name);
    return name;
  }

  const vrml::Scene& in_;
  const std::map<const Node*, mesh::Mesh>& meshes_;
  const std::map<const Node*, Animation>& animations_;
  std::unordered_set<std::string> used_, scripts_;
  std::unordered_map<const Node*, NodePtr> done_;
  std::unordered_set<std::string> replaced_names_;
};

}  // namespace

std::string export_vrml(const vrml::Scene& in, const std::map<const Node*, mesh::Mesh>& meshes,
                        const std::map<const Node*, Animation>& animations, const std::string& output_path) {
  vrml::Scene out;
  Exporter ex(in, meshes, animations);
  if (!output_path.empty() && output_path != "-")
    ex.output_dir = std::filesystem::path(output_path).parent_path().empty()
        ? std::filesystem::path(".")
        : std::filesystem::path(output_path).parent_path();
  for (auto [kind, i] : in.order) {
    switch (kind) {
      case vrml::Scene::Kind::Proto:
        if (vrml::is_fvrml_node(in.protos[i]->iface.name)) continue;  // the FVRML PROTOs are gone
        out.protos.push_back(std::make_unique<vrml::ProtoDef>(*in.protos[i]));
        for (auto& u : out.protos.back()->urls) u = ex.rebase(u, nullptr);  // an EXTERNPROTO's file
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
    if ((ex.replaced(r.from_node) || ex.replaced(r.to_node)) && !ex.kept(r)) continue;
    out.routes.push_back(r);
    out.order.push_back({kind, out.routes.size() - 1});
  }
  for (const auto& r : ex.routes) {
    out.routes.push_back(r);
    out.order.push_back({vrml::Scene::Kind::Route, out.routes.size() - 1});
  }
  return vrml::write_scene(out);
}

}  // namespace fscript::scene
