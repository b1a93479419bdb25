// fvrml-run: reads an FVRML scene, runs the time model, meshes every FVRML shape and writes VRML97,
// glTF, PLY, OBJ, STL or a PNG picture; animated shapes become frames (VRML97 Switch, glTF
// animation, numbered mesh files or a contact sheet); `--stats` reports the resolved scene as JSON.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <nlohmann/json.hpp>
#include <thread>

#include "backends/backend.h"
#include "runtime/support/big_stack.h"
#include "frontend/vrml/inline.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "runtime/mesh/distance.h"
#include "runtime/mesh/dual_contour.h"
#include "runtime/mesh/field.h"
#include "runtime/mesh/mesh_io.h"
#include "runtime/mesh/mesh_read.h"
#include "runtime/mesh/octree.h"
#include "runtime/render/png.h"
#include "runtime/render/raster.h"
#include "runtime/scene/scene_model.h"
#include "runtime/scene/shape_mesh.h"
#include "runtime/scene/vrml_export.h"
#include "tools/fvrml-run/run.h"
#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "runtime/support/version.h"
#include "tools/budget_flags.h"

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
    nlohmann::json j = {{"operation", g.operation}, {"type", g.type}, {"fraction", g.fraction}, {"shapes", g.shapes},
                        {"ftransforms", g.groups}, {"parent", g.parent}, {"affine", affine}};
    if (meshed && meshed->group_counts.count(i))
      j["vertices"] = meshed->group_counts.at(i).first, j["triangles"] = meshed->group_counts.at(i).second;
    groups.push_back(j);
  }
  return {{"shapes", shapes}, {"ftransforms", groups}};
}

// "640x480" or "512" (a square), each side in [16, 8192].
bool parse_size(const std::string& s, uint32_t& w, uint32_t& h) {
  unsigned long a = 0, b = 0;
  size_t x = s.find('x');
  try {
    size_t used = 0;
    a = std::stoul(s.substr(0, x), &used);
    if (used != (x == std::string::npos ? s.size() : x)) return false;
    b = a;
    if (x != std::string::npos) {
      b = std::stoul(s.substr(x + 1), &used);
      if (used != s.size() - x - 1) return false;
    }
  } catch (const std::exception&) {
    return false;
  }
  if (a < 16 || b < 16 || a > 8192 || b > 8192) return false;
  w = static_cast<uint32_t>(a), h = static_cast<uint32_t>(b);
  return true;
}

// "AZ,EL" in degrees, the elevation strictly between -90 and 90.
bool parse_view(const std::string& s, double& az, double& el) {
  size_t comma = s.find(',');
  if (comma == std::string::npos) return false;
  try {
    size_t u1 = 0, u2 = 0;
    double a = std::stod(s.substr(0, comma), &u1), e = std::stod(s.substr(comma + 1), &u2);
    if (u1 != comma || u2 != s.size() - comma - 1 || !std::isfinite(a) || !(e > -90 && e < 90)) return false;
    az = a, el = e;
  } catch (const std::exception&) {
    return false;
  }
  return true;
}

bool is_script_path(const std::string& path) { return path.size() > 3 && path.compare(path.size() - 3, 3, ".fs") == 0; }

