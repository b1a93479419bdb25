// The steps every fvrml-run output shares: meshing a frame, merging, building the model, writing
// mesh files, and the picture's camera and lights from the scene.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>

#include "frontend/fscript/embedded.h"
#include "engine/mesh/field.h"
#include "engine/mesh/field_profile.h"
#include "engine/mesh/local_field.h"
#include "engine/mesh/mesh_io.h"
#include "engine/scene/shape_diagnostics.h"
#include "engine/scene/shape_mesh.h"
#include "engine/scene/shape_profile.h"
#include "engine/scene/standard_geometry.h"
#include "runtime/support/progress.h"
#include "tools/fvrml-run/memo.h"
#include "tools/profile_picture.h"
#include "tools/fvrml-run/run.h"

namespace fvrml_run {

// The lines --profile prints per shape (the stats' "profile" has every line).
constexpr size_t kProfileRows = 20;

double evaluation_ms_since(uint64_t ns0) { return (mesh::evaluation_ns().load() - ns0) / 1e6; }

void report(const Options& o, const vrml::Scene& scene, const vrml::Node* n, const fscript::backends::RuntimeError& err,
            const std::string& prefix) {
  static std::mutex lock;  // frames are meshed in parallel
  std::lock_guard<std::mutex> hold(lock);
  namespace fe = fscript::frontend;
  fe::Severity sev = o.keep_going ? fe::Severity::Warning : fe::Severity::Error;
  std::string path = n->file && n->file != scene.file.get() ? "" : o.path;  // (an Inline's own path)
  std::cerr << fe::render(fscript::scene::runtime_diagnostic(scene, *n, err, sev, prefix, path));
}

namespace {

// What mesh_scene meshes on its own: shapes outside any FTransform and top-level FTransforms, but
// not those in `skip` (animated ones, meshed frame by frame).
bool own_shape(const fscript::scene::Shape& s, const std::set<const vrml::Node*>& skip) {
  return s.group < 0 && !skip.count(s.fshape);
}
bool own_group(const fscript::scene::Group& g, const std::set<const vrml::Node*>& skip) {
  return g.parent < 0 && !skip.count(g.node);
}

}  // namespace

namespace {

// One shape or top-level FTransform, from the memo when it has it (then stored there when made).
template <class Make>
bool memo_mesh(const Options& o, const std::string& key, mesh::Mesh& m, Make make) {
  if (o.memo)
    if (auto hit = o.memo->find(key)) {
      fscript::support::ProgressJob done;  // the run's progress counts it as made
      m = std::move(*hit);
      return true;
    }
  if (!make()) return false;
  if (o.memo && !o.merging) o.memo->store(key, m);  // a merge's memo holds the parts' frames, for this run only
  return true;
}

}  // namespace

Meshed mesh_scene(const Options& o, const vrml::Scene& scene, const SceneModel& model, bool world, int threads,
                  const std::set<const vrml::Node*>& skip) {
  Meshed out;
  for (size_t i = 0; i < model.shapes.size(); ++i) {
    const auto& s = model.shapes[i];
    if (cancelled(o)) return out.failed = true, out;
    mesh::Mesh m;
    fscript::backends::RuntimeError err;
    bool mine = own_shape(s, skip);
    std::string key = mine && o.memo ? shape_key(o, scene, model, i, world) : "";
    if (mine && !memo_mesh(o, key, m, [&] {
          return fscript::scene::mesh_shape(s, m, err, world, threads, o.prune, o.mesher);
        })) {
      report(o, scene, s.fshape, err);
      out.failed = true;
    }
    out.counts.push_back({m.positions.size(), m.triangles.size()});
    if (mine) out.put(s.fshape, std::move(m));
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    if (!own_group(model.groups[g], skip)) continue;
    if (cancelled(o)) return out.failed = true, out;
    mesh::Mesh m;
    fscript::backends::RuntimeError err;
    std::string key = o.memo ? group_key(o, scene, model, g, world) : "";
    if (!memo_mesh(o, key, m, [&] {
          return fscript::scene::mesh_group(model, static_cast<int>(g), m, err, world, threads, o.prune, o.mesher);
        })) {
      report(o, scene, model.groups[g].node, err, "FTransform: ");
      out.failed = true;
    }
    out.group_counts[g] = {m.positions.size(), m.triangles.size()};
    out.put(model.groups[g].node, std::move(m));
  }
  return out;
}

uint32_t node_line(const vrml::Scene& scene, const vrml::Node& n) {
  return vrml::file_of(scene, n).position(n.span.begin).line;
}

uint64_t mesh_jobs(const SceneModel& model, const std::set<const vrml::Node*>& skip) {
  uint64_t n = 0;
  for (const auto& s : model.shapes) n += own_shape(s, skip);
  for (const auto& g : model.groups) n += own_group(g, skip);
  return n;
}

mesh::Mesh picture(Meshed& m, const vrml::Scene& scene) {
  mesh::Mesh all = merged(m);
  for (const auto& part : fscript::scene::standard_meshes(scene)) all.append(part);
  return all;
}

mesh::Mesh merged(Meshed& m) {
  if (m.by_node.size() == 1) return std::move(m.by_node.begin()->second);
  return m.all();
}

bool build(Loaded& l, SceneModel& model, const fscript::scene::ModelOptions& mo, bool print) {
  bool ok = fscript::scene::build_scene_model(l.scene, mo, l.diag, model);
  if (ok && l.from_script && !model.shapes.empty() && model.shapes[0].kind != fscript::scene::ShapeKind::Implicit) {
    std::cerr << l.scene.file->path() << ": error: fvrml-run FILE.fs takes an implicit script (function FRep, or "
              << "one expression); a parametric script needs its resolution and parameters in an FShape of a .wrl "
              << "(docs/scenes.md, \"Shapes\")\n";
    return false;
  }
  if (print || !ok) std::cerr << fscript::frontend::render_all(l.diag);
  l.diag.clear();
  return ok;
}

void report_shapes(const Options& o, const Loaded& l, const SceneModel& model, nlohmann::json& st) {
  auto t0 = Clock::now();
  // The statistics of meshing (evaluation time, local tapes) leave out the diagnostics' work.
  mesh::LocalTapeStats& tapes = mesh::local_tape_totals();
  const uint64_t eval_ns = mesh::evaluation_ns().load(), regions = tapes.regions.load(),
                 simplified = tapes.simplified.load(), tape_ops = tapes.tape_ops.load(),
                 full_ops = tapes.full_ops.load(), gradients = tapes.gradients.load();
  auto found = fscript::scene::diagnose_scene(l.scene, model);
  mesh::evaluation_ns() = eval_ns, tapes.regions = regions, tapes.simplified = simplified, tapes.tape_ops = tape_ops;
  tapes.full_ops = full_ops, tapes.gradients = gradients;
  if (!o.stats || o.print_shape_diagnostics)
    for (const auto& f : found) std::cerr << fscript::frontend::render(f.diag);
  if (!o.stats) return;
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : found) {
    nlohmann::json j = {{"issue", fscript::scene::issue_name(f.issue)},
                        {"severity", f.diag.severity == fscript::frontend::Severity::Note ? "note" : "warning"},
                        {"path", f.diag.path},
                        {"line", f.diag.pos.line},
                        {"col", f.diag.pos.col},
                        {"message", f.diag.message}};
    if (f.has_box) j["bboxCenter"] = f.center, j["bboxSize"] = f.size;
    if (f.resolution) j["resolution"] = f.resolution;
    if (f.fraction > 0) j["fraction"] = f.fraction;
    list.push_back(j);
  }
  st["shape_diagnostics"] = list;
  st["shape_diagnostics_ms"] = ms_since(t0);
}

