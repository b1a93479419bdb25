// The live preview's meshes from the last run, by what they are made from (memo.h).
#include "tools/fvrml-run/memo.h"

#include <cstdio>

#include "frontend/vrml/writer.h"

namespace fvrml_run {
namespace {

void add(std::string& out, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g ", v);
  out += buf;
}

void add(std::string& out, const fscript::scene::CompiledField& f) {
  out += f.field + ":";
  for (double v : {f.span0, f.span1, f.t}) add(out, v);
}

// Everything of a resolved shape that its mesh depends on besides its node's text.
std::string shape_numbers(const fscript::scene::Shape& s, bool world) {
  std::string out = "kind " + std::string(fscript::scene::kind_name(s.kind)) + "\n";
  for (double v : s.domain) add(out, v);
  for (int v : s.resolution) add(out, v);
  if (world)
    for (double v : s.transform) add(out, v);
  for (double v : {s.fraction, double(s.time.ever_active), double(s.time.active), s.time.fraction, s.time.cycle_time,
                   s.time.time_of_last_event, double(s.frames)})
    add(out, v);
  add(out, s.geometry);
  if (s.texture) add(out, *s.texture);
  if (s.colour) add(out, *s.colour);
  for (const auto& f : s.material) add(out, f);
  return out + "\n";
}

std::string options_text(const Options& o, bool world) {
  std::string out = "backend " + o.model.compile.backend + (o.prune ? " prune" : " no-prune") +
      (o.mesher.kind == mesh::Mesher::DualContouring ? " dc " : " mt ") + (world ? "world " : "local ");
  add(out, o.mesher.tolerance);
  return out + "\n";
}

}  // namespace

std::string shape_key(const Options& o, const vrml::Scene& scene, const SceneModel& model, size_t i, bool world) {
  const auto& s = model.shapes[i];
  return "shape\n" + options_text(o, world) + shape_numbers(s, world) + vrml::write_node(scene, *s.fshape, true);
}

std::string group_key(const Options& o, const vrml::Scene& scene, const SceneModel& model, size_t i, bool world) {
  const auto& g = model.groups[i];
  std::string out = "group\n" + options_text(o, world);
  for (size_t k = 0; k < model.groups.size(); ++k)
    if (fscript::scene::inside_group(model, static_cast<int>(k), static_cast<int>(i))) {
      const auto& inner = model.groups[k];
      add(out, inner.fraction);
      if (inner.op_kernel) add(out, *inner.op_kernel);
      for (const auto& [field, parts] : inner.affine)
        for (const auto& f : parts) add(out, f);
      out += "\n";
    }
  for (const auto& s : model.shapes)
    if (fscript::scene::inside_group(model, s.group, static_cast<int>(i))) out += shape_numbers(s, world);
  return out + vrml::write_node(scene, *g.node, true);
}

template <class T>
std::optional<T> MeshMemo::take(std::map<std::string, Entry<T>>& entries, const std::string& key) {
  std::lock_guard<std::mutex> hold(lock_);
  auto it = entries.find(key);
  if (it == entries.end()) return std::nullopt;
  it->second.used = true;
  ++counts_.reused;
  return it->second.mesh;
}

template <class T>
void MeshMemo::keep(std::map<std::string, Entry<T>>& entries, const std::string& key, const T& m) {
  std::lock_guard<std::mutex> hold(lock_);
  entries[key] = {m, true};
  ++counts_.made;
}

std::optional<mesh::Mesh> MeshMemo::find(const std::string& key) { return take(meshes_, key); }
void MeshMemo::store(const std::string& key, const mesh::Mesh& m) { keep(meshes_, key, m); }
std::optional<mesh::CompactMesh> MeshMemo::find_frame(const std::string& key) { return take(frames_, key); }
void MeshMemo::store_frame(const std::string& key, const mesh::CompactMesh& m) { keep(frames_, key, m); }

void MeshMemo::sweep() {
  std::lock_guard<std::mutex> hold(lock_);
  auto drop = [](auto& entries) {
    for (auto it = entries.begin(); it != entries.end();) {
      if (!it->second.used) it = entries.erase(it);
      else it->second.used = false, ++it;
    }
  };
  drop(meshes_), drop(frames_);
}

MeshMemo::Counts MeshMemo::counts() {
  std::lock_guard<std::mutex> hold(lock_);
  return counts_;
}

void MeshMemo::reset_counts() {
  std::lock_guard<std::mutex> hold(lock_);
  counts_ = {};
}

}  // namespace fvrml_run