// fvrml-run shape.fs: the script as the definition of one FShape with every other field at its
// FVRML default. The scene's file is the script itself, the definition starting at its first
// character, so diagnostics and runtime errors name the .fs file's own lines and columns.
bool script_scene(const std::string& path, const std::string& text, Loaded& l) {
  const std::string wrapper = "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"0\" } }\n";
  if (!vrml::parse_scene(std::make_unique<fscript::frontend::SourceFile>(path, wrapper), l.diag, l.scene)) return false;
  const vrml::Value* g = l.scene.roots.empty() ? nullptr : l.scene.roots[0]->get("geometry");
  vrml::Node* geometry = g && !g->nodes.empty() ? g->nodes[0].get() : nullptr;
  if (geometry)
    for (vrml::FieldSlot& f : geometry->fields) {
      if (f.name != "definition" || f.value.strs.empty() || f.value.str_spans.empty()) continue;
      f.value.strs[0] = text;
      f.value.str_spans[0] = {0, static_cast<uint32_t>(text.size())};
      l.scene.file = std::make_unique<fscript::frontend::SourceFile>(path, text);
      for (vrml::Node* n : {l.scene.roots[0].get(), geometry}) n->file = l.scene.file.get();  // not the wrapper's
      return true;
    }
  std::cerr << path << ": error: internal: the FShape wrapper of a script has no definition\n";
  return false;
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

// The octree's figures over every implicit shape meshed (runtime/mesh/octree.h).
nlohmann::json prune_json() {
  const mesh::PruneStats& p = mesh::prune_totals();
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& l : p.levels)
    levels.push_back({{"size", l.size}, {"empty", l.empty}, {"full", l.full}, {"ambiguous", l.ambiguous}});
  return {{"pruned", p.pruned}, {"levels", levels}, {"points", p.points}, {"evaluated", p.evaluated},
          {"evaluated_fraction", p.points ? double(p.evaluated) / double(p.points) : 1.0}, {"fallbacks", p.fallbacks}};
}

// Dual contouring's figures over every implicit shape it meshed (runtime/mesh/dc_octree.h).
nlohmann::json dual_contouring_json() {
  mesh::DualContourStats d = mesh::dual_contour_totals();
  return {{"shapes", d.jobs}, {"vertices", d.cells}, {"merged_cells", d.merged}, {"triangles", d.triangles},
          {"max_qef_error_cells", d.max_error}};
}

// 590776 -> "590,776".
std::string thousands(uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

// The line a successful write ends with: "wrote f6.ply: 590,776 triangles, 1 shape, 0.41 s".
std::string written_summary(const Options& o, const nlohmann::json& st, double ms) {
  // Triangles: of every shape (one frame), of every cached animation frame, or of the frame files.
  uint64_t triangles = 0;
  for (const char* part : {"shapes", "ftransforms", "animations", "frames"})
    if (st.contains(part) && st[part].is_array())
      for (const auto& s : st[part])
        if (s.contains("triangles") && s["triangles"].is_number()) triangles += s["triangles"].get<uint64_t>();
  std::string what;
  if (st.contains("frames") && st["frames"].is_array()) what = std::to_string(st["frames"].size()) + " frame files, ";
  if (st.contains("animations") && !st["animations"].empty()) what = "animated, ";
  what += thousands(triangles) + " triangles";
  if (st.contains("shapes")) {
    size_t shapes = st["shapes"].size();
    what += ", " + std::to_string(shapes) + (shapes == 1 ? " shape" : " shapes");
  }
  char secs[32];
  std::snprintf(secs, sizeof secs, ", %.2f s", ms / 1000.0);
  return "wrote " + o.output + ": " + what + secs;
}

int single(const Options& o, Loaded& l, nlohmann::json& st);

// What the preview page takes from the scene: the first Viewpoint, the DirectionalLights (in world
// coordinates), the headlight and the background colour.
nlohmann::json view_json(const fscript::render::RenderOptions& ro) {
  nlohmann::json v = {{"headlight", ro.headlight}, {"background", ro.background}, {"lights", nlohmann::json::array()}};
  if (ro.camera)
    v["camera"] = {{"position", ro.camera->position}, {"orientation", ro.camera->orientation},
                   {"fieldOfView", ro.camera->field_of_view}};
  for (const auto& l : ro.lights)
    v["lights"].push_back({{"direction", l.direction}, {"colour", l.colour}, {"intensity", l.intensity}, {"ambient", l.ambient}});
  return v;
}

}  // namespace

