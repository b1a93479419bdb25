// fscript profile: the scene model built as fvrml-run builds it, every implicit shape outside an
// FTransform and every top-level FTransform meshed with a profiler, each profile reported.
#include "tools/fscript/profile.h"

#include <iostream>
#include <memory>

#include "engine/scene/shape_diagnostics.h"
#include "engine/scene/shape_profile.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/script_scene.h"
#include "tools/fscript/common.h"
#include "tools/profile_picture.h"

namespace fscript::cli {
namespace {

bool load(const std::string& path, vrml::Scene& scene, frontend::DiagnosticSink& diag) {
  std::string text, error;
  bool is_wrl = is_scene_path(path);
  if (is_wrl ? !vrml::read_scene_text(path, text, error) : !read_source(path, text)) {
    if (is_wrl) std::cerr << path << ":1:1: error: " << error << "\n";
    return false;
  }
  return vrml::scene_of_text(path, text, is_wrl, scene, diag);
}

void report(const vrml::Scene& scene, const vrml::Node& n, const backends::RuntimeError& err) {
  std::cerr << frontend::render(scene::runtime_diagnostic(scene, n, err, frontend::Severity::Error));
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
  mo.compile.budgets = a.budgets;
  mo.resolution_scale = a.resolution_scale;
  scene::SceneModel model;
  ok = scene::build_scene_model(scene, mo, diag, model);
  print_diagnostics(diag);
  if (!ok) return kExitInput;
  scene::SceneProfile sp;
  backends::RuntimeError err;
  const vrml::Node* where = nullptr;
  if (!scene::profile_scene(scene, model, static_cast<int>(a.threads), a.prune, sp, err, where))
    return report(scene, *where, err), kExitInput;
  if (sp.shapes.empty()) {
    std::cerr << a.file << ": error: no implicit shape to profile (parametric shapes are sampled on their grid, "
              << "with no pruning to show)\n";
    return kExitInput;
  }
  nlohmann::json all = nlohmann::json::array();
  for (size_t i = 0; i < sp.shapes.size(); ++i) {
    if (a.json) all.push_back(scene::profile_json(sp.shapes[i]));
    else std::cout << (i ? "\n" : "") << scene::profile_text(sp.shapes[i]);
    if (a.picture.empty()) continue;
    std::string path = a.picture, error;
    if (sp.shapes.size() > 1)
      path.insert(path.rfind('.') == std::string::npos ? path.size() : path.rfind('.'), "-" + std::to_string(i));
    if (!tools::write_profile_picture(*sp.profiles[i], path, error))
      return std::cerr << "error: " << error << "\n", kExitInput;
    if (!a.json)
      std::cout << "  cost picture: " << path << " (seen from +z; left: work per column, right: mean tape length)\n";
  }
  if (a.json) std::cout << all.dump(1) << "\n";
  return kExitOk;
}

}  // namespace fscript::cli
