// fvrml-run: reads an FVRML scene, runs the time model, meshes every FVRML shape and writes VRML97,
// glTF, PLY, OBJ, STL or a PNG picture; animated shapes become frames (VRML97 Switch, glTF
// animation, numbered mesh files or a contact sheet); `--stats` reports the resolved scene as JSON.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <set>
#include <nlohmann/json.hpp>
#include <thread>

#include "backends/backend.h"
#include "backends/row_split_kernel.h"
#include "backends/tiered/tiered.h"
#include "engine/mesh/dual_contour.h"
#include "engine/mesh/field_profile.h"
#include "engine/mesh/local_field.h"
#include "engine/mesh/sample_pruning.h"
#include "runtime/support/big_stack.h"
#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "runtime/support/version.h"
#include "tools/budget_flags.h"
#include "tools/cli_suggest.h"
#include "tools/limit_flags.h"
#include "tools/fvrml-run/run.h"
#include "tools/fvrml-run/memo.h"
#include "tools/fvrml-run/serve.h"
#include "tools/fvrml-run/shard.h"

namespace fvrml_run {
namespace {

#if defined(FS_HAVE_SERVE)
// --serve without --max-seconds: a run of the live preview that takes longer is cancelled.
constexpr double kServeMaxSeconds = 60;
#endif

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

// The tapes simplified per region of the mesh (engine/mesh/local_field.h).
nlohmann::json local_tapes_json() {
  const mesh::LocalTapeStats& l = mesh::local_tape_totals();
  uint64_t simplified = l.simplified.load();
  return {{"regions", l.regions.load()},
          {"simplified", simplified},
          {"mean_ops", simplified ? double(l.tape_ops.load()) / double(simplified) : 0.0},
          {"full_ops", simplified ? l.full_ops.load() / simplified : 0},
          {"gradient_tapes", l.gradients.load()}};
}

// The octree's figures over every implicit shape meshed (engine/mesh/sample_pruning.h).
nlohmann::json prune_json() {
  const mesh::PruneStats& p = mesh::prune_totals();
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& l : p.levels)
    levels.push_back({{"size", l.size}, {"empty", l.empty}, {"full", l.full}, {"ambiguous", l.ambiguous}});
  return {{"pruned", p.pruned},
          {"levels", levels},
          {"points", p.points},
          {"evaluated", p.evaluated},
          {"evaluated_fraction", p.points ? double(p.evaluated) / double(p.points) : 1.0},
          {"fallbacks", p.fallbacks},
          {"local_tapes", local_tapes_json()}};
}

// Dual contouring's figures over every implicit shape it meshed (engine/mesh/dc_cell_merge.h).
nlohmann::json dual_contouring_json() {
  mesh::DualContourStats d = mesh::dual_contour_totals();
  return {{"shapes", d.jobs},
          {"vertices", d.cells},
          {"merged_cells", d.merged},
          {"triangles", d.triangles},
          {"max_qef_error_cells", d.max_error},
          {"normals", {{"gradient", d.gradient_normals}, {"differences", d.difference_normals}}}};
}

// What the auto backend did: native compiles, the switch, the points on each tier.
nlohmann::json tiers_json() {
  fscript::backends::TierStats t = fscript::backends::tier_stats();
  return {{"native", t.native},
          {"kernels", t.kernels},
          {"compiles", t.compiles},
          {"cached", t.cached},
          {"switched", t.switched},
          {"failed", t.failed},
          {"first_switch_ms", t.first_switch_ms},
          {"vm_points", t.vm_points},
          {"native_points", t.native_points},
          {"native_share",
           t.vm_points + t.native_points ? double(t.native_points) / double(t.vm_points + t.native_points) : 0.0}};
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
  std::string what, files = o.output;
  if (st.contains("frames") && st["frames"].is_array()) {
    int n = static_cast<int>(st["frames"].size());
    if (o.format == "png") what = "a contact sheet of " + std::to_string(n) + (n == 1 ? " frame, " : " frames, ");
    else {
      files = n == 1 ? numbered(o.output, 0, n) : numbered(o.output, 0, n) + " ... " + numbered(o.output, n - 1, n);
      what = std::to_string(n) + (n == 1 ? " frame file, " : " frame files, ");
    }
  }
  int frames = 0;
  if (st.contains("animations"))
    for (const auto& a : st["animations"])
      if (a.contains("frames") && a["frames"].is_number()) frames = std::max(frames, a["frames"].get<int>());
  if (frames > 0) what = "animated, " + std::to_string(frames) + " frames a cycle, ";
  what += thousands(triangles) + " triangles";
  if (st.contains("shapes")) {
    size_t shapes = st["shapes"].size();
    what += ", " + std::to_string(shapes) + (shapes == 1 ? " shape" : " shapes");
  }
  char secs[32];
  std::snprintf(secs, sizeof secs, ", %.2f s", ms / 1000.0);
  std::string out = "wrote " + files + ": " + what + secs;
  if (st.value("one_instant", false)) {
    std::string format = o.format == "png" ? "a picture"
        : o.format == "stl"                ? "STL"
        : o.format == "obj"                ? "OBJ"
                                           : "PLY";
    out += "\nnote: the scene changes in time and " + format +
        " holds one instant: this is the scene at time 0; --frames N writes N " +
        (o.format == "png" ? "frames on a contact sheet" : "files") +
        " over its cycle, --time T or --fraction F another instant, and -o NAME.glb or NAME.wrl an animation";
  }
  return out;
}

// fvrml-run merge: the parts' frames in a memo the run takes every frame from.
struct Merge {
  const Part* first = nullptr;
  MeshMemo* memo = nullptr;
  const std::map<uint32_t, mesh::Mesh>* whole_frames = nullptr;
  mesh::SlabSplit* slabs = nullptr;  // a still scene's slabs, joined
};

constexpr char kShardNeeds[] =
    "error: --shard writes the part file -o PART and needs --format, the format of the merged output (wrl, glb, ply, "
    "obj, stl or png; fvrml-run merge PART... -o OUT)\n";

int run(int argc, char** argv, const Merge* merge = nullptr) {
  CLI::App app{"fvrml-run: FVRML scenes (VRML97 with function-defined shapes)"};
  app.set_version_flag("--version", fscript::support::version_line("fvrml-run"));
  Options o;
  o.model.compile.backend = fscript::backends::default_backend();
  o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  app.add_option("SCENE", o.path, "the .wrl scene (plain or gzip), or an .fs script: one FShape with its definition")
      ->required();
  app.add_option("--backend", o.model.compile.backend,
                 "evaluation backend: auto (the VM at once, native code from a background compile when the job is big "
                 "enough), vm, sse or llvm (default: auto)");
  bool disk_cache = false;
  app.add_flag("--llvm-disk-cache", disk_cache,
               "keep the llvm backend's machine code in ~/.cache/fscript/llvm for the next run");
  // The budgets of every script of the scene, as fscript's (README, "Common options").
  fscript::backends::Budgets& budgets = o.model.compile.budgets;
  fscript::tools::add_budget_flags(app, budgets, budgets.max_call_depth);
  fscript::tools::RunLimits limits;
  fscript::tools::add_limit_flags(app, limits, "none; 60 under --serve, where a run over it is cancelled");
  app.add_option("--time", o.model.now, "the scene clock in seconds after load (default 0)")->type_name("SECONDS");
  app.add_option("--fraction", o.fraction, "drive every node as if set_fraction F (0 to 1) had been received")
      ->check(CLI::Range(0.0, 1.0).description(""))
      ->type_name("F");
  app.add_option("--frames", o.frames,
                 "sample N (1 to 1,000) fractions i/N of the cycle: numbered mesh files, or a PNG contact sheet")
      ->check(CLI::Range(1, 1000).description(""))
      ->type_name("N");
  app.add_option("--resolution-scale", o.model.resolution_scale, "multiply every node's resolution by K > 0")
      ->check(CLI::Validator(
          [](std::string& text) {
            char* end = nullptr;
            double k = std::strtod(text.c_str(), &end);
            return end && *end == '\0' && k > 0 && std::isfinite(k) ? std::string()
                                                                    : "wants a number above 0, got '" + text + "'";
          },
          ""))
      ->type_name("K");
  app.add_flag("--stats", o.stats, "print one JSON object describing the resolved scene on standard error");
  std::string stats_file;
  app.add_option("--stats-file", stats_file,
                 "write --stats' object to FILE instead, with the scene's view (camera, lights, background), the "
                 "diagnostics still on standard error (the browser page reads it)")
      ->type_name("FILE");
  bool no_prune = false;
  app.add_flag("--no-prune", no_prune,
               "sample every grid point of implicit shapes, and every step of a direct picture's rays (the same "
               "meshes and pictures; by default interval bounds skip the regions far from the surface)");
  std::string mesher = "dc";
  app.add_option("--mesher", mesher,
                 "implicit shapes by dc (dual contouring, the default: sharp CSG edges and corners kept, large "
                 "triangles where the surface is flat) or mt (marching tetrahedra: a dense mesh with smooth normals)")
      ->check(CLI::IsMember({"mt", "dc"}))
      ->type_name("MESHER");
  CLI::Option* tolerance =
      app.add_option("--tolerance", o.mesher.tolerance,
                     "dual contouring merges cells while their vertex stays within T cells (root-mean-square) of the "
                     "surface's tangent planes; 0 keeps every cell (default 0.02)")
          ->check(CLI::Range(0.0, 10.0).description(""))
          ->type_name("T");
  std::string render = "direct";
  app.add_option("--render", render,
                 "how pictures draw implicit shapes: direct (the default: each pixel's ray meets the surface, no mesh) "
                 "or mesh (the mesh the other formats write, rasterised) (png)")
      ->check(CLI::IsMember({"direct", "mesh"}))
      ->type_name("HOW");
  app.add_flag("--profile", o.profile,
               "after the run, where implicit shapes' evaluation went: each script line's share of the time and of "
               "the operations evaluated after pruning, and the pruning figures (meshes pictures: --render mesh)");
  app.add_option("--profile-picture", o.profile_picture,
                 "with --profile: a PNG of the box seen from +z, the work per column and the mean tape length")
      ->type_name("FILE.png");
  app.add_option("-o,--output", o.output, "output file: .wrl (default), .glb, .ply, .obj, .stl or .png");
  std::string shard_text;
  app.add_option("--shard", shard_text,
                 "make only shard K of M into the part file -o PART, --format naming the merged output: the "
                 "animations' frames i with i % M == K, or in a still scene slab K of each implicit shape; auto: "
                 "Slurm's array task (docs/sharding.md)")
      ->type_name("K/M|auto");
  ServeOptions serve;
  app.add_flag("--serve", serve.on,
               "a live preview in the browser: serves a page that shows the scene and updates on every save, "
               "until Ctrl-C");
  app.add_option("--port", serve.port, "--serve: the port (default 8800; 0 picks a free one)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--host", serve.host, "--serve: the address to listen on (default 127.0.0.1: this machine only)");
  app.add_flag("--open", serve.open, "--serve: open the page in the desktop's browser (xdg-open)");
  app.add_option("--format", o.format, "wrl|glb|ply|obj|stl|png (default: from the output's extension; wrl)");
  app.add_flag("--keep-going", o.keep_going, "write what succeeded when a shape fails");
  app.add_flag("--force", o.force,
               "let an output replace a file the run reads (the scene, an Inline or EXTERNPROTO file, the --check "
               "mesh); without it that is refused");
  app.add_flag("--strict", o.strict,
               "an Inline that cannot be read (a missing file, or only remote URLs: never fetched) is an error; "
               "without it, a warning, and the scene is drawn without the Inline");
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
  app.add_option("--threads", o.threads,
                 "worker threads, 1 to 256 (default: all cores); the output is the same for any count")
      ->check(CLI::Range(1, 256).description(""))
      ->type_name("N");
  if (std::string error; !fscript::tools::check_command_line(app, argc, argv, false, error))
    return std::cerr << "error: " << error << "\nRun with --help for more information.\n", 2;
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
  o.direct_pictures = render == "direct";
  if (!o.profile_picture.empty() && !o.profile) o.profile = true;
  mesh::Profiler profiler;
  if (o.profile) o.mesher.profiler = &profiler, o.direct_pictures = false;
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
  if (!serve.on && o.output.empty() && o.format.empty() && !o.stats && o.check.empty() && o.frames == 0 &&
      isatty(STDOUT_FILENO)) {
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
  if (o.profile && (serve.on || !shard_text.empty() || merge))
    return std::cerr << "error: --profile profiles one run on this machine: not with --serve, --shard or merge\n", 2;
  if (!shard_text.empty() && o.format.empty()) return std::cerr << kShardNeeds, 2;
  if (o.format.empty() && o.output == "-") o.format = "wrl";
  if (o.format.empty() && !o.output.empty()) o.format = o.output.substr(o.output.find_last_of('.') + 1);
  if (o.format.empty()) o.format = "wrl";
  static const std::set<std::string> kFormats = {"wrl", "glb", "ply", "obj", "stl", "png"};
  if (!kFormats.count(o.format)) {
    std::cerr << "error: unsupported output format '" << o.format
              << "': fvrml-run writes wrl, glb, ply, obj, stl and png\n";
    return 2;
  }
  bool animation = o.format == "wrl" || o.format == "glb";
  if (o.frames > 0 && !animation && o.output.empty()) {
    std::cerr << "error: --frames with " << o.format << " needs -o (the frames go to numbered files)\n";
    return 2;
  }
  Shard shard;
  Part part;
  MeshMemo shard_memo;
  if (!shard_text.empty()) {
    std::string error;
    if (!parse_shard(shard_text, shard, error)) return std::cerr << "error: " << error << "\n", 2;
    if (serve.on || o.output.empty() || o.output == "-" || !o.check.empty() ||
        std::none_of(argv, argv + argc, [](const char* a) { return std::strncmp(a, "--format", 8) == 0; }))
      return std::cerr << kShardNeeds, 2;
    part.shard = shard;
    part.cwd = std::filesystem::current_path().string();
    part.args = args_for_part(argc, argv);
    o.shard_part = &part;
    o.memo = &shard_memo;  // for the frames' keys
  }
  if (merge)
    o.merging = merge->first, o.memo = merge->memo, o.whole_frames = merge->whole_frames, o.mesher.slabs = merge->slabs;
  // Under --serve the clock is per run (cancelled, the server goes on), not a watchdog on the process.
  o.instant = app.count("--time") > 0 || app.count("--fraction") > 0;
  if (!stats_file.empty()) o.stats = o.view_json = o.print_shape_diagnostics = true;
  fscript::mesh::evaluation_timing() = o.stats || serve.on;  // only a run that reports it times evaluation
  if (!fscript::tools::apply_limits("fvrml-run", limits, !serve.on)) return 1;
  o.model.max_memory_mib = limits.max_memory_mib;
  if (serve.on) {
#if defined(FS_HAVE_SERVE)
    o.max_seconds = limits.max_seconds > 0 ? limits.max_seconds : kServeMaxSeconds;
    return fvrml_run::serve(o, serve);
#else
    return std::cerr << "error: --serve is not in the browser build: its page is the preview\n", 2;
#endif
  }
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
    if (o.model.compile.backend == "auto") st["tiers"] = tiers_json();
    fscript::backends::RowStats rs = fscript::backends::row_stats();
    st["row_split"] = {{"kernels", rs.kernels}, {"rows", rs.rows}, {"points", rs.points}};
    st["huge_heap_mib"] = fscript::support::huge_heap().reserved >> 20;
    std::string error;
    if (stats_file.empty()) std::cerr << st.dump() << "\n";
    else if (!fscript::support::write_file_atomic(stats_file, st.dump() + "\n", error))
      return std::cerr << "error: " << error << "\n", 1;
  }
  if (o.shard_part && rc == 0) {
    std::string error;
    if (!write_part(o.output, part, error)) return std::cerr << "error: " << error << "\n", 1;
    size_t made = part.frames.size() + part.whole_frames.size(), slabs = part.slabs.size();
    std::cerr << "wrote " << o.output << ": shard " << shard.index << " of " << shard.count << ", ";
    if (part.still && slabs) std::cerr << "its slab of " << slabs << (slabs == 1 ? " shape\n" : " shapes\n");
    else if (part.still) std::cerr << "no slab (the merge makes every shape)\n";
    else std::cerr << made << (made == 1 ? " frame\n" : " frames\n");
    return 0;
  }
  if (!o.stats && rc == 0 && !o.output.empty() && o.output != "-")
    std::cerr << written_summary(o, st, ms_since(t0)) << "\n";
  return rc;
}

// fvrml-run merge PART... -o OUT: the parts checked, their frames in a memo, then the job's own
// command line run with -o OUT, every animation frame (or implicit shape's slab) taken from the parts.
int merge_main(int argc, char** argv) {
  CLI::App app{"fvrml-run merge: the parts of a sharded job (fvrml-run --shard K/M) into its output"};
  std::vector<std::string> paths;
  std::string output;
  app.add_option("PART", paths, "every part of the job (fvrml-run --shard K/M -o PART)")->required();
  app.add_option("-o,--output", output, "the output, of the shards' --format (.wrl, .glb, .ply, .obj, .stl or .png)")
      ->required();
  try {
    app.parse(argc - 1, argv + 1);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  for (const std::string& p : paths)
    if (fscript::support::same_file(p, output))
      return std::cerr << "error: -o " << output << " is a part this merge reads (" << p << "); name another output\n",
             1;
  std::vector<Part> parts(paths.size());
  std::string error;
  for (size_t i = 0; i < paths.size(); ++i)
    if (!read_part(paths[i], parts[i], error)) return std::cerr << paths[i] << ": error: " << error << "\n", 1;
  if (!check_parts(paths, parts, error)) return std::cerr << "error: " << error << "\n", 1;
  MeshMemo memo;
  std::set<std::string> keys;
  std::map<uint32_t, mesh::Mesh> whole;
  for (size_t i = 0; i < parts.size(); ++i) {
    for (const PartFrame& f : parts[i].frames) {
      if (!keys.insert(f.key).second)
        return std::cerr << paths[i]
                         << ": error: a frame that another part holds too (parts of one job never overlap)\n",
               1;
      memo.store_frame(f.key, f.compact);
    }
    for (auto& [index, m] : parts[i].whole_frames)
      if (!whole.emplace(index, std::move(m)).second)
        return std::cerr << paths[i]
                         << ": error: a frame that another part holds too (parts of one job never overlap)\n",
               1;
  }
  // The shards' --format is the output's: an -o of another type would get the wrong bytes.
  const std::vector<std::string>& a = parts[0].args;
  for (size_t i = 0; i < a.size(); ++i) {
    std::string format = a[i] == "--format" && i + 1 < a.size() ? a[i + 1]
        : a[i].rfind("--format=", 0) == 0                       ? a[i].substr(9)
                                                                : "";
    if (!format.empty() && output.substr(output.find_last_of('.') + 1) != format)
      return std::cerr << "error: the shards were made for " << format << " output: -o NAME." << format << "\n", 2;
  }
  std::string out = std::filesystem::absolute(output).string();
  std::error_code ec;
  if (std::filesystem::is_directory(parts[0].cwd, ec)) std::filesystem::current_path(parts[0].cwd, ec);
  std::vector<std::string> args = {"fvrml-run"};
  args.insert(args.end(), parts[0].args.begin(), parts[0].args.end());
  for (const char* a : {"-o", out.c_str()}) args.push_back(a);
  std::vector<char*> av;
  for (auto& a : args) av.push_back(a.data());
  std::vector<mesh::Slab> slabs;
  for (Part& p : parts) std::move(p.slabs.begin(), p.slabs.end(), std::back_inserter(slabs));
  std::unique_ptr<mesh::SlabSplit> joined = slabs.empty() ? nullptr : mesh::SlabSplit::join(std::move(slabs));
  Merge m{&parts[0], &memo, &whole, joined.get()};
  return run(static_cast<int>(av.size()), av.data(), &m);
}

}  // namespace
}  // namespace fvrml_run

int main(int argc, char** argv) {
  fscript::support::prepare_huge_heap();  // before any thread: one heap for all
  fscript::support::set_default_thread_stack();  // workers' stacks not sized by ulimit -s
  int rc = 0;
  fscript::support::run_with_big_stack([&] {
    rc =
        argc > 1 && std::strcmp(argv[1], "merge") == 0 ? fvrml_run::merge_main(argc, argv) : fvrml_run::run(argc, argv);
  });
  return rc;
}