int run_scene(const Options& o, nlohmann::json& st, std::vector<std::string>* files) {
  auto t0 = Clock::now();
  std::string text, error;
  bool script = is_script_path(o.path);
  if (!(script ? fscript::support::read_file(o.path, text, error) : vrml::read_scene_text(o.path, text, error))) {
    std::cerr << o.path << ": error: " << error << "\n";
    return 1;
  }
  Loaded l;
  l.from_script = script;
  bool ok = script ? script_scene(o.path, text, l)
                   : vrml::parse_scene(std::make_unique<fscript::frontend::SourceFile>(o.path, text), l.diag, l.scene);
  if (ok && !script) ok = vrml::load_inlines(l.scene, l.diag, files);  // local Inline files, read and parsed
  st = {{"parse_ms", ms_since(t0)}};
  if (!ok) {
    std::cerr << fscript::frontend::render_all(l.diag);
    return 1;
  }
  if (o.view_json) st["view"] = view_json(render_options(o, l.scene, o.width, o.height));
  bool animation = o.format == "wrl" || o.format == "glb";
  return o.frames > 0 && !animation ? frames(o, l, st) : single(o, l, st);
}

namespace {

// One frame: VRML97 to a file or standard output, a mesh file, or a picture.
int single(const Options& o, Loaded& l, nlohmann::json& st) {
  auto t1 = Clock::now();
  SceneModel model;
  if (!build(l, model, o.model, true)) return 1;
  st["compile_ms"] = ms_since(t1);
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
  if (write && !tracks(o, model).empty()) {
    int rc = animated(o, l, model, st);
    nlohmann::json s = stats(l.scene, model, nullptr);
    st["shapes"] = s["shapes"], st["ftransforms"] = s["ftransforms"];
    return rc;
  }
  if (write) {
    fscript::support::progress_expect(mesh_jobs(model), "meshes");
    meshed = mesh_scene(o, l.scene, model, o.format != "wrl", o.threads);
    if (meshed.failed && !o.keep_going) return 1;
    st["polygonize_ms"] = ms_since(t2);
    st["evaluation_ms"] = evaluation_ms_since(e0);
    t2 = Clock::now();
    std::string error;
    if (o.format == "wrl") {
      std::string text = fscript::scene::export_vrml(l.scene, meshed.by_node);
      if (o.output.empty() || o.output == "-") std::cout << text;
      else if (!fscript::support::write_file_atomic(o.output, text, error)) return std::cerr << "error: " << error << "\n", 1;
    } else if (o.format == "png") {
      fscript::render::RenderOptions ro = render_options(o, l.scene, o.width, o.height);
      if (!fscript::render::write_png(o.output, ro.width, ro.height, 3, fscript::render::render(picture(meshed, l.scene), ro), error))
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

int run(int argc, char** argv) {
  CLI::App app{"fvrml-run: FVRML scenes (VRML97 with function-defined shapes)"};
  app.set_version_flag("--version", fscript::support::version_line("fvrml-run"));
  Options o;
  o.model.compile.backend = fscript::backends::available_backends().front();
  o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("SCENE", o.path, "the .wrl scene (plain or gzip), or an .fs script: one FShape with its definition")
      ->required();
  app.add_option("--backend", o.model.compile.backend, "evaluation backend: vm, sse or llvm (default: vm)");
  bool disk_cache = false;
  app.add_flag("--llvm-disk-cache", disk_cache,
               "keep the llvm backend's machine code in ~/.cache/fscript/llvm for the next run");
  // The budgets of every script of the scene, as fscript's (README, "Common options").
  fscript::backends::Budgets& budgets = o.model.compile.budgets;
  fscript::tools::add_budget_flags(app, budgets, budgets.max_call_depth);
  app.add_option("--time", o.model.now, "the scene clock in seconds after load (default 0)")->type_name("SECONDS");
  app.add_option("--fraction", o.fraction, "drive every node as if set_fraction F (0 to 1) had been received")
      ->check(CLI::Range(0.0, 1.0).description(""))
      ->type_name("F");
  app.add_option("--frames", o.frames,
                 "sample N (1 to 1,000) fractions i/N of the cycle: numbered mesh files, or a PNG contact sheet")
      ->check(CLI::Range(1, 1000).description(""))
      ->type_name("N");
  app.add_option("--resolution-scale", o.model.resolution_scale, "multiply every node's resolution by K > 0")
      ->check(CLI::PositiveNumber.description(""))
      ->type_name("K");
  app.add_flag("--stats", o.stats, "print one JSON object describing the resolved scene on standard error");
  bool no_prune = false;
  app.add_flag("--no-prune", no_prune,
               "sample every grid point of implicit shapes (the same meshes; by default interval bounds skip the "
               "regions far from the surface)");
  std::string mesher = "dc";
  app.add_option("--mesher", mesher,
                 "implicit shapes by dc (dual contouring, the default: sharp CSG edges and corners kept, large "
                 "triangles where the surface is flat) or mt (marching tetrahedra: a dense mesh with smooth normals)")
      ->check(CLI::IsMember({"mt", "dc"}))
      ->type_name("MESHER");
  CLI::Option* tolerance = app.add_option("--tolerance", o.mesher.tolerance,
                 "dual contouring merges cells while their vertex stays within T cells (root-mean-square) of the "
                 "surface's tangent planes; 0 keeps every cell (default 0.02)")
      ->check(CLI::Range(0.0, 10.0).description(""))
      ->type_name("T");
  app.add_option("-o,--output", o.output, "output file: .wrl (default), .glb, .ply, .obj, .stl or .png");
  ServeOptions serve;
  app.add_flag("--serve", serve.on,
               "a live preview in the browser: serves a page that shows the scene and updates on every save, "
               "until Ctrl-C");
  app.add_option("--port", serve.port, "--serve: the port (default 8800; 0 picks a free one)")->check(CLI::Range(0, 65535));
  app.add_option("--host", serve.host, "--serve: the address to listen on (default 127.0.0.1: this machine only)");
  app.add_flag("--open", serve.open, "--serve: open the page in the desktop's browser (xdg-open)");
  app.add_option("--format", o.format, "wrl|glb|ply|obj|stl|png (default: from the output's extension; wrl)");
  app.add_flag("--keep-going", o.keep_going, "write what succeeded when a shape fails");
  app.add_option("--check", o.check, "compare the mesh with the reference mesh REF (ply, obj, stl): distances as JSON");
  app.add_option("--width", o.width, "picture width in pixels, 16 to 8,192 (png)")
      ->check(CLI::Range(16u, 8192u).description(""))
      ->type_name("W");
  app.add_option("--height", o.height, "picture height in pixels, 16 to 8,192 (png)")
      ->check(CLI::Range(16u, 8192u).description(""))
      ->type_name("H");
  std::string size, view;
  app.add_option("--size", size, "picture size WxH (or W for a square), 16 to 8,192 pixels a side (png)")
      ->type_name("WxH");
  app.add_option("--view", view,
                 "look from azimuth AZ (degrees about the vertical, from the front toward the right) and elevation "
                 "EL (degrees above the horizon), framing the scene automatically even if it has a Viewpoint "
                 "(default 30,20) (png)")
      ->type_name("AZ,EL");
  app.add_option("--zoom", o.zoom, "come closer (F > 1) or step back (F < 1) from the automatic framing (png)")
      ->check(CLI::Range(0.01, 100.0).description(""))
      ->type_name("F");
  app.add_option("--threads", o.threads, "worker threads, 1 to 256 (default: all cores); the output is the same for any count")
      ->check(CLI::Range(1, 256).description(""))
      ->type_name("N");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (o.fraction >= 0) o.model.fraction = o.fraction;
  if (!size.empty() && !parse_size(size, o.width, o.height)) {
    std::cerr << "error: --size wants WxH (or W) with 16 <= W, H <= 8192, got '" << size << "'\n";
    return 2;
  }
  if (!view.empty() && !parse_view(view, o.azimuth, o.elevation)) {
    std::cerr << "error: --view wants AZ,EL in degrees with -90 < EL < 90, got '" << view << "'\n";
    return 2;
  }
  o.view_given = !view.empty();
  o.prune = !no_prune;
  o.mesher.kind = mesher == "dc" ? mesh::Mesher::DualContouring : mesh::Mesher::MarchingTetrahedra;
  if (tolerance->count() && o.mesher.kind != mesh::Mesher::DualContouring)
    std::cerr << "warning: --tolerance has no effect with --mesher mt (marching tetrahedra merges no cells)\n";
  if (std::string message; disk_cache && !fscript::backends::enable_llvm_disk_cache(message)) {
    std::cerr << "error: " << message << "\n";
    return 2;
  }
  if (!fscript::backends::make_backend(o.model.compile.backend)) {
    std::cerr << "error: " << fscript::backends::missing_backend_message(o.model.compile.backend) << "\n";
    return 2;
  }
  // On a terminal, no -o would mean thousands of coordinates on the screen: a picture instead, in
  // the current folder, named after the scene (a pipe still gets VRML97 on standard output).
  if (!serve.on && o.output.empty() && o.format.empty() && !o.stats && o.check.empty() && o.frames == 0 && isatty(STDOUT_FILENO)) {
    std::string name = std::filesystem::path(o.path).filename().string();
    for (const char* ext : {".wrl.gz", ".wrz", ".wrl", ".WRL", ".fs"})
      if (name.size() > std::strlen(ext) && name.compare(name.size() - std::strlen(ext), std::string::npos, ext) == 0) {
        name.erase(name.size() - std::strlen(ext));
        break;
      }
    o.output = name + ".png";
    std::cerr << "no -o given: writing " << o.output << " (-o OUT.wrl|glb|ply|obj|stl|png chooses; -o - "
              << "writes VRML97 to standard output)\n";
  }
  if (o.format.empty() && o.output == "-") o.format = "wrl";
  if (o.format.empty() && !o.output.empty()) o.format = o.output.substr(o.output.find_last_of('.') + 1);
  if (o.format.empty()) o.format = "wrl";
  static const std::set<std::string> kFormats = {"wrl", "glb", "ply", "obj", "stl", "png"};
  if (!kFormats.count(o.format)) {
    std::cerr << "error: unsupported output format '" << o.format << "': fvrml-run writes wrl, glb, ply, obj, stl and png\n";
    return 2;
  }
  bool animation = o.format == "wrl" || o.format == "glb";
  if (o.frames > 0 && !animation && o.output.empty()) {
    std::cerr << "error: --frames with " << o.format << " needs -o (the frames go to numbered files)\n";
    return 2;
  }
  if (serve.on) return fvrml_run::serve(o, serve);
  auto t0 = Clock::now();
  nlohmann::json st;
  int rc;
  {
    fscript::support::ProgressLine line("fvrml-run");  // on a terminal, for runs over a second
    rc = run_scene(o, st, nullptr);
  }
  if (o.stats && rc == 0) {
    st["prune"] = prune_json();
    if (o.mesher.kind == mesh::Mesher::DualContouring) st["dual_contouring"] = dual_contouring_json();
    std::cerr << st.dump() << "\n";
  }
  if (!o.stats && rc == 0 && !o.output.empty() && o.output != "-") std::cerr << written_summary(o, st, ms_since(t0)) << "\n";
  return rc;
}

}  // namespace
}  // namespace fvrml_run

int main(int argc, char** argv) {
  int rc = 0;
  fscript::support::run_with_big_stack([&] { rc = fvrml_run::run(argc, argv); });
  return rc;
}
