// fscript profile: the scene model built as fvrml-run builds it, every implicit shape outside an
// FTransform and every top-level FTransform meshed with a profiler, each profile reported.
#include "tools/fscript/profile.h"

#include <iostream>
#include <memory>

#include "engine/mesh/field_profile.h"
#include "engine/scene/shape_field.h"
#include "engine/scene/shape_mesh.h"
#include "engine/scene/shape_profile.h"
#include "frontend/vrml/inline.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/script_scene.h"
#include "frontend/vrml/vrml_parser.h"
#include "tools/fscript/common.h"

namespace fscript::cli {
namespace {

bool load(const std::string& path, vrml::Scene& scene, frontend::DiagnosticSink& diag) {
  std::string text, error;
  bool is_wrl = is_scene_path(path);
  if (is_wrl ? !vrml::read_scene_text(path, text, error) : !read_source(path, text)) {
    if (is_wrl) std::cerr << path << ":1:1: error: " << error << "\n";
    return false;
  }
  return is_wrl ? vrml::parse_scene(std::make_unique<frontend::SourceFile>(path, text), diag, scene) &&
          vrml::load_inlines(scene, diag)
                : vrml::script_scene(path, text, scene, diag);
}

// A runtime error of the shape at `n`: at the script's line where the error knows it.
void report(const vrml::Scene& scene, const vrml::Node& n, const backends::RuntimeError& err) {
  const frontend::SourceFile& file = vrml::file_of(scene, n);
  frontend::LineCol at = err.line ? frontend::LineCol{err.line, std::max(err.col, 1u)} : file.position(n.span.begin);
  std::cerr << frontend::render(
      frontend::located(frontend::Severity::Error, file.path(), at, file.line_at(at.line), err.message));
}

}  // namespace

int cmd_profile(const ProfileArgs& a) {
  vrml::Scene scene;
  frontend::DiagnosticSink diag;
  bool ok = load(a.file, scene, diag);
  print_diagnostics(diag);
  if (!ok) return kExitInput;
  diag.clear();
  scene::ModelOptions mo;
  mo.compile.backend = a.backend;
  mo.resolution_scale = a.resolution_scale;
  scene::SceneModel model;
  ok = scene::build_scene_model(scene, mo, diag, model);
  print_diagnostics(diag);
  if (!ok) return kExitInput;
  mesh::Profiler profiler;
  mesh::MesherOptions mesher;
  mesher.profiler = &profiler;
  const int threads = static_cast<int>(a.threads);
  for (const scene::Shape& s : model.shapes) {
    if (s.group >= 0 || s.kind != scene::ShapeKind::Implicit) continue;
    mesh::Mesh m;
    backends::RuntimeError err;
    if (!scene::mesh_shape(s, m, err, true, threads, a.prune, mesher)) return report(scene, *s.fshape, err), kExitInput;
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    if (model.groups[g].parent >= 0 || scene::parametric_group(model, static_cast<int>(g))) continue;
    mesh::Mesh m;
    backends::RuntimeError err;
    if (!scene::mesh_group(model, static_cast<int>(g), m, err, true, threads, a.prune, mesher))
      return report(scene, *model.groups[g].node, err), kExitInput;
  }
  if (profiler.profiles().empty()) {
    std::cerr << a.file << ": error: no implicit shape to profile (parametric shapes are sampled on their grid, "
              << "with no pruning to show)\n";
    return kExitInput;
  }
  nlohmann::json all = nlohmann::json::array();
  size_t index = 0, count = profiler.profiles().size();
  for (const auto& [key, p] : profiler.profiles()) {
    scene::ShapeProfile r = scene::profile_report(scene, *static_cast<const vrml::Node*>(key), *p);
    if (a.json) all.push_back(scene::profile_json(r));
    else std::cout << scene::profile_text(r) << (index + 1 < count ? "\n" : "");
    if (!a.picture.empty()) {
      std::string path = a.picture, error;
      if (count > 1)
        path.insert(path.rfind('.') == std::string::npos ? path.size() : path.rfind('.'), "-" + std::to_string(index));
      if (!scene::write_profile_picture(*p, path, error)) return std::cerr << "error: " << error << "\n", kExitInput;
      if (!a.json)
        std::cout << "  cost picture: " << path << " (seen from +z; left: work per column, right: mean tape length)\n";
    }
    ++index;
  }
  if (a.json) std::cout << all.dump(1) << "\n";
  return kExitOk;
}

}  // namespace fscript::cli
