#pragma once
// A shape's evaluation profile as a report: each source line of its script with the operations
// evaluated on it after pruning, its share of the evaluation time and the share of points whose
// tape still runs it; the pruning figures; a picture of where in the box the work goes.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/mesh/field_profile.h"
#include "engine/scene/scene_model.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::scene {

struct LineCost {
  uint32_t line = 0;    // 0: the function's inputs and constants
  double ops = 0;       // operations evaluated on it (values and gradients)
  double ns = 0;        // evaluation time charged to it: each field's measured time split by op cost
  double runs_at = 0;   // share of the points evaluated whose tape runs it (0..1)
  std::string text;     // the source line, as written
};

struct ShapeProfile {
  std::string path;      // the file the script is in
  uint32_t line = 0;     // the shape's node
  std::string kind;      // "FShape", "FTransform"
  bool mapped = false;   // its function runs on tapes, so its work maps to lines
  uint64_t points = 0, gradients = 0, boxes = 0;  // values, gradients evaluated; boxes bounded
  double value_ms = 0, gradient_ms = 0, bound_ms = 0;
  size_t whole_length = 0;    // operations of the whole function's tape
  uint64_t whole_points = 0;  // points evaluated on it (regions its bounds did not simplify)
  size_t regions = 0;         // regions with a tape of their own that evaluated points
  size_t tape_min = 0, tape_max = 0;  // operations of their tapes
  double tape_mean = 0;       // over those regions
  double ops_per_point = 0;   // operations per value evaluated
  uint64_t decided = 0, undecided = 0;  // octree regions the bounds decided (empty or full), and not
  double ops = 0, ns = 0;     // totals over the lines
  std::vector<LineCost> lines;  // by line, those with work
};

// Every implicit shape outside an FTransform and every top-level implicit FTransform of the model
// meshed as fvrml-run meshes them, profiled. False on a runtime error (`where`: its shape's node).
struct SceneProfile {
  mesh::Profiler profiler;
  std::vector<ShapeProfile> shapes;  // in the order they were meshed
  std::vector<const mesh::FieldProfile*> profiles;  // theirs, for pictures
};
bool profile_scene(const vrml::Scene& scene, const SceneModel& model, int threads, bool prune, SceneProfile& out,
                   backends::RuntimeError& err, const vrml::Node*& where);

// The report of one profile; `node`: the shape's FShape (or FTransform).
ShapeProfile profile_report(const vrml::Scene& scene, const vrml::Node& node, const mesh::FieldProfile& p);

// The report as text: a header with the figures, then a table of the lines that have work, the
// costliest first (at most `rows`; 0: all).
std::string profile_text(const ShapeProfile& r, size_t rows = 0);

// The report as JSON (fvrml-run --stats's "profile", fscript profile --json): the figures, and per
// line its operations, its share of the time and the share of points that run it.
nlohmann::json profile_json(const ShapeProfile& r);

// The picture: two panels of the box seen from +z, the operations evaluated per column (left) and
// the mean tape length of the points there (right); columns where nothing was evaluated dark blue.
// RGB rows from the top; empty when nothing was evaluated.
std::vector<uint8_t> profile_picture(const mesh::FieldProfile& p, uint32_t& width, uint32_t& height);

// Nanoseconds per point of one step of `op` on the VM's tape evaluator, measured on this machine
// at the first ask (what a region's time is split by).
double op_cost_ns(ir::Op op);

}  // namespace fscript::scene
