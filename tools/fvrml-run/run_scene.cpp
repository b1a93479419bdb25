// fvrml-run's one run of a scene: read it (a .wrl with its Inlines, or an .fs script as one FShape),
// build the model, mesh it and write the output the options name, with the --stats figures.
#include <iostream>
#include <nlohmann/json.hpp>

#include "frontend/vrml/inline.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "frontend/vrml/script_scene.h"
#include "engine/mesh/distance.h"
#include "engine/mesh/mesh_read.h"
#include "engine/render/png.h"
#include "engine/render/raster.h"
#include "engine/scene/vrml_export.h"
#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "tools/fvrml-run/run.h"
#include "tools/fvrml-run/shard.h"

namespace fvrml_run {
namespace {

nlohmann::json field_json(const fscript::scene::CompiledField& f) {
  return {{"field", f.field}, {"timeSpan", {f.span0, f.span1}}, {"t", f.t}};
}

nlohmann::json stats(const vrml::Scene& scene, const SceneModel& m, const Meshed* meshed) {
  nlohmann::json shapes = nlohmann::json::array();
  for (size_t i = 0; i < m.shapes.size(); ++i) {
    const auto& s = m.shapes[i];
    nlohmann::json j = {{"line", node_line(scene, *s.fshape)},
                        {"kind", fscript::scene::kind_name(s.kind)},
                        {"domain", s.domain},
                        {"resolution", s.resolution},
                        {"fraction", s.fraction},
                        {"active", s.time.active},
                        {"frames", s.frames},
                        {"geometry", field_json(s.geometry)},
                        {"transform", s.transform}};
    if (!s.fshape->def_name.empty()) j["def"] = s.fshape->def_name;
    if (s.group >= 0) j["ftransform"] = s.group;
    if (s.colour) j["colour"] = field_json(*s.colour), j["colour"]["rgb"] = s.colour->rgb;
    if (s.texture) j["texture"] = field_json(*s.texture);
    if (meshed && i < meshed->counts.size())
      j["vertices"] = meshed->counts[i].first, j["triangles"] = meshed->counts[i].second;
    shapes.push_back(j);
  }
  nlohmann::json groups = nlohmann::json::array();
  for (size_t i = 0; i < m.groups.size(); ++i) {
    const auto& g = m.groups[i];
    nlohmann::json affine = nlohmann::json::object();
    for (const auto& [field, parts] : g.affine) affine[field] = parts.size();
    nlohmann::json j = {{"operation", g.operation}, {"type", g.type},          {"fraction", g.fraction},
                        {"shapes", g.shapes},       {"ftransforms", g.groups}, {"parent", g.parent},
                        {"affine", affine}};
    if (meshed && meshed->group_counts.count(i))
      j["vertices"] = meshed->group_counts.at(i).first, j["triangles"] = meshed->group_counts.at(i).second;
    groups.push_back(j);
  }
  return {{"shapes", shapes}, {"ftransforms", groups}};
}

bool is_script_path(const std::string& path) { return path.size() > 3 && path.compare(path.size() - 3, 3, ".fs") == 0; }

// --check REF: distances between the frame's mesh and a reference mesh, as JSON on standard output.
bool check_against(const std::string& ref, const mesh::Mesh& all) {
  mesh::Mesh reference;
  std::string error;
  if (!mesh::read_mesh(ref, reference, error)) {
    std::cerr << ref << ": error: " << error << "\n";
    return false;
  }
  auto d = mesh::mesh_distances(all, reference);
  double diag = mesh::bbox_diagonal(all);
  auto t = mesh::topology(all);
  nlohmann::json j = {{"hausdorff", d.hausdorff},
                      {"chamfer", d.chamfer},
                      {"hausdorff_relative", diag > 0 ? d.hausdorff / diag : 0.0},
                      {"chamfer_relative", diag > 0 ? d.chamfer / diag : 0.0},
                      {"vertices", all.positions.size()},
                      {"triangles", all.triangles.size()},
                      {"watertight", t.watertight},
                      {"manifold", t.manifold},
                      {"euler", t.euler}};
  std::cout << j.dump() << "\n";
  return true;
}

int single(const Options& o, Loaded& l, nlohmann::json& st);

// The files the run writes: -o, or with --frames N and a mesh format the N numbered files.
std::vector<std::string> outputs(const Options& o) {
  if (o.output.empty() || o.output == "-") return {};
  bool numbered_frames = o.frames > 0 && o.format != "wrl" && o.format != "glb" && o.format != "png" && !o.shard_part;
  if (!numbered_frames) return {o.output};
  std::vector<std::string> out;
  for (int f = 0; f < o.frames; ++f) out.push_back(numbered(o.output, f, o.frames));
  return out;
}

// False, with the error printed, where an output would replace a file the run reads: `fvrml-run
// lab.wrl -o lab.wrl` replaced a student's scene with our VRML97 export, without a word.
bool outputs_clear_of_inputs(const Options& o, const std::vector<std::string>& inputs) {
  for (const std::string& out : outputs(o)) {
    for (size_t i = 0; i < inputs.size(); ++i)
      if (fscript::support::same_file(out, inputs[i])) {
        std::cerr << "error: the output " << out << " is "
                  << (i == 0 ? "the scene this run reads" : "a file this scene reads (" + inputs[i] + ")")
                  << ": writing it would replace that file; name another output, or add --force\n";
        return false;
      }
    if (!o.check.empty() && fscript::support::same_file(out, o.check)) {
      std::cerr << "error: the output " << out
                << " is the reference mesh of --check: writing it would replace that file; "
                << "name another output, or add --force\n";
      return false;
    }
  }
  return true;
}

// --stats: each Inline drawn as nothing, where it is and what was tried.
nlohmann::json missing_json(const std::vector<vrml::MissingInline>& missing) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& m : missing) {
    fscript::frontend::LineCol at = m.file->position(m.span.begin);
    out.push_back({{"url", m.url},
                   {"file", m.file->path()},
                   {"line", at.line},
                   {"column", at.col},
                   {"looked_at", m.looked_at},
                   {"reason", m.reason}});
  }
  return out;
}