bool report_profiles(const Options& o, const Loaded& l, nlohmann::json& st) {
  namespace sc = fscript::scene;
  const auto& all = o.mesher.profiler->profiles();
  nlohmann::json list = nlohmann::json::array();
  int index = 0;
  for (const auto& [key, p] : all) {
    sc::ShapeProfile r = sc::profile_report(l.scene, *static_cast<const vrml::Node*>(key), *p);
    std::cerr << sc::profile_text(r, kProfileRows);
    list.push_back(sc::profile_json(r));
    if (!o.profile_picture.empty()) {
      std::string path = all.size() == 1 ? o.profile_picture : numbered(o.profile_picture, index, int(all.size()));
      std::string error;
      if (!fscript::tools::write_profile_picture(*p, path, error))
        return std::cerr << "error: " << error << "\n", false;
      std::cerr << "  cost picture: " << path << " (seen from +z; left: work per column, right: mean tape length)\n";
    }
    ++index;
  }
  if (all.empty()) std::cerr << o.path << ": note: --profile: no implicit shape was meshed, nothing to profile\n";
  st["profile"] = list;
  return true;
}

std::string numbered(const std::string& path, int frame, int frames) {
  size_t dot = path.find_last_of('.');
  int digits = static_cast<int>(std::to_string(std::max(1, frames - 1)).size());
  char num[16];
  std::snprintf(num, sizeof num, "-%0*d", digits, frame);
  return dot == std::string::npos ? path + num : path.substr(0, dot) + num + path.substr(dot);
}

