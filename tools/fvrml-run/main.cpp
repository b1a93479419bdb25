// fvrml-run: reads an FVRML scene, runs the time model, meshes every FVRML shape and writes VRML97,
// glTF, PLY, OBJ, STL or a PNG picture; `--frames N` samples N fractions of the cycle (numbered
// mesh files, or a contact sheet for PNG); `--stats` reports the resolved scene as JSON.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <nlohmann/json.hpp>
#include <thread>

#include "backends/backend.h"
#include "frontend/big_stack.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "runtime/mesh/distance.h"
#include "runtime/mesh/mesh_io.h"
#include "runtime/mesh/mesh_read.h"
#include "runtime/render/png.h"
#include "runtime/render/raster.h"
#include "runtime/scene/scene_model.h"
#include "runtime/scene/shape_mesh.h"
#include "runtime/scene/vrml_export.h"

namespace {

using Clock = std::chrono::steady_clock;
using fscript::scene::SceneModel;
namespace vrml = fscript::vrml;
namespace mesh = fscript::mesh;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Options {
  std::string path, output, format, check;
  fscript::scene::ModelOptions model;
  double fraction = -1;
  int frames = 0, threads = 1;
  bool stats = false, keep_going = false;
  uint32_t width = 800, height = 600;
};

// The meshes of one frame: per replaced node (FShape or top-level FTransform) and per shape.
struct Meshed {
  std::map<const vrml::Node*, mesh::Mesh> by_node;
  std::vector<std::pair<size_t, size_t>> counts;  // vertices, triangles per shape
  bool failed = false;
};

void report(const Options& o, const vrml::Scene& scene, const vrml::Node* n, const std::string& what) {
  fscript::frontend::LineCol lc = scene.file->position(n->span.begin);
  std::cerr << o.path << ":" << lc.line << ": " << (o.keep_going ? "warning: " : "error: ") << what << "\n";
}

// Meshes every shape outside an FTransform and every top-level FTransform; `world` applies the
// enclosing Transforms (mesh files and pictures) or not (the VRML97 output keeps them).
Meshed mesh_scene(const Options& o, const vrml::Scene& scene, const SceneModel& model, bool world) {
  Meshed out;
  for (const auto& s : model.shapes) {
    mesh::Mesh m;
    fscript::backend::RuntimeError err;
    if (s.group < 0 && !fscript::scene::mesh_shape(s, m, err, world, o.threads)) {
      report(o, scene, s.fshape, err.message + (err.line ? " (script line " + std::to_string(err.line) + ")" : ""));
      out.failed = true;
    }
    out.counts.push_back({m.positions.size(), m.triangles.size()});
    if (s.group < 0) out.by_node[s.fshape] = std::move(m);
  }
  for (size_t g = 0; g < model.groups.size(); ++g) {
    if (model.groups[g].parent >= 0) continue;
    mesh::Mesh m;
    fscript::backend::RuntimeError err;
    if (!fscript::scene::mesh_group(model, static_cast<int>(g), m, err, world, o.threads)) {
      report(o, scene, model.groups[g].node, "FTransform: " + err.message);
      out.failed = true;
    }
    out.by_node[model.groups[g].node] = std::move(m);
  }
  return out;
}

// All the frame's meshes in one (moved out of `m` when there is only one).
mesh::Mesh merged(Meshed& m) {
  if (m.by_node.size() == 1) return std::move(m.by_node.begin()->second);
  mesh::Mesh all;
  for (const auto& [node, part] : m.by_node) all.append(part);
  return all;
}

nlohmann::json field_json(const fscript::scene::CompiledField& f) {
  return {{"field", f.field}, {"timeSpan", {f.span0, f.span1}}, {"t", f.t}};
}

nlohmann::json stats(const vrml::Scene& scene, const SceneModel& m, const Meshed* meshed) {
  nlohmann::json shapes = nlohmann::json::array();
  for (size_t i = 0; i < m.shapes.size(); ++i) {
    const auto& s = m.shapes[i];
    nlohmann::json j = {{"line", scene.file->position(s.fshape->span.begin).line},
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
  for (const auto& g : m.groups) {
    nlohmann::json affine = nlohmann::json::object();
    for (const auto& [field, parts] : g.affine) affine[field] = parts.size();
    groups.push_back({{"operation", g.operation}, {"type", g.type}, {"fraction", g.fraction}, {"shapes", g.shapes},
                      {"ftransforms", g.groups}, {"parent", g.parent}, {"affine", affine}});
  }
  return {{"shapes", shapes}, {"ftransforms", groups}};
}

// The camera of the scene's first Viewpoint at the top level (VRML97 binds the first one), if any.
std::optional<fscript::render::Camera> viewpoint(const vrml::Scene& scene) {
  for (const auto& n : scene.roots) {
    if (!n || n->type != "Viewpoint") continue;
    fscript::render::Camera c;
    const vrml::Value* p = n->get("position");
    const vrml::Value* r = n->get("orientation");
    const vrml::Value* f = n->get("fieldOfView");
    for (int k = 0; k < 3 && p && k < static_cast<int>(p->nums.size()); ++k) c.position[k] = p->nums[k];
    for (int k = 0; k < 4 && r && k < static_cast<int>(r->nums.size()); ++k) c.orientation[k] = r->nums[k];
    if (f && !f->nums.empty() && f->nums[0] > 0 && f->nums[0] < 3.1) c.field_of_view = f->nums[0];
    return c;
  }
  return std::nullopt;
}

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
  nlohmann::json j = {{"hausdorff", d.hausdorff}, {"chamfer", d.chamfer},
                      {"hausdorff_relative", diag > 0 ? d.hausdorff / diag : 0.0},
                      {"chamfer_relative", diag > 0 ? d.chamfer / diag : 0.0},
                      {"vertices", all.positions.size()}, {"triangles", all.triangles.size()},
                      {"watertight", t.watertight}, {"manifold", t.manifold}, {"euler", t.euler}};
  std::cout << j.dump() << "\n";
  return true;
}

// "out.ply", frame 3 of 12 -> "out-03.ply".
std::string numbered(const std::string& path, int frame, int frames) {
  size_t dot = path.find_last_of('.');
  int digits = static_cast<int>(std::to_string(std::max(1, frames - 1)).size());
  char num[16];
  std::snprintf(num, sizeof num, "-%0*d", digits, frame);
  return dot == std::string::npos ? path + num : path.substr(0, dot) + num + path.substr(dot);
}

bool write_frame(const Options& o, const std::string& path, const mesh::Mesh& all) {
  std::string error;
  mesh::MeshFormat f = o.format == "ply" ? mesh::MeshFormat::Ply : o.format == "obj" ? mesh::MeshFormat::Obj
                     : o.format == "stl" ? mesh::MeshFormat::Stl : mesh::MeshFormat::Glb;
  if (!mesh::write_mesh(all, f, path, error)) {
    std::cerr << "error: " << error << "\n";
    return false;
  }
  return true;
}

struct Loaded {
  fscript::frontend::DiagnosticSink diag;
  vrml::Scene scene;
};

// Builds the model; diagnostics are printed the first time only (frames repeat the same ones).
bool build(Loaded& l, SceneModel& model, const fscript::scene::ModelOptions& mo, bool print) {
  bool ok = fscript::scene::build_scene_model(l.scene, mo, l.diag, model);
  if (print || !ok) std::cerr << fscript::frontend::render_all(l.diag);
  l.diag.clear();
  return ok;
}

// One frame: VRML97 to a file or standard output, a mesh file, or a picture.
int single(const Options& o, Loaded& l, nlohmann::json& st) {
  auto t1 = Clock::now();
  SceneModel model;
  if (!build(l, model, o.model, true)) return 1;
  st["compile_ms"] = ms_since(t1);
  auto t2 = Clock::now();
  bool write = !o.output.empty() || (!o.stats && o.check.empty());
  Meshed meshed;
  if (!o.check.empty()) {
    meshed = mesh_scene(o, l.scene, model, true);
    if (meshed.failed && !o.keep_going) return 1;
    if (!check_against(o.check, merged(meshed))) return 1;
  }
  if (write) {
    meshed = mesh_scene(o, l.scene, model, o.format != "wrl");
    if (meshed.failed && !o.keep_going) return 1;
    st["polygonize_ms"] = ms_since(t2);
    t2 = Clock::now();
    std::string error;
    if (o.format == "wrl") {
      std::string text = fscript::scene::export_vrml(l.scene, meshed.by_node);
      if (o.output.empty() || o.output == "-") std::cout << text;
      else if (!fscript::frontend::write_file_atomic(o.output, text, error)) return std::cerr << "error: " << error << "\n", 1;
    } else if (o.format == "png") {
      fscript::render::RenderOptions ro;
      ro.width = o.width, ro.height = o.height;
      ro.camera = viewpoint(l.scene);
      if (!fscript::render::write_png(o.output, ro.width, ro.height, 3, fscript::render::render(merged(meshed), ro), error))
        return std::cerr << "error: " << error << "\n", 1;
    } else if (!write_frame(o, o.output, merged(meshed))) {
      return 1;
    }
    st["write_ms"] = ms_since(t2);
  } else {
    st["polygonize_ms"] = ms_since(t2);
  }
  nlohmann::json s = stats(l.scene, model, write ? &meshed : nullptr);
  st["shapes"] = s["shapes"], st["ftransforms"] = s["ftransforms"];
  return meshed.failed ? 1 : 0;
}

// --frames N: fractions i/N. Mesh formats get numbered files; PNG a contact sheet of all frames.
int frames(const Options& o, Loaded& l, nlohmann::json& st) {
  auto t2 = Clock::now();
  int cols = static_cast<int>(std::ceil(std::sqrt(o.frames))), rows = (o.frames + cols - 1) / cols;
  uint32_t tw = std::max<uint32_t>(16, o.width / cols), th = std::max<uint32_t>(16, o.height / rows);
  std::vector<uint8_t> sheet(size_t(tw) * cols * th * rows * 3, 255);
  nlohmann::json per_frame = nlohmann::json::array();
  bool failed = false;
  for (int f = 0; f < o.frames; ++f) {
    fscript::scene::ModelOptions mo = o.model;
    mo.fraction = static_cast<double>(f) / o.frames;
    SceneModel model;
    if (!build(l, model, mo, f == 0)) return 1;
    Meshed meshed = mesh_scene(o, l.scene, model, true);
    failed |= meshed.failed;
    if (meshed.failed && !o.keep_going) return 1;
    mesh::Mesh all = merged(meshed);
    per_frame.push_back({{"fraction", *mo.fraction}, {"vertices", all.positions.size()}, {"triangles", all.triangles.size()}});
    if (o.format != "png") {
      if (!write_frame(o, numbered(o.output, f, o.frames), all)) return 1;
      continue;
    }
    fscript::render::RenderOptions ro;
    ro.width = tw, ro.height = th;
    auto px = fscript::render::render(all, ro);
    int cx = f % cols, cy = f / cols;
    for (uint32_t y = 0; y < th; ++y)
      std::copy_n(px.begin() + size_t(y) * tw * 3, tw * 3, sheet.begin() + ((size_t(cy) * th + y) * tw * cols + size_t(cx) * tw) * 3);
  }
  std::string error;
  if (o.format == "png" && !fscript::render::write_png(o.output, tw * cols, th * rows, 3, sheet, error))
    return std::cerr << "error: " << error << "\n", 1;
  st["frames"] = per_frame;
  st["polygonize_ms"] = ms_since(t2);
  return failed ? 1 : 0;
}

int run(int argc, char** argv) {
  CLI::App app{"fvrml-run: FVRML scenes (VRML97 with function-defined shapes)"};
  Options o;
  o.model.backend = fscript::backend::available_backends().front();
  o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("SCENE", o.path, "the .wrl scene (plain or gzip)")->required();
  app.add_option("--backend", o.model.backend, "evaluation backend (default: the fastest built)");
  app.add_option("--time", o.model.now, "the scene clock in seconds after load (default 0)");
  app.add_option("--fraction", o.fraction, "drive every node as if set_fraction F had been received")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--frames", o.frames, "sample N fractions i/N of the cycle: numbered mesh files, or a PNG contact sheet")
      ->check(CLI::Range(1, 1000));
  app.add_option("--resolution-scale", o.model.resolution_scale, "multiply every node's resolution")
      ->check(CLI::PositiveNumber);
  app.add_flag("--stats", o.stats, "print one JSON object describing the resolved scene on standard error");
  app.add_option("-o,--output", o.output, "output file: .wrl (default), .glb, .ply, .obj, .stl or .png");
  app.add_option("--format", o.format, "wrl|glb|ply|obj|stl|png (default: from the output's extension; wrl)");
  app.add_flag("--keep-going", o.keep_going, "write what succeeded when a shape fails");
  app.add_option("--check", o.check, "compare the mesh with the reference mesh REF (ply, obj, stl): distances as JSON");
  app.add_option("--width", o.width, "picture width in pixels (png)")->check(CLI::Range(16u, 8192u));
  app.add_option("--height", o.height, "picture height in pixels (png)")->check(CLI::Range(16u, 8192u));
  app.add_option("--threads", o.threads, "worker threads (default: all cores); the output is the same for any count")
      ->check(CLI::Range(1, 256));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (o.fraction >= 0) o.model.fraction = o.fraction;
  if (!fscript::backend::make_backend(o.model.backend)) {
    std::cerr << "error: backend '" << o.model.backend << "' is not built in this binary\n";
    return 2;
  }
  if (o.format.empty() && !o.output.empty()) o.format = o.output.substr(o.output.find_last_of('.') + 1);
  if (o.format.empty()) o.format = "wrl";
  static const std::set<std::string> kFormats = {"wrl", "glb", "ply", "obj", "stl", "png"};
  if (!kFormats.count(o.format)) {
    std::cerr << "error: output format '" << o.format << "' is not built yet (this build writes wrl, glb, ply, obj, stl and png)\n";
    return 2;
  }
  if (o.frames > 0 && (o.output.empty() || o.format == "wrl")) {
    std::cerr << "error: --frames needs -o with a mesh or png format (animated VRML97 output is not built yet)\n";
    return 2;
  }
  auto t0 = Clock::now();
  std::string text, error;
  if (!vrml::read_scene_text(o.path, text, error)) {
    std::cerr << o.path << ": error: " << error << "\n";
    return 1;
  }
  Loaded l;
  bool ok = vrml::parse_scene(std::make_unique<fscript::frontend::SourceFile>(o.path, text), l.diag, l.scene);
  nlohmann::json st = {{"parse_ms", ms_since(t0)}};
  if (!ok) {
    std::cerr << fscript::frontend::render_all(l.diag);
    return 1;
  }
  int rc = o.frames > 0 ? frames(o, l, st) : single(o, l, st);
  if (o.stats && rc == 0) std::cerr << st.dump() << "\n";
  return rc;
}

}  // namespace

int main(int argc, char** argv) {
  int rc = 0;
  fscript::frontend::run_with_big_stack([&] { rc = run(argc, argv); });
  return rc;
}
