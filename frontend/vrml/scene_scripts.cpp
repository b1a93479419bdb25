// Walks a scene graph (iteratively: deep files stay safe) and collects FVRML script fields.
#include "frontend/vrml/scene_scripts.h"

#include <functional>
#include <unordered_set>

namespace fscript::vrml {

void for_each_node(const Scene& scene, const std::function<void(const Node&)>& visit) {
  std::unordered_set<const Node*> seen;
  std::vector<const Node*> stack;
  for (const auto& r : scene.roots) stack.push_back(r.get());
  for (const auto& p : scene.protos)
    for (const auto& n : p->body) stack.push_back(n.get());
  while (!stack.empty()) {
    const Node* n = stack.back();
    stack.pop_back();
    if (!n || !seen.insert(n).second) continue;
    visit(*n);
    for (const auto& f : n->fields)
      for (const auto& child : f.value.nodes) stack.push_back(child.get());
    for (const auto& child : n->inlined) stack.push_back(child.get());  // an Inline's file
  }
}

std::vector<SceneScript> scene_scripts(const Scene& scene) {
  std::vector<SceneScript> out;
  for_each_node(scene, [&](const Node& n) {
    if (!n.fvrml) return;
    for (const auto& f : n.fields) {
      if (!f.is_ref.empty() || f.value.type != FieldType::SFString || f.value.strs.empty()) continue;
      if (!frontend::is_fscript_field(n.type, f.name)) continue;
      if (f.value.strs[0].find_first_not_of(" \t\r\n") == std::string::npos) continue;
      SceneScript s;
      s.node = &n;
      s.script.field = f.name;
      s.script.text = f.value.strs[0];
      frontend::LineCol lc = file_of(scene, n).position(f.value.str_spans[0].begin);
      s.script.line = lc.line;
      s.script.col = lc.col;
      out.push_back(std::move(s));
    }
  });
  return out;
}

}  // namespace fscript::vrml