bool write_frame(const Options& o, const std::string& path, const mesh::Mesh& all) {
  std::string error;
  mesh::MeshFormat f = o.format == "ply" ? mesh::MeshFormat::Ply
      : o.format == "obj"                ? mesh::MeshFormat::Obj
      : o.format == "stl"                ? mesh::MeshFormat::Stl
                                         : mesh::MeshFormat::Glb;
  if (!mesh::write_mesh(all, f, path, error)) {
    std::cerr << "error: " << error << "\n";
    return false;
  }
  return true;
}

namespace {

void numbers(const vrml::Node& n, const char* field, double* out, int count) {
  const vrml::Value* v = n.get(field);
  for (int k = 0; v && k < count && k < static_cast<int>(v->nums.size()); ++k) out[k] = v->nums[k];
}

// DirectionalLights in the scene's grouping nodes, turned by the enclosing Transforms' rotations.
void lights(const vrml::Node* n, const fscript::scene::Mat4& m, std::vector<fscript::render::Light>& out, int depth) {
  if (!n || depth > 1000) return;
  if (n->type == "DirectionalLight") {
    double dir[3] = {0, 0, -1}, colour[3] = {1, 1, 1}, intensity = 1, ambient = 0, on = 1;
    numbers(*n, "direction", dir, 3), numbers(*n, "color", colour, 3), numbers(*n, "intensity", &intensity, 1);
    numbers(*n, "ambientIntensity", &ambient, 1), numbers(*n, "on", &on, 1);
    if (on == 0) return;
    fscript::render::Light l;
    for (int r = 0; r < 3; ++r) {
      l.direction[r] = static_cast<float>(m[r] * dir[0] + m[4 + r] * dir[1] + m[8 + r] * dir[2]);
      l.colour[r] = static_cast<float>(colour[r]);
    }
    l.intensity = static_cast<float>(intensity), l.ambient = static_cast<float>(ambient);
    out.push_back(l);
    return;
  }
  fscript::scene::Mat4 here = m;
  if (n->type == "Transform") here = fscript::scene::multiply(m, fscript::scene::transform_matrix(*n));
  if (n->type == "Transform" || n->type == "Group" || n->type == "Anchor" || n->type == "Collision")
    if (const vrml::Value* v = n->get("children"))
      for (const auto& c : v->nodes) lights(c.get(), here, out, depth + 1);
}

}  // namespace

fscript::render::RenderOptions render_options(const Options& o, const vrml::Scene& scene, uint32_t width,
                                              uint32_t height) {
  fscript::render::RenderOptions ro;
  ro.width = width, ro.height = height;
  ro.azimuth = o.azimuth, ro.elevation = o.elevation, ro.zoom = o.zoom, ro.view_given = o.view_given;
  ro.threads = static_cast<unsigned>(std::max(1, o.threads)), ro.prune = o.prune;
  for (const auto& n : scene.roots) {
    if (n && n->type == "Viewpoint" && !ro.camera) {  // VRML97 binds the first one
      fscript::render::Camera c;
      double p[3] = {0, 0, 10}, r[4] = {0, 0, 1, 0}, f = 0.785398;
      numbers(*n, "position", p, 3), numbers(*n, "orientation", r, 4), numbers(*n, "fieldOfView", &f, 1);
      for (int k = 0; k < 3; ++k) c.position[k] = p[k];
      for (int k = 0; k < 4; ++k) c.orientation[k] = r[k];
      if (f > 0 && f < 3.1) c.field_of_view = f;
      ro.camera = c;
    }
    if (n && n->type == "NavigationInfo") {
      double head = 1;
      numbers(*n, "headlight", &head, 1);
      ro.headlight = head != 0;
    }
    lights(n.get(), fscript::scene::identity(), ro.lights, 0);
  }
  if (auto sky = fscript::scene::background_colour(scene)) ro.background = *sky;
  return ro;
}

}  // namespace fvrml_run