// What the preview page takes from the scene: the first Viewpoint, the DirectionalLights (in world
// coordinates), the headlight and the background colour.
nlohmann::json view_json(const fscript::render::RenderOptions& ro) {
  nlohmann::json v = {{"headlight", ro.headlight}, {"background", ro.background}, {"lights", nlohmann::json::array()}};
  if (ro.camera)
    v["camera"] = {{"position", ro.camera->position},
                   {"orientation", ro.camera->orientation},
                   {"fieldOfView", ro.camera->field_of_view}};
  for (const auto& l : ro.lights)
    v["lights"].push_back(
        {{"direction", l.direction}, {"colour", l.colour}, {"intensity", l.intensity}, {"ambient", l.ambient}});
  return v;
}

}  // namespace

int run_scene(const Options& o, nlohmann::json& st, std::vector<std::string>* files) {
  auto t0 = Clock::now();
  std::string text, error;
  bool script = is_script_path(o.path);
  if (!(script ? fscript::support::read_file(o.path, text, error, fscript::support::kMaxInputBytes)
               : vrml::read_scene_text(o.path, text, error))) {
    // A whole-file error (unreadable, too large, a gzip bomb) is placed at the file's start.
    std::cerr << o.path << ":1:1: error: " << error << "\n";
    return 1;
  }
  Loaded l;
  l.from_script = script;
  bool ok = script ? vrml::script_scene(o.path, text, l.scene, l.diag)
                   : vrml::parse_scene(std::make_unique<fscript::frontend::SourceFile>(o.path, text), l.diag, l.scene);
  l.files = {o.path};
  if (ok && !script)
    ok = vrml::load_inlines(l.scene, l.diag, &l.files, o.strict);  // local Inline files, read and parsed
  if (files) files->insert(files->end(), l.files.begin() + 1, l.files.end());
  st = {{"parse_ms", ms_since(t0)}};
  if (!l.scene.missing_inlines.empty()) st["missing_inlines"] = missing_json(l.scene.missing_inlines);
  if (!o.force && !outputs_clear_of_inputs(o, l.files)) return 1;
  if (!ok) {
    std::cerr << fscript::frontend::render_all(l.diag);
    return 1;
  }
  if (o.view_json) st["view"] = view_json(render_options(o, l.scene, o.width, o.height));
  bool animation = o.format == "wrl" || o.format == "glb";
  int rc = o.frames > 0 && !animation ? frames(o, l, st) : single(o, l, st);
  if (rc == 0 && o.profile && !report_profiles(o, l, st)) return 1;
  return rc;
}

