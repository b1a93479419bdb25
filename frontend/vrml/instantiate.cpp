// PROTO instantiation by copying the body with IS references resolved; DEF/USE sharing inside the
// body is kept (a USE in the copy points at the copy of its DEF).
#include "frontend/vrml/instantiate.h"

#include <unordered_map>

namespace fscript::vrml {
namespace {

class Copier {
 public:
  explicit Copier(const Node& instance) : inst_(instance) {}

  NodePtr copy(const NodePtr& n) {
    if (!n) return nullptr;
    auto it = done_.find(n.get());
    if (it != done_.end()) return it->second;
    auto c = std::make_shared<Node>(*n);
    done_[n.get()] = c;
    for (auto& f : c->fields) {
      if (!f.is_ref.empty()) {
        if (const Value* v = value(f.is_ref)) f.value = *v;
        f.is_ref.clear();
        continue;
      }
      for (auto& child : f.value.nodes) child = copy(child);
    }
    for (auto& d : c->script_decls)
      for (auto& child : d.default_value.nodes) child = copy(child);
    return c;
  }

 private:
  // The instance's value, else the default of the PROTO an EXTERNPROTO was read from.
  const Value* value(const std::string& field) const {
    if (const Value* v = inst_.get(field)) return v;
    if (const ProtoDef* d = inst_.proto ? inst_.proto->definition : nullptr)
      if (const FieldDecl* decl = d->iface.find(field); decl && decl->has_default) return &decl->default_value;
    return nullptr;
  }

  const Node& inst_;
  std::unordered_map<const Node*, NodePtr> done_;
};

}  // namespace

std::vector<NodePtr> instantiate(const Node& instance) {
  std::vector<NodePtr> out;
  if (!instance.proto) return out;
  const ProtoDef& p = instance.proto->definition ? *instance.proto->definition
                                                 : *instance.proto;  // an EXTERNPROTO not read has no body
  Copier c(instance);
  for (const auto& n : p.body) out.push_back(c.copy(n));
  return out;
}

}  // namespace fscript::vrml
