// fvrml-run: reads an FVRML scene, runs the time model and resolves every FVRML node. This first
// stage reports the result (`--stats`); meshes, files and pictures come with the polygonizers.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <map>
#include <thread>
#include <iostream>
#include <nlohmann/json.hpp>

#include "backends/backend.h"
#include "frontend/big_stack.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "runtime/mesh/mesh_io.h"
#include "runtime/render/png.h"
#include "runtime/render/raster.h"
#include "runtime/scene/scene_model.h"
#include "runtime/scene/shape_mesh.h"
#include "runtime/scene/vrml_export.h"

namespace {

using Clock = std::chrono::steady_clock;
using fscript::scene::SceneModel;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

nlohmann::json field_json(const fscript::scene::CompiledField& f) {
  return {{"field", f.field}, {"timeSpan", {f.span0, f.span1}}, {"t", f.t}};
}

nlohmann::json stats(const fscript::vrml::Scene& scene, const SceneModel& m, double parse_ms, double build_ms) {
  nlohmann::json shapes = nlohmann::json::array();
  for (const auto& s : m.shapes) {
    fscript::frontend::LineCol lc = scene.file->position(s.fshape->span.begin);
    nlohmann::json j = {{"line", lc.line},
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
    shapes.push_back(j);
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& g : m.groups) {
    nlohmann::json affine = nlohmann::json::object();
    for (const auto& [field, parts] : g.affine) affine[field] = parts.size();
    groups.push_back({{"operation", g.operation}, {"type", g.type}, {"fraction", g.fraction}, {"shapes", g.shapes},
                      {"ftransforms", g.groups}, {"parent", g.parent}, {"affine", affine}});
  }
  return {{"shapes", shapes}, {"ftransforms", groups}, {"parse_ms", parse_ms}, {"compile_ms", build_ms}};
}

int run(int argc, char** argv) {
  CLI::App app{"fvrml-run: FVRML scenes (VRML97 with function-defined shapes)"};
  std::string path;
  fscript::scene::ModelOptions opts;
  double fraction = -1;
  bool want_stats = false, keep_going = false;
  std::string output, format;
  opts.backend = fscript::backend::available_backends().front();
  app.add_option("SCENE", path, "the .wrl scene (plain or gzip)")->required();
  app.add_option("--backend", opts.backend, "evaluation backend (default: the fastest built)");
  app.add_option("--time", opts.now, "the scene clock in seconds after load (default 0)");
  app.add_option("--fraction", fraction, "drive every node as if set_fraction F had been received")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--resolution-scale", opts.resolution_scale, "multiply every node's resolution")
      ->check(CLI::PositiveNumber);
  app.add_flag("--stats", want_stats, "print one JSON object describing the resolved scene on standard error");
  app.add_option("-o,--output", output, "output file: .wrl (default), .glb, .ply, .obj, .stl or .png");
  app.add_option("--format", format, "wrl|glb|ply|obj|stl|png (default: from the output's extension; wrl)");
  app.add_flag("--keep-going", keep_going, "write what succeeded when a shape fails");
  uint32_t width = 800, height = 600;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("--threads", threads, "worker threads (default: all cores); the output is the same for any count")
      ->check(CLI::Range(1, 256));
  app.add_option("--width", width, "picture width in pixels (png)")->check(CLI::Range(16u, 8192u));
  app.add_option("--height", height, "picture height in pixels (png)")->check(CLI::Range(16u, 8192u));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (fraction >= 0) opts.fraction = fraction;
  if (!fscript::backend::make_backend(opts.backend)) {
    std::cerr << "error: backend '" << opts.backend << "' is not built in this binary\n";
    return 2;
  }
  if (format.empty() && !output.empty()) format = output.substr(output.find_last_of('.') + 1);
  if (format.empty()) format = "wrl";
  fscript::mesh::MeshFormat mesh_format = fscript::mesh::MeshFormat::Ply;
  bool png = format == "png", wrl = format == "wrl";
  if (!png && !wrl) {
    if (format == "ply") mesh_format = fscript::mesh::MeshFormat::Ply;
    else if (format == "obj") mesh_format = fscript::mesh::MeshFormat::Obj;
    else if (format == "stl") mesh_format = fscript::mesh::MeshFormat::Stl;
    else if (format == "glb") mesh_format = fscript::mesh::MeshFormat::Glb;
    else {
      std::cerr << "error: output format '" << format << "' is not built yet (this build writes wrl, glb, ply, obj, stl and png)\n";
      return 2;
    }
  }
  bool write_output = !output.empty() || !want_stats;  // no -o: VRML97 on standard output
  auto t0 = Clock::now();
  std::string text, error;
  if (!fscript::vrml::read_scene_text(path, text, error)) {
    std::cerr << path << ": error: " << error << "\n";
    return 1;
  }
  fscript::frontend::DiagnosticSink diag;
  fscript::vrml::Scene scene;
  bool ok = fscript::vrml::parse_scene(std::make_unique<fscript::frontend::SourceFile>(path, text), diag, scene);
  double parse_ms = ms_since(t0);
  auto t1 = Clock::now();
  SceneModel model;
  if (ok) ok = fscript::scene::build_scene_model(scene, opts, diag, model);
  double build_ms = ms_since(t1);
  std::cerr << fscript::frontend::render_all(diag);
  if (!ok) return 1;
  auto t2 = Clock::now();
  fscript::mesh::Mesh all;
  std::vector<std::pair<size_t, size_t>> counts;
  bool failed = false;
  if (write_output && wrl) {
    std::map<const fscript::vrml::Node*, fscript::mesh::Mesh> meshes;
    for (const auto& s : model.shapes) {
      fscript::backend::RuntimeError err;
      fscript::mesh::Mesh m;
      if (s.group >= 0) continue;
      if (!fscript::scene::mesh_shape(s, m, err, false, threads)) {
        fscript::frontend::LineCol lc = scene.file->position(s.fshape->span.begin);
        std::cerr << path << ":" << lc.line << ": " << (keep_going ? "warning: " : "error: ") << err.message << "\n";
        failed = true;
        continue;
      }
      counts.push_back({m.positions.size(), m.triangles.size()});
      meshes[s.fshape] = std::move(m);
    }
    for (size_t g = 0; g < model.groups.size(); ++g) {
      if (model.groups[g].parent >= 0) continue;
      fscript::backend::RuntimeError err;
      fscript::mesh::Mesh m;
      if (!fscript::scene::mesh_group(model, static_cast<int>(g), m, err, false, threads)) {
        fscript::frontend::LineCol lc = scene.file->position(model.groups[g].node->span.begin);
        std::cerr << path << ":" << lc.line << ": " << (keep_going ? "warning: " : "error: ") << "FTransform: "
                  << err.message << "\n";
        failed = true;
        continue;
      }
      meshes[model.groups[g].node] = std::move(m);
    }
    if (failed && !keep_going) return 1;
    std::string text = fscript::scene::export_vrml(scene, meshes);
    std::string error;
    if (output.empty() || output == "-") {
      std::cout << text;
    } else if (!fscript::frontend::write_file_atomic(output, text, error)) {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
  } else if (write_output) {
    for (const auto& s : model.shapes) {
      fscript::mesh::Mesh m;
      fscript::backend::RuntimeError err;
      fscript::frontend::LineCol lc = scene.file->position(s.fshape->span.begin);
      std::string where = path + ":" + std::to_string(lc.line) + ": ";
      if (s.group >= 0) {
        counts.push_back({0, 0});  // meshed with its FTransform below
        continue;
      }
      if (!fscript::scene::mesh_shape(s, m, err, true, threads)) {
        std::cerr << where << (keep_going ? "warning: " : "error: ") << err.message
                  << (err.line ? " (script line " + std::to_string(err.line) + ")" : "") << "\n";
        failed = true;
      }
      counts.push_back({m.positions.size(), m.triangles.size()});
      all.append(m);
    }
    for (size_t g = 0; g < model.groups.size(); ++g) {
      if (model.groups[g].parent >= 0) continue;
      fscript::mesh::Mesh m;
      fscript::backend::RuntimeError err;
      if (!fscript::scene::mesh_group(model, static_cast<int>(g), m, err, true, threads)) {
        fscript::frontend::LineCol lc = scene.file->position(model.groups[g].node->span.begin);
        std::cerr << path << ":" << lc.line << ": " << (keep_going ? "warning: " : "error: ")
                  << "FTransform: " << err.message << "\n";
        failed = true;
      }
      all.append(m);
    }
    if (failed && !keep_going) return 1;
    std::string error;
    if (png) {
      fscript::render::RenderOptions ro;
      ro.width = width;
      ro.height = height;
      if (!fscript::render::write_png(output, ro.width, ro.height, 3, fscript::render::render(all, ro), error)) {
        std::cerr << "error: " << error << "\n";
        return 1;
      }
    } else if (!fscript::mesh::write_mesh(all, mesh_format, output, error)) {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
  }
  double mesh_ms = ms_since(t2);
  if (want_stats) {
    auto j = stats(scene, model, parse_ms, build_ms);
    for (size_t i = 0; i < counts.size() && i < j["shapes"].size(); ++i) {
      j["shapes"][i]["vertices"] = counts[i].first;
      j["shapes"][i]["triangles"] = counts[i].second;
    }
    j["polygonize_ms"] = mesh_ms;
    std::cerr << j.dump() << "\n";
  }
  return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  int rc = 0;
  fscript::frontend::run_with_big_stack([&] { rc = run(argc, argv); });
  return rc;
}
