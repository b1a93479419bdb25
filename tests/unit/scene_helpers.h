#pragma once
// A .wrl text parsed and resolved into its scene model, for the scene-level unit tests.
#include <memory>
#include <string>

#include "frontend/vrml/vrml_parser.h"
#include "engine/scene/scene_model.h"

namespace fscript::test {

struct LoadedScene {
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  scene::SceneModel model;
  bool ok = false;  // parsed and resolved without an error (diag says what went wrong)
};

inline std::unique_ptr<LoadedScene> load_scene(const std::string& path, const std::string& text,
                                               const scene::ModelOptions& opts = {}) {
  auto l = std::make_unique<LoadedScene>();
  l->ok = vrml::parse_scene(std::make_unique<frontend::SourceFile>(path, text), l->diag, l->scene) &&
      scene::build_scene_model(l->scene, opts, l->diag, l->model);
  return l;
}

}  // namespace fscript::test
