#pragma once
// The scene model: every FVRML node of a parsed scene resolved into what the shape pipeline
// needs: the shape's kind, compiled kernels (geometry, 3D texture, colour), domain, resolution,
// the FTransform tree above it, the enclosing Transforms, and the time state of every node at a
// clock value (or a forced fraction).
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "frontend/diagnostics.h"
#include "frontend/vrml/scene_graph.h"
#include "ir/interval_eval.h"
#include "engine/driver/driver.h"
#include "engine/scene/shape_cost.h"
#include "engine/scene/time_model.h"

namespace fscript::scene {

enum class ShapeKind { Implicit, Curve, Surface, Solid };
const char* kind_name(ShapeKind k);

using Mat4 = std::array<double, 16>;  // column-major, as OpenGL
Mat4 identity();
Mat4 multiply(const Mat4& a, const Mat4& b);
// The VRML97 Transform: T * C * R * SR * S * -SR * -C.
Mat4 vrml_transform(const double t[3], const double r[4], const double s[3], const double sr[4], const double c[3]);
// The local matrix of a Transform node (its fields, or their defaults).
Mat4 transform_matrix(const vrml::Node& transform);

// Component k of a numeric field (written or the interface default), else `fallback`.
double field_number(const vrml::Node& n, const char* field, size_t k = 0, double fallback = 0);
// The TimeSensor fields of a TimeSensor, FShape or FTransform.
TimeSensorFields time_fields(const vrml::Node& n);

// The gradient kernel of an FRep (ir::gradient_module: outputs f, df/dx, df/dy, df/dz), built
// and compiled on the first get(): only the dual contouring of a shape with crossings asks, so
// other shapes and other jobs never pay for it. Safe to call from several threads.
class LazyGradient {
 public:
  LazyGradient(std::shared_ptr<const ir::Module> m, std::string backend, const backends::Budgets& b)
      : module_(std::move(m)), backend_(std::move(backend)), budgets_(b) {}
  // nullptr when the FRep has no gradient here (not straight-line, or noise) or it did not compile.
  const backends::Kernel* get() const;
  // The gradient module as a flat tape, what regions simplify (engine/mesh/local_field.h); nullptr
  // where get() is.
  const ir::IntervalTape* tape() const;

 private:
  void build() const;
  std::shared_ptr<const ir::Module> module_;
  std::string backend_;
  backends::Budgets budgets_;
  mutable std::once_flag once_;
  mutable std::unique_ptr<backends::Kernel> kernel_;
  mutable std::unique_ptr<ir::IntervalTape> tape_;
};

// One compiled FScript field of a node.
struct CompiledField {
  std::string field;
  std::unique_ptr<backends::Kernel> kernel;
  std::shared_ptr<const ir::IntervalTape> intervals;  // bounds on it, when ir::interval_evaluable
  std::shared_ptr<const LazyGradient> gradient;        // an FShape's definition: its gradient
  bool rgb = false;  // colour: the script sets r, g, b (else its value goes through the pattern)
  double span0 = 0, span1 = 1;  // the node's timeSpan
  double t = 0;                 // the node's t at the evaluated time
  bool reads_t = true;          // the optimised kernel uses t (false: the same at every time)
};

struct Shape {
  const vrml::Node* fshape = nullptr;
  const vrml::Node* geometry_node = nullptr;
  const vrml::Node* material_node = nullptr;  // the FMaterial (patternKey, patternColor)
  int group = -1;  // index of the FTransform directly above it, or -1
  ShapeKind kind = ShapeKind::Implicit;
  std::array<double, 6> domain{};  // implicit: x0 x1 y0 y1 z0 z1 (the box); parametric: u0 u1 v0 v1 w0 w1
  std::array<int, 3> resolution{50, 50, 50};
  CompiledField geometry;
  std::optional<CompiledField> texture;  // FTexture3D
  std::optional<CompiledField> colour;   // FMaterial.diffuseColor
  std::vector<CompiledField> material;   // the other FMaterial strings
  Mat4 transform = identity();
  double fraction = 0;
  TimeSensorState time;
  int frames = 0;
};

// An analytical FTransform operation sees f, g (first and second child) and f1 ... f16.
constexpr int kMaxOperands = 16;

// An FTransform: an operation over its children (shapes and nested FTransforms).
struct Group {
  const vrml::Node* node = nullptr;
  int parent = -1;
  std::string operation;  // "union", ... or the analytical expression
  std::string type;
  std::optional<CompiledField> op_kernel;  // type "analytical"
  // Affine fields given as FScript strings: one kernel per component (3 or 4), of t.
  std::vector<std::pair<std::string, std::vector<CompiledField>>> affine;
  std::vector<int> shapes, groups;
  std::vector<std::pair<bool, int>> children;  // in file order: (is a group, index)
  double fraction = 0;
};

// The most nodes the scene's graph expands to, counting every PROTO instance's body and every USE
// of a DEF again (VRML97 allows both to multiply a small file into a huge graph: "billion laughs"),
// and the deepest it may nest through PROTO instances. More is an error at the node that crosses it.
constexpr size_t kMaxExpandedNodes = 1'000'000;
constexpr int kMaxExpandedDepth = 2000;
// The most frames an FShape's or FTransform's `frames` (or fvrml-run --frames) may ask for.
constexpr int kMaxFrames = 1000;
// What one frame of a shape costs (shape_cost.h), from its kind and resolution.
ShapeCost shape_cost(const Shape& s);

struct ModelOptions {
  // Every script of the scene compiles with these (tiered execution unless the caller says
  // otherwise).
  driver::CompileOptions compile;
  double now = 0;                   // --time
  std::optional<double> fraction;   // --fraction: every node as if set_fraction had been received
  double resolution_scale = 1;
  // The memory a shape may need (--max-memory, in MiB; 0: its default): a shape over it, or over
  // the points one shape may evaluate, is refused at its `resolution` before any work.
  uint64_t max_memory_mib = 0;
};

struct SceneModel {
  std::vector<Shape> shapes;
  std::vector<Group> groups;
  std::vector<std::vector<vrml::NodePtr>> expanded;  // PROTO instances' bodies the shapes live in
};

// Whether FTransform `group` is `top` or lies under it (-1: a shape outside every FTransform).
bool inside_group(const SceneModel& m, int group, int top);

// Builds the model. Every script is compiled with diagnostics at .wrl positions; returns false
// when there was any error.
bool build_scene_model(const vrml::Scene& scene, const ModelOptions& opts, frontend::DiagnosticSink& diag,
                       SceneModel& out);

}  // namespace fscript::scene
