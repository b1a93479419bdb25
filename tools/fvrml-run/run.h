#pragma once
// What the parts of fvrml-run share: the options, the loaded scene, the meshes of one frame, and
// the steps every output goes through.
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "engine/mesh/mesh.h"
#include "engine/render/raster.h"
#include "engine/scene/scene_model.h"

namespace fvrml_run {

using Clock = std::chrono::steady_clock;
using fscript::scene::SceneModel;
namespace vrml = fscript::vrml;
namespace mesh = fscript::mesh;

inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Milliseconds of function evaluation since `ns0` (summed over threads).
double evaluation_ms_since(uint64_t ns0);

class MeshMemo;
struct Part;

struct Options {
  std::string path, output, format, check;
  fscript::scene::ModelOptions model;
  double fraction = -1;
  int frames = 0, threads = 1;
  bool stats = false, keep_going = false, prune = true;
  bool strict = false;  // a missing Inline is an error, not a warning
  bool force = false;   // an output may replace a file the run reads
  bool instant = false;  // --time or --fraction: one instant asked for, not an animation
  mesh::MesherOptions mesher;  // --mesher, --tolerance
  bool direct_pictures = true;  // --render direct (default) or mesh: how pictures draw implicit shapes
  uint32_t width = 800, height = 600;
  double azimuth = 30, elevation = 20, zoom = 1;  // the picture's automatic camera (raster.h)
  bool view_given = false;
  bool view_json = false;  // --serve: the scene's Viewpoint, lights and background in the stats' "view"
  // --serve: shape diagnostics printed (for the page's overlay) as well as kept in the stats.
  bool print_shape_diagnostics = false;
  // --profile: where evaluation goes, by source line (printed after the run; mesher.profiler set),
  // and --profile-picture: where in the box it goes, as a PNG.
  bool profile = false;
  std::string profile_picture;
  MeshMemo* memo = nullptr;  // --serve: the meshes of the last run, reused where nothing changed
  // --serve, glTF: the scene so far while animations are polygonized (its static shapes and the
  // frames made: `frames` of `of` of the animation under way).
  std::function<void(const std::string& glb, size_t frames, size_t of)> on_partial;
  // --serve: set when a newer save makes the run moot; it stops between shapes and frames, and the
  // meshers stop within a batch of evaluations (the caller holds a support::CancelScope of it).
  const std::atomic<bool>* cancel = nullptr;
  // --serve: a run longer than this is cancelled and reported as an error on the page (0: none).
  double max_seconds = 0;
  // --shard K/M: the animation frames i % M == K go to this part (shard.h) instead of an output.
  Part* shard_part = nullptr;
  // fvrml-run merge: every animation frame comes from `memo` (filled from the parts), made from
  // the files these parts were made from; a frame missing from it is an error, not made here.
  const Part* merging = nullptr;
  // fvrml-run merge of --frames N with mesh files or a contact sheet: the parts' whole frames.
  const std::map<uint32_t, mesh::Mesh>* whole_frames = nullptr;
};

inline bool cancelled(const Options& o) { return o.cancel && o.cancel->load(); }

struct Loaded {
  fscript::frontend::DiagnosticSink diag;
  vrml::Scene scene;
  bool from_script = false;  // an .fs file wrapped in one FShape (main.cpp, script_scene)
  std::vector<std::string> files;  // the files read: the scene, then its Inlines and EXTERNPROTOs
};

// The meshes of one frame: per replaced node (FShape or top-level FTransform) and per shape.
struct Meshed {
  std::map<const vrml::Node*, mesh::Mesh> by_node;
  std::vector<const vrml::Node*> order;  // by_node's keys as put, in the model's order
  // Files and pictures take the meshes in this order, never the map's (pointer) order: that moved
  // with the heap, so one scene's shapes came out in another order when a backend allocated more.
  void put(const vrml::Node* n, mesh::Mesh m) {
    if (!by_node.count(n)) order.push_back(n);
    by_node[n] = std::move(m);
  }
  mesh::Mesh all() const {
    mesh::Mesh out;
    for (const vrml::Node* n : order) out.append(by_node.at(n));
    return out;
  }
  std::vector<std::pair<size_t, size_t>> counts;  // vertices, triangles per shape
  std::map<size_t, std::pair<size_t, size_t>> group_counts;  // per top-level FTransform
  bool failed = false;
};

// Prints a shape's runtime error at one place, as a compiler would ("PATH:LINE:COL: error: WHAT",
// the line and a caret): the script's own line and column in the scene (the error knows them), else
// the node's. A warning with --keep-going.
void report(const Options& o, const vrml::Scene& scene, const vrml::Node* n, const fscript::backends::RuntimeError& err,
            const std::string& prefix = "");

// --profile: each profiled shape's report on standard error (its lines, the costliest first), in
// the stats as "profile", and the picture when asked; false when the picture cannot be written.
bool report_profiles(const Options& o, const Loaded& l, nlohmann::json& st);

// Meshes every shape outside an FTransform and every top-level FTransform except those in `skip`;
// `world` applies the enclosing Transforms (mesh files and pictures) or not (the VRML97 output keeps
// them); `threads` per shape.
Meshed mesh_scene(const Options& o, const vrml::Scene& scene, const SceneModel& model, bool world, int threads,
                  const std::set<const vrml::Node*>& skip = {});
// How many meshes mesh_scene makes (each a job of the progress line: the callers announce them
// before they start, so the share done does not jump back as more appear).
uint64_t mesh_jobs(const SceneModel& model, const std::set<const vrml::Node*>& skip = {});
// Reads, parses (with local Inlines, whose paths go to `files` when given) and runs the scene as
// the options say, writing o.output; diagnostics on standard error; st gets the --stats figures.
int run_scene(const Options& o, nlohmann::json& st, std::vector<std::string>* files);

// --serve: the live preview (serve.h).
struct ServeOptions;
int serve(const Options& o, const ServeOptions& s);

// The line of a node in the file it was read from (the scene's, or an Inline's).
uint32_t node_line(const vrml::Scene& scene, const vrml::Node& n);

// All the frame's meshes in one (moved out of `m` when there is only one).
mesh::Mesh merged(Meshed& m);

// What a picture shows: the frame's meshes and the scene's standard VRML97 geometry.
mesh::Mesh picture(Meshed& m, const vrml::Scene& scene);

// Builds the model; diagnostics are printed the first time only (frames repeat the same ones).
bool build(Loaded& l, SceneModel& model, const fscript::scene::ModelOptions& mo, bool print);

// What the shape diagnostics say of the model's implicit shapes (engine/scene/shape_diagnostics.h):
// printed, or with --stats in the statistics as "shape_diagnostics".
void report_shapes(const Options& o, const Loaded& l, const SceneModel& model, nlohmann::json& st);

// "out.ply", frame 3 of 12 -> "out-03.ply".
std::string numbered(const std::string& path, int frame, int frames);

// Writes a mesh file in the format of the options; prints the error.
bool write_frame(const Options& o, const std::string& path, const mesh::Mesh& all);

// The camera of the scene's first top-level Viewpoint, its DirectionalLights, its headlight.
fscript::render::RenderOptions render_options(const Options& o, const vrml::Scene& scene, uint32_t width,
                                              uint32_t height);

// The shapes a picture draws without meshing (--render direct): every implicit shape outside an
// FTransform and every top-level FTransform of implicit shapes whose field intervals can bound,
// except those in `skip`; the rest is meshed. `meshed_no_more` gets their nodes.
struct DirectParts {
  std::vector<std::unique_ptr<mesh::Field>> fields;
  std::vector<fscript::render::DirectShape> shapes;
  std::vector<const vrml::Node*> nodes;  // per shape: where its runtime errors are reported
  std::set<const vrml::Node*> meshed_no_more;
};
bool direct_parts(const Options& o, const vrml::Scene& scene, const SceneModel& model, DirectParts& out,
                  const std::set<const vrml::Node*>& skip = {});
// A frame's picture: the meshes of `meshed` with the scene's standard geometry, and the direct
// shapes, in one depth buffer. Prints a runtime error at its shape and returns false.
bool draw(const Options& o, const vrml::Scene& scene, Meshed& meshed, const DirectParts& direct,
          const fscript::render::RenderOptions& ro, std::vector<uint8_t>& px);

// --frames N with a mesh format or PNG: numbered files, or a contact sheet.
int frames(const Options& o, Loaded& l, nlohmann::json& st);

// VRML97 or glTF of a scene with animated nodes (FShape / top-level FTransform with frames N > 0,
// or every one under --frames N): each becomes its frames, polygonized through a frame cache.
// `model` is the scene at the clock; the static nodes are meshed from it.
int animated(const Options& o, Loaded& l, const SceneModel& model, nlohmann::json& st);

// The animated nodes of the model (empty when the output is not VRML97 or glTF).
// The frames of a cycle an animated shape gets in glTF and VRML97 when neither the command line
// (--frames) nor the shape (its `frames` field) says: the live preview's too.
constexpr int kDefaultAnimationFrames = 24;

struct Track {
  const vrml::Node* node = nullptr;
  bool group = false;  // a top-level FTransform (model.groups[index]), else model.shapes[index]
  int index = 0;
  int frames = 0;
};
// The shapes and top-level FTransforms glTF and VRML97 write as animations: with --frames every
// one (a still one then comes out as one frame); else those with a `frames` field, and those that
// change in time (moves) with kDefaultAnimationFrames, unless one instant was asked for.
std::vector<Track> tracks(const Options& o, const SceneModel& model);
// Whether the shape or group of `t` changes with its t (geometry, colour, texture, material, CSG).
bool moves(const SceneModel& m, const Track& t);
// Whether anything in the scene changes with time.
bool scene_moves(const SceneModel& m);
// Whether the run stays within what one run may cost (scene/shape_cost.h): the points of every shape
// times `frames` (--frames with a mesh format or pictures), else times the frames of the animation
// it belongs to, and the memory of a frame with the frames an animation keeps. An error at the
// costliest shape's resolution when not.
bool within_sample_limits(const Options& o, Loaded& l, const SceneModel& model, int frames);

}  // namespace fvrml_run