namespace {

// --shard K/M of a still scene: slab K of every implicit shape's dual contouring blocks into the
// part (dc_slabs.h); the merge joins them and makes the rest (parametric shapes, colours, marching
// tetrahedra), as one machine does.
int shard_slabs(const Options& o, Loaded& l, const SceneModel& model) {
  auto split = mesh::SlabSplit::make(o.shard_part->shard.index, o.shard_part->shard.count);
  Options mine = o;
  mine.mesher.slabs = split.get();
  fscript::support::progress_expect(mesh_jobs(model), "meshes");
  if (mesh_scene(mine, l.scene, model, o.format != "wrl", o.threads).failed) return 1;
  o.shard_part->slabs = split->slabs();
  o.shard_part->still = true;
  if (o.shard_part->slabs.empty())
    std::cerr << o.path << ": note: no shape here is meshed by dual contouring in slabs (the implicit shapes with "
              << "--mesher dc): the merge makes every shape\n";
  return 0;
}

// One frame: VRML97 to a file or standard output, a mesh file, or a picture.
int single(const Options& o, Loaded& l, nlohmann::json& st) {
  auto t1 = Clock::now();
  SceneModel model;
  if (!build(l, model, o.model, true) || !within_sample_limits(o, l, model, 0)) return 1;
  st["compile_ms"] = ms_since(t1);
  report_shapes(o, l, model, st);
  auto t2 = Clock::now();
  uint64_t e0 = mesh::evaluation_ns().load();
  bool write = !o.output.empty() || (!o.stats && o.check.empty());
  Meshed meshed;
  if (!o.check.empty()) {
    fscript::support::progress_expect(mesh_jobs(model), "meshes");
    meshed = mesh_scene(o, l.scene, model, true, o.threads);
    if (meshed.failed && !o.keep_going) return 1;
    if (!check_against(o.check, merged(meshed))) return 1;
  }
  if (o.shard_part && tracks(o, model).empty()) return shard_slabs(o, l, model);
  if (write && !tracks(o, model).empty()) {
    int rc = animated(o, l, model, st);
    nlohmann::json s = stats(l.scene, model, nullptr);
    st["shapes"] = s["shapes"], st["ftransforms"] = s["ftransforms"];
    return rc;
  }
  if (write) {
    DirectParts direct;  // a picture's implicit shapes, drawn without meshing
    if (o.format == "png" && !direct_parts(o, l.scene, model, direct)) return 1;
    fscript::support::progress_expect(mesh_jobs(model, direct.meshed_no_more), "meshes");
    meshed = mesh_scene(o, l.scene, model, o.format != "wrl", o.threads, direct.meshed_no_more);
    if (meshed.failed && !o.keep_going) return 1;
    st["polygonize_ms"] = ms_since(t2);
    st["evaluation_ms"] = evaluation_ms_since(e0);
    t2 = Clock::now();
    std::string error;
    if (o.format == "wrl") {
      std::string text = fscript::scene::export_vrml(l.scene, meshed.by_node, {}, o.output);
      if (o.output.empty() || o.output == "-") std::cout << text;
      else if (!fscript::support::write_file_atomic(o.output, text, error))
        return std::cerr << "error: " << error << "\n", 1;
    } else if (o.format == "png") {
      fscript::render::RenderOptions ro = render_options(o, l.scene, o.width, o.height);
      std::vector<uint8_t> px;
      if (!draw(o, l.scene, meshed, direct, ro, px)) return 1;
      nlohmann::json lines = nlohmann::json::array();  // the shapes drawn without meshing, by line
      for (const vrml::Node* n : direct.nodes) lines.push_back(node_line(l.scene, *n));
      st["direct_shapes"] = lines;
      if (!fscript::render::write_png(o.output, ro.width, ro.height, 3, px, error))
        return std::cerr << "error: " << error << "\n", 1;
    } else if (!write_frame(o, o.output, o.format == "glb" ? picture(meshed, l.scene) : merged(meshed))) {
      return 1;
    }
    st["write_ms"] = ms_since(t2);
    // A scene that changes in time, written to a format of one instant: said, with the way to frames.
    if (!o.instant && o.format != "wrl" && o.format != "glb" && scene_moves(model)) st["one_instant"] = true;
  } else {
    st["polygonize_ms"] = ms_since(t2);
  }
  nlohmann::json s = stats(l.scene, model, write ? &meshed : nullptr);
  st["shapes"] = s["shapes"], st["ftransforms"] = s["ftransforms"];
  return meshed.failed ? 1 : 0;
}

}  // namespace
}  // namespace fvrml_run
