// fscript.profile and textDocument/codeLens: until asked, one lens at the top that runs the
// profile; after, a lens on each script line with work (its share of its shape's evaluation time
// and operations, and of the points whose tape still runs it: engine/scene/shape_profile.h).
// Nothing is evaluated until the command runs, and an edit makes the lenses go until the next.
#include <cstdio>

#include "engine/scene/shape_profile.h"
#include "lsp/features/features.h"

namespace fscript::lsp {
namespace {

// Lines under this share of both time and operations get no lens.
constexpr double kLeast = 0.005;

json lens(uint32_t line, const std::string& title, const std::string& command, const json& arguments) {
  json c = {{"title", title}, {"command", command}};
  if (!arguments.is_null()) c["arguments"] = arguments;
  return {{"range", {{"start", {{"line", line}, {"character", 0}}}, {"end", {{"line", line}, {"character", 0}}}}},
          {"command", c}};
}

std::string percent(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100 * v);
  return buf;
}

}  // namespace

json run_profile(const Document& d, ProfileLenses& out) {
  vrml::Scene scene;
  scene::SceneModel model;
  if (!scene_model_of(d, scene, model))
    return {{"__error", kRequestFailed}, {"message", "the document has errors: fix them to profile it"}};
  scene::SceneProfile sp;
  backends::RuntimeError err;
  const vrml::Node* where = nullptr;
  if (!scene::profile_scene(scene, model, 1, true, sp, err, where))
    return {{"__error", kRequestFailed}, {"message", "the shape failed while it was meshed: " + err.message}};
  if (sp.shapes.empty())
    return {{"__error", kRequestFailed}, {"message", "no implicit shape to profile in this document"}};
  out.revision = d.revision;
  out.lenses = json::array();
  json shapes = json::array();
  for (const scene::ShapeProfile& r : sp.shapes) {
    shapes.push_back(scene::profile_json(r));
    if (r.path != scene.file->path()) continue;  // an Inline's shape: its lines are in another file
    for (const scene::LineCost& c : r.lines) {
      double time = r.ns > 0 ? c.ns / r.ns : 0, ops = r.ops > 0 ? c.ops / r.ops : 0;
      if (!c.line || (time < kLeast && ops < kLeast)) continue;
      std::string title = percent(time) + " of time · " + percent(ops) + " of operations · runs at " +
          percent(c.runs_at) + " of points";
      out.lenses.push_back(lens(c.line - 1, title, "", nullptr));
    }
  }
  return {{"shapes", shapes}};
}

json code_lenses(const Document& d, const ProfileLenses* last) {
  json all = json::array();
  bool current = last && last->revision == d.revision;
  all.push_back(
      lens(0, current ? "Profile evaluation again" : "Profile evaluation", "fscript.profile", json::array({d.uri})));
  if (current)
    for (const json& l : last->lenses) all.push_back(l);
  return all;
}

}  // namespace fscript::lsp
