// textDocument/publishDiagnostics: the same diagnostics as `fscript check`, for .fs and .wrl,
// the shape diagnostics with the edits of their quick fixes.
#include "engine/scene/shape_diagnostics.h"
#include "frontend/check.h"
#include "frontend/vrml/script_scene.h"
#include "lsp/analysis.h"
#include "lsp/features/features.h"
#include "lsp/preview.h"

namespace fscript::lsp {
namespace {

// An edit setting `field` of node n to `value`: its value replaced where the file writes it, else
// the field added after the definition.
json set_field(const std::string& text, const vrml::Node& n, const std::string& field, const std::string& value) {
  if (const vrml::FieldSlot* s = n.slot(field); s && s->is_ref.empty())
    return {{"range", range_of_span(text, s->value.span.begin, s->value.span.end)}, {"newText", value}};
  const vrml::FieldSlot* def = n.slot("definition");
  uint32_t at = def ? def->value.span.end : n.span.end;
  return {{"range", range_of_span(text, at, at)}, {"newText", "\n" + field + " " + value}};
}

// The quick fix of a finding, as the diagnostic's data (code_actions reads it back): the box that
// holds the shape, or the resolution that shows it.
json fix_of(const std::string& text, const vrml::Scene& scene, const scene::ShapeFinding& f) {
  if (!f.node || vrml::file_of(scene, *f.node).path() != scene.file->path() || !f.node->slot("definition"))
    return nullptr;
  if (f.has_box) {
    json edits = json::array({set_field(text, *f.node, "bboxSize", scene::field_numbers(f.size))});
    const vrml::Value* c = f.node->get("bboxCenter");
    bool moved = false;
    for (size_t a = 0; a < 3; ++a) moved |= std::abs((c && a < c->nums.size() ? c->nums[a] : 0) - f.center[a]) > 1e-9;
    if (moved) edits.push_back(set_field(text, *f.node, "bboxCenter", scene::field_numbers(f.center)));
    return {
        {"title",
         "Set the box to " + scene::field_numbers(f.size) + (moved ? " around " + scene::field_numbers(f.center) : "")},
        {"edits", edits}};
  }
  if (f.resolution > 0) {
    std::string r = "[" + std::to_string(f.resolution) + "]";
    return {{"title", "Set resolution to " + r}, {"edits", json::array({set_field(text, *f.node, "resolution", r)})}};
  }
  return nullptr;
}

// The shape diagnostics of the document's implicit shapes (none while it has errors).
void shape_diagnostics(const Document& d, json& list) {
  vrml::Scene scene;
  scene::SceneModel model;
  if (!scene_model_of(d, scene, model)) return;
  for (const auto& f : scene::diagnose_scene(scene, model)) {
    if (f.diag.path != scene.file->path()) continue;  // in an Inline's file
    json diag = {{"range", range_of(d.text, f.diag.pos.line, f.diag.pos.col, f.diag.length)},
                 {"severity", f.diag.severity == frontend::Severity::Warning ? 2 : 4},  // a note: a hint
                 {"source", "fscript"},
                 {"code", std::string("shape-") + scene::issue_name(f.issue)},
                 {"message", f.diag.message}};
    if (json fix = fix_of(d.text, scene, f); !fix.is_null()) diag["data"] = fix;
    list.push_back(diag);
  }
}

}  // namespace

bool scene_model_of(const Document& d, vrml::Scene& scene, scene::SceneModel& model) {
  frontend::DiagnosticSink ignored;
  std::string path = path_of_uri(d.uri);
  bool ok = vrml::scene_of_text(path.empty() ? d.uri : path, d.text, d.scene, scene, ignored);
  scene::ModelOptions mo;
  mo.compile.backend = "vm";
  return ok && scene::build_scene_model(scene, mo, ignored, model);
}

json range_of(const std::string& text, uint32_t line, uint32_t col, uint32_t length) {
  Position a = position_of_line_col(text, line, col), b = position_of_line_col(text, line, col + std::max(1u, length));
  return {{"start", {{"line", a.line}, {"character", a.character}}},
          {"end", {{"line", b.line}, {"character", b.character}}}};
}

json range_of_span(const std::string& text, uint32_t begin, uint32_t end) {
  Position a = position_of(text, begin), b = position_of(text, end);
  return {{"start", {{"line", a.line}, {"character", a.character}}},
          {"end", {{"line", b.line}, {"character", b.character}}}};
}

Position position_param(const json& params) {
  Position p;
  const json& pos = params.at("position");
  p.line = pos.at("line").get<uint32_t>();
  p.character = pos.at("character").get<uint32_t>();
  return p;
}

json diagnostics(const Document& d) {
  frontend::DiagnosticSink sink;
  std::vector<frontend::Diagnostic> all;
  if (d.scene) {
    frontend::check_scene(d.uri, d.text, sink);
  } else {  // check_script's steps, on the analysis the other features share
    auto a = analyze_document(d);
    all = a->diag.all();
    if (!a->diag.has_errors()) frontend::lowering_warnings(a->script, sink);
  }
  all.insert(all.end(), sink.all().begin(), sink.all().end());
  json list = json::array();
  bool errors = false;
  for (const auto& diag : all) {
    errors |= diag.severity == frontend::Severity::Error;
    int severity = diag.severity == frontend::Severity::Error ? 1
        : diag.severity == frontend::Severity::Warning        ? 2
                                                              : 3;
    list.push_back({{"range", range_of(d.text, diag.pos.line, diag.pos.col, diag.length)},
                    {"severity", severity},
                    {"source", "fscript"},
                    {"message", diag.message}});
  }
  if (!errors) shape_diagnostics(d, list);
  return {{"uri", d.uri}, {"version", d.version}, {"diagnostics", list}};
}

}  // namespace fscript::lsp
