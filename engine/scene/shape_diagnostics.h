#pragma once
// Shape diagnostics: what an implicit shape's function does over its box, told before (or
// without) meshing it: empty, full, cut by its box, not a number, finer than its grid. Found by
// interval bounds over an octree and samples only where the bounds leave the sign open.
#include <array>
#include <string>
#include <vector>

#include "engine/scene/scene_model.h"
#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"

namespace fscript::scene {

enum class ShapeIssue { Empty, Full, InsideOut, Cut, NotANumber, FinerThanGrid };
const char* issue_name(ShapeIssue i);
// Three numbers as the diagnostics write them (%.3g, space-separated): a field's value.
std::string field_numbers(const std::array<double, 3>& v);

struct ShapeFinding {
  ShapeIssue issue = ShapeIssue::Empty;
  const vrml::Node* node = nullptr;  // the FGeometry (what a quick fix edits)
  frontend::Diagnostic diag;  // at the definition, the operation, or the bboxSize / resolution field
  // What would fix it, where there is an obvious fix: a box that holds the shape (Empty: it lies
  // outside its box; Full and Cut: it is bounded just outside), or a resolution that shows what
  // the grid misses.
  bool has_box = false;
  std::array<double, 3> center{}, size{};
  int resolution = 0;
  double fraction = 0;  // of the box (NotANumber), of the cells checked (FinerThanGrid)
};

// The findings of one implicit shape at the model's time, in the order of ShapeIssue; `top`: a
// shape outside every FTransform (one inside is cut by its box, or fills it, on purpose).
// Parametric shapes get none; a runtime error of the function (reported where the shape is
// meshed) ends the survey with what was found before it.
std::vector<ShapeFinding> diagnose_shape(const vrml::Scene& scene, const Shape& s, bool top);

// A runtime error of the shape or transform at `n`, at the script's line and column where the
// error knows them, else at the node; in `path` where given (the name the user gave the scene).
frontend::Diagnostic runtime_diagnostic(const vrml::Scene& scene, const vrml::Node& n,
                                        const backends::RuntimeError& err, frontend::Severity sev,
                                        const std::string& prefix = "", const std::string& path = "");

// Every implicit shape of the model (cut-by-box and full only for shapes outside FTransforms,
// whose children are cut by their boxes on purpose).
std::vector<ShapeFinding> diagnose_scene(const vrml::Scene& scene, const SceneModel& model);

}  // namespace fscript::scene
