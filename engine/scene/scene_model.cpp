// Building the scene model: a walk over the scene graph that carries the Transform matrix and
// the enclosing FTransform, compiling each FVRML node's scripts and evaluating its time.
#include "engine/scene/scene_model.h"

#include <cstdio>
#include <algorithm>
#include <cmath>
#include <map>

#include "frontend/fscript/embedded.h"
#include "frontend/fscript/entry.h"
#include "frontend/vrml/instantiate.h"
#include "engine/driver/driver.h"

namespace fscript::scene {

const char* kind_name(ShapeKind k) {
  switch (k) {
    case ShapeKind::Implicit: return "implicit";
    case ShapeKind::Curve: return "parametric curve";
    case ShapeKind::Surface: return "parametric surface";
    case ShapeKind::Solid: return "parametric solid";
  }
  return "implicit";
}

void LazyGradient::build() const {
  std::call_once(once_, [this] {
    std::unique_ptr<ir::Module> g = driver::gradient_ir(*module_);
    if (!g) return;
    kernel_ = driver::compile_gradient(*g, backend_, budgets_);
    const ir::Function& k = g->kernel_function();
    if (kernel_ && ir::interval_evaluable(k)) tape_ = std::make_unique<ir::IntervalTape>(k);
  });
}

const backends::Kernel* LazyGradient::get() const {
  build();
  return kernel_.get();
}

const ir::IntervalTape* LazyGradient::tape() const {
  build();
  return tape_.get();
}

Mat4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
  return r;
}

namespace {

Mat4 translate(const double v[3], double sign = 1) {
  Mat4 m = identity();
  for (int i = 0; i < 3; ++i) m[12 + i] = sign * v[i];
  return m;
}

Mat4 rotate(const double r[4], double sign = 1) {
  double x = r[0], y = r[1], z = r[2], a = sign * r[3];
  double len = std::sqrt(x * x + y * y + z * z);
  if (len == 0) return identity();
  x /= len, y /= len, z /= len;
  double c = std::cos(a), s = std::sin(a), t = 1 - c;
  return {t * x * x + c,
          t * x * y + s * z,
          t * x * z - s * y,
          0,
          t * x * y - s * z,
          t * y * y + c,
          t * y * z + s * x,
          0,
          t * x * z + s * y,
          t * y * z - s * x,
          t * z * z + c,
          0,
          0,
          0,
          0,
          1};
}

Mat4 scale(const double v[3]) {
  Mat4 m = identity();
  m[0] = v[0], m[5] = v[1], m[10] = v[2];
  return m;
}

}  // namespace

Mat4 vrml_transform(const double t[3], const double r[4], const double s[3], const double sr[4], const double c[3]) {
  Mat4 m = translate(t);
  m = multiply(m, translate(c));
  m = multiply(m, rotate(r));
  m = multiply(m, rotate(sr));
  m = multiply(m, scale(s));
  m = multiply(m, rotate(sr, -1));
  return multiply(m, translate(c, -1));
}

double field_number(const vrml::Node& n, const char* field, size_t k, double fallback) {
  const vrml::Value* v = n.get(field);
  return v && v->nums.size() > k ? v->nums[k] : fallback;
}

Mat4 transform_matrix(const vrml::Node& n) {
  double t[3], r[4], s[3], sr[4], c[3];
  for (int i = 0; i < 3; ++i) {
    t[i] = field_number(n, "translation", i);
    s[i] = field_number(n, "scale", i, 1);
    c[i] = field_number(n, "center", i);
  }
  for (int i = 0; i < 4; ++i) {
    r[i] = field_number(n, "rotation", i);
    sr[i] = field_number(n, "scaleOrientation", i);
  }
  return vrml_transform(t, r, s, sr, c);
}

TimeSensorFields time_fields(const vrml::Node& n) {
  return {field_number(n, "startTime"), field_number(n, "stopTime"), field_number(n, "cycleInterval", 0, 1),
          field_number(n, "loop") != 0, field_number(n, "enabled", 0, 1) != 0};
}

namespace {

// A field's number as a message shows it.
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
// A count of points as a message shows it: three digits are enough to compare it with a limit.
std::string count_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
std::string str(const vrml::Node& n, const char* field) {
  const vrml::Value* v = n.get(field);
  return v && !v->strs.empty() ? v->strs[0] : "";
}
const vrml::Node* child(const vrml::Node& n, const char* field) {
  const vrml::Value* v = n.get(field);
  return v && !v->nodes.empty() ? v->nodes[0].get() : nullptr;
}

enum class Role { Geometry, Point, Operation };

class Builder {
 public:
  Builder(const vrml::Scene& s, const ModelOptions& o, frontend::DiagnosticSink& d, SceneModel& out)
      : scene_(s), opts_(o), diag_(d), out_(out) {}

  bool run() {
    size_t before = diag_.error_count();
    for (const auto& r : scene_.roots) walk(r.get(), identity(), -1, 0);
    return diag_.error_count() == before;
  }

 private:
  // The file a node was read from (an Inline's, or the scene's).
  const frontend::SourceFile& file_of(const vrml::Node& n) const { return vrml::file_of(scene_, n); }
  const std::vector<std::string>& lines_of(const frontend::SourceFile& f) {
    auto [it, fresh] = lines_.try_emplace(&f);
    if (fresh) it->second = frontend::split_lines(f.text());
    return it->second;
  }

  // ---- scripts ----
  // Compiles the script of `field` of `n`; false (with diagnostics) on error or if absent.
  bool compile(const vrml::Node& n, const char* field, Role role, CompiledField& out, bool* implicit = nullptr,
               const std::vector<std::string>& extra = {}) {
    const vrml::FieldSlot* slot = n.slot(field);
    const vrml::Value* v = n.get(field);
    if (!v || v->type != vrml::FieldType::SFString || v->strs.empty() ||
        v->strs[0].find_first_not_of(" \t\r\n") == std::string::npos)
      return false;
    const frontend::SourceFile& from = file_of(n);
    frontend::LineCol lc = slot ? from.position(v->str_spans[0].begin) : frontend::LineCol{n.span.begin, 1};
    auto file = std::make_unique<frontend::SourceFile>(from.path(), v->strs[0], lc.line, lc.col);
    file->set_outer_lines(lines_of(from));
    auto entry = [&](const frontend::SemaResult& sema, frontend::KernelSpec& spec, std::string& err) {
      bool ok = role == Role::Point ? frontend::point_spec(sema, spec, out.rgb, err)
          : role == Role::Operation ? frontend::named_inputs_spec(sema, operation_inputs(), spec, err)
                                    : frontend::default_spec(sema, spec, err);
      if (implicit) *implicit = sema.entry.frep >= 0 || sema.form == frontend::ScriptForm::Expression;
      if (ok && role == Role::Geometry && !*implicit) ok = geometry_outputs(sema, spec, err);
      return ok;
    };
    driver::Compiled c;
    driver::Outcome r = driver::compile(std::move(file), entry, options(extra), diag_, c);
    if (r.stage == driver::Stage::Source) return false;
    if (!r.ok()) {
      std::string what = r.stage == driver::Stage::Entry ? "'" + std::string(field) + "' of " + n.type + ": "
                                                         : "cannot compile '" + std::string(field) + "': ";
      diag_.error(*c.script.file, {0, 1}, what + r.error);
      return false;
    }
    keep(c, out);
    if (role == Role::Geometry && implicit && *implicit && c.module)
      out.gradient =
          std::make_shared<const LazyGradient>(std::move(c.module), opts_.compile.backend, opts_.compile.budgets);
    out.field = field;
    return true;
  }

  // Whether the optimised module reads input `name`: the kernel's parameter, or a global it sets.
  static bool reads_input(const driver::Compiled& c, const char* name) {
    const auto& names = c.spec.input_names;
    size_t k = static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    if (k == names.size()) return false;
    if (!c.module) return true;
    const auto& slots = k < c.spec.input_globals.size() ? c.spec.input_globals[k] : std::vector<int>{};
    for (const auto& fn : c.module->functions)
      for (const auto& b : fn->blocks)
        for (const ir::Inst* i : b->insts) {
          if (i->op == ir::Op::GLoad && std::find(slots.begin(), slots.end(), i->aux) != slots.end()) return true;
          if (fn.get() == &c.module->kernel_function())
            for (const ir::Inst* a : i->args)
              if (a->op == ir::Op::Param && a->aux == static_cast<int32_t>(k)) return true;
        }
    return false;
  }

  // The kernel, and its interval tape for the polygonizer's octree.
  static void keep(driver::Compiled& c, CompiledField& out) {
    out.reads_t = reads_input(c, "t");
    out.kernel = std::move(c.kernel);
    if (c.module && ir::interval_evaluable(c.module->kernel_function()))
      out.intervals = std::make_shared<const ir::IntervalTape>(c.module->kernel_function());
  }

  driver::CompileOptions options(const std::vector<std::string>& extra = {}) const {
    driver::CompileOptions o = opts_.compile;
    o.extra_globals = extra;
    return o;
  }

  // An affine field written as FScript components ("0.5*t, 0, 0"): one kernel per component.
  bool affine(const vrml::Node& n, const char* field, double fraction, std::vector<CompiledField>& out) {
    const vrml::Value* v = n.get(field);
    if (!v || v->type != vrml::FieldType::SFString || v->strs.empty() || !n.slot(field)) return false;
    frontend::EmbeddedScript whole;
    whole.field = field;
    whole.text = v->strs[0];
    frontend::LineCol lc = file_of(n).position(v->str_spans[0].begin);
    whole.line = lc.line;
    whole.col = lc.col;
    size_t want =
        std::string(field).find("otation") != std::string::npos || std::string(field) == "scaleOrientation" ? 4 : 3;
    auto parts = frontend::split_components(whole);
    if (parts.size() != want) {
      auto file = std::make_unique<frontend::SourceFile>(file_of(n).path(), whole.text, whole.line, whole.col);
      file->set_outer_lines(lines_of(file_of(n)));
      diag_.error(*file, {0, 1},
                  "'" + std::string(field) + "' of FTransform needs " + std::to_string(want) + " components, found " +
                      std::to_string(parts.size()));
      return false;
    }
    for (const auto& p : parts) {
      CompiledField c;
      if (!compile_text(n, p, c)) return false;
      set_time(c, n, fraction);
      out.push_back(std::move(c));
    }
    return true;
  }

  bool compile_text(const vrml::Node& n, const frontend::EmbeddedScript& e, CompiledField& out) {
    auto file = std::make_unique<frontend::SourceFile>(file_of(n).path(), e.text, e.line, e.col);
    file->set_outer_lines(lines_of(file_of(n)));
    auto entry = [&](const frontend::SemaResult& sema, frontend::KernelSpec& spec, std::string& err) {
      return frontend::point_spec(sema, spec, out.rgb, err);
    };
    driver::Compiled c;
    driver::Outcome r = driver::compile(std::move(file), entry, options(), diag_, c);
    if (r.stage == driver::Stage::Source) return false;
    if (!r.ok()) {
      diag_.error(*c.script.file, {0, 1},
                  r.stage == driver::Stage::Entry ? r.error : "cannot compile '" + e.field + "': " + r.error);
      return false;
    }
    keep(c, out);
    out.field = e.field;
    return true;
  }

  static std::vector<std::string> operation_inputs() {
    std::vector<std::string> names = {"f", "g"};
    for (int k = 1; k <= kMaxOperands; ++k) names.push_back("f" + std::to_string(k));
    names.push_back("t");
    return names;
  }

  // A parametric geometry kernel returns exactly x, y, z (an assignment list may set only some).
  static bool geometry_outputs(const frontend::SemaResult& s, frontend::KernelSpec& spec, std::string& err) {
    if (s.form != frontend::ScriptForm::Assignments) return true;
    spec.outputs.clear();
    for (const char* n : {"x", "y", "z"}) {
      frontend::KernelOutput o;
      o.name = n;
      o.global = s.global_slot(n);
      spec.outputs.push_back(o);
    }
    (void)err;
    return true;
  }

  // ---- time ----
  // The fraction of a node with TimeSensor fields (FShape, FTransform): --fraction, else an
  // external TimeSensor routed to set_fraction, else its own sensor (restarted by a routed cycleTime).
  TimeSensorState time_of(const vrml::Node& n) {
    if (opts_.fraction) {
      TimeSensorState s;
      s.ever_active = true;
      s.fraction = *opts_.fraction;
      return s;
    }
    TimeSensorFields own = time_fields(n);
    if (&file_of(n) != scene_.file.get())
      return evaluate_time_sensor(own, opts_.now);  // an Inline's file: its own names
    for (const auto& r : scene_.routes) {
      if (r.to_node != n.def_name || n.def_name.empty()) continue;
      auto src = scene_.defs.find(r.from_node);
      if (src == scene_.defs.end() || src->second->type != "TimeSensor") continue;
      TimeSensorState ext = evaluate_time_sensor(time_fields(*src->second), opts_.now);
      if (r.to_field == "set_fraction" && r.from_field == "fraction_changed") return ext;
      if ((r.to_field == "startTime" || r.to_field == "set_startTime") && r.from_field == "cycleTime" &&
          ext.ever_active)
        own.start_time = ext.cycle_time;
    }
    return evaluate_time_sensor(own, opts_.now);
  }

  void set_time(CompiledField& f, const vrml::Node& n, double fraction) {
    f.span0 = field_number(n, "timeSpan", 0, 0);
    f.span1 = field_number(n, "timeSpan", 1, 1);
    f.t = node_time(fraction, f.span0, f.span1);
  }

  // A node's `frames` (how many an animation of it is made of), refused over kMaxFrames.
  int frames_of(const vrml::Node& n) {
    double f = field_number(n, "frames");
    if (f <= kMaxFrames) return static_cast<int>(f);
    const vrml::FieldSlot* at = n.slot("frames");
    diag_.error(file_of(n), at ? at->span : n.span,
                "frames " + number_text(f) + " is over the limit of " + std::to_string(kMaxFrames) + " for one node");
    return 0;
  }

  // ---- walk ----
  void walk(const vrml::Node* n, const Mat4& m, int group, int depth) {
    if (!n || too_large_) return;
    if (++walked_ > kMaxExpandedNodes || depth > kMaxExpandedDepth) {
      too_large_ = true;
      diag_.error(file_of(*n), n->span,
                  walked_ > kMaxExpandedNodes ? "the scene expands to more than " + std::to_string(kMaxExpandedNodes) +
                          " nodes (every PROTO instance and every USE counted again); refused"
                                              : "nodes nested more than " + std::to_string(kMaxExpandedDepth) +
                          " deep through PROTO instances (PROTOs whose bodies are instances of PROTOs); refused");
      return;
    }
    if (n->type == "FShape") return shape(*n, m, group);
    if (n->type == "FTransform") return ftransform(*n, m, group, depth);
    if (n->proto) {  // a user PROTO: its first body node is what the instance is (VRML97 4.8.3)
      auto body = vrml::instantiate(*n);
      if (!body.empty()) {
        const vrml::Node* first = body.front().get();
        expanded_.push_back(std::move(body));  // kept alive: shapes point into it
        walk(first, m, group, depth + 1);
      }
      return;
    }
    if (n->type == "Inline") {  // a local file's nodes (vrml::load_inlines), in the Inline's frame
      for (const auto& c : n->inlined) walk(c.get(), m, group, depth + 1);
      return;
    }
    Mat4 here = m;
    if (n->type == "Transform") here = multiply(m, transform_matrix(*n));
    for (const char* f : {"children", "choice", "level"})
      if (const vrml::Value* v = n->get(f))
        for (const auto& c : v->nodes) walk(c.get(), here, group, depth + 1);
  }

  void ftransform(const vrml::Node& n, const Mat4& m, int parent, int depth) {
    Group g;
    g.node = &n;
    g.parent = parent;
    g.operation = str(n, "operation");
    g.type = str(n, "type");
    TimeSensorState ts = time_of(n);
    g.fraction = ts.fraction;
    frames_of(n);  // checked here; fvrml-run reads it when it animates the group
    int index = static_cast<int>(out_.groups.size());
    if (g.type == "analytical") {
      CompiledField f;
      std::vector<std::string> extra = operation_inputs();
      extra.pop_back();  // t is a standard global already
      if (compile(n, "operation", Role::Operation, f, nullptr, extra)) {
        set_time(f, n, ts.fraction);
        g.op_kernel = std::move(f);
      }
    }
    for (const char* f : {"translation", "rotation", "scale", "scaleOrientation", "center"}) {
      std::vector<CompiledField> parts;
      if (affine(n, f, ts.fraction, parts)) g.affine.push_back({f, std::move(parts)});
    }
    out_.groups.push_back(std::move(g));
    if (parent >= 0) {
      out_.groups[parent].groups.push_back(index);
      out_.groups[parent].children.push_back({true, index});
    }
    if (const vrml::Value* v = n.get("children"))
      for (const auto& c : v->nodes) walk(c.get(), m, index, depth + 1);
  }

  void shape(const vrml::Node& n, const Mat4& m, int group) {
    Shape s;
    s.fshape = &n;
    s.group = group;
    s.transform = m;
    s.time = time_of(n);
    s.fraction = s.time.fraction;
    s.frames = frames_of(n);
    const vrml::Node* geo = child(n, "geometry");
    if (!geo || geo->type != "FGeometry") {
      diag_.warning(file_of(n), n.span, "FShape without an FGeometry: nothing to draw");
      return;
    }
    s.geometry_node = geo;
    bool implicit = true;
    if (!compile(*geo, "definition", Role::Geometry, s.geometry, &implicit)) {
      if (!geo->get("definition") || str(*geo, "definition").find_first_not_of(" \t\r\n") == std::string::npos)
        diag_.error(file_of(*geo), geo->span, "FGeometry has an empty definition");
      return;
    }
    set_time(s.geometry, *geo, s.fraction);
    std::string type = str(*geo, "type");
    if (type == "implicit") implicit = true;
    if (type == "parametric") implicit = false;
    resolve_domain(s, *geo, implicit);
    appearance(s, child(n, "appearance"));
    if (group >= 0) {
      out_.groups[group].shapes.push_back(static_cast<int>(out_.shapes.size()));
      out_.groups[group].children.push_back({false, static_cast<int>(out_.shapes.size())});
    }
    out_.shapes.push_back(std::move(s));
  }

  // A shape is refused by what one frame costs (shape_cost.h): the points it evaluates, by its own
  // dimension, and the memory they need; NaN and infinite resolutions too, before any work.
  bool within_cost(ShapeKind kind, const std::array<double, 3>& r, const vrml::Node& geo) {
    ShapeCost c = shape_cost(kind, r);
    double max_samples = kind == ShapeKind::Implicit ? kMaxShapeSamples : kMaxParametricSamples;
    double memory = memory_limit_bytes(opts_.max_memory_mib);
    std::string why;
    if (!(c.samples <= max_samples))
      why = "asks for " + count_text(c.samples) + " sample points, over the limit of " + count_text(max_samples) +
          " for one shape";
    else if (!(c.bytes <= memory))
      why = "needs about " + bytes_text(c.bytes) + " of memory (" + count_text(c.samples) +
          " sample points), over the " + bytes_text(memory) + " of --max-memory";
    if (why.empty()) return true;
    int used = kind == ShapeKind::Curve ? 1 : kind == ShapeKind::Surface ? 2 : 3;
    std::string text = "resolution [";
    char num[32];
    for (int k = 0; k < used; ++k) std::snprintf(num, sizeof num, "%s%.10g", k ? " " : "", r[k]), text += num;
    text += "]";
    if (opts_.resolution_scale != 1) text += " (after --resolution-scale " + number_text(opts_.resolution_scale) + ")";
    text += std::string(" of this ") + (kind == ShapeKind::Implicit ? "implicit shape" : kind_name(kind)) + " " + why;
    const vrml::FieldSlot* at = geo.slot("resolution");
    diag_.error(file_of(geo), at ? at->span : geo.span, text);
    return false;
  }

  void resolve_domain(Shape& s, const vrml::Node& geo, bool implicit) {
    const vrml::Value* res = geo.get("resolution");
    size_t dims = res ? res->nums.size() : 3;
    std::array<double, 3> scaled;
    for (int k = 0; k < 3; ++k) {
      double r = res && !res->nums.empty() ? res->nums[std::min<size_t>(k, res->nums.size() - 1)] : 50;
      scaled[k] = r * opts_.resolution_scale;
    }
    std::string poly = s.fshape ? str(*s.fshape, "polygonizer") : "";
    s.kind = implicit                               ? ShapeKind::Implicit
        : (dims <= 1 || poly == "analytical_curve") ? ShapeKind::Curve
        : dims == 2                                 ? ShapeKind::Surface
                                                    : ShapeKind::Solid;
    bool refused = !within_cost(s.kind, scaled, geo);
    for (int k = 0; k < 3; ++k)
      s.resolution[k] = refused ? 1 : std::max(1, static_cast<int>(std::lround(std::min(scaled[k], 2e9))));
    if (implicit) {
      if (const vrml::FieldSlot* unused = geo.slot("parameters"); unused && unused->is_ref.empty())
        diag_.warning(file_of(geo), unused->span,
                      "'parameters' is not used by an implicit shape (its box is bboxCenter and bboxSize); it "
                      "bounds u, v, w of a parametric one");
      for (int k = 0; k < 3; ++k) {
        double c = field_number(geo, "bboxCenter", k), size = field_number(geo, "bboxSize", k, 10);
        s.domain[2 * k] = c - size / 2;
        s.domain[2 * k + 1] = c + size / 2;
      }
      return;
    }
    // Parametric children of an FTransform share its parameters when they give none themselves.
    const vrml::Value* p = geo.slot("parameters") ? geo.get("parameters") : nullptr;
    for (int g = s.group; !p && g >= 0; g = out_.groups[g].parent)
      if (out_.groups[g].node->slot("parameters")) p = out_.groups[g].node->get("parameters");
    for (int k = 0; k < 3; ++k) {
      // A parameter beyond the given pairs takes the lower bound of its pair (0 without one).
      bool have_pair = p && p->nums.size() >= static_cast<size_t>(2 * k + 2);
      bool have_lo = p && p->nums.size() >= static_cast<size_t>(2 * k + 1);
      s.domain[2 * k] = have_lo ? p->nums[2 * k] : 0;
      s.domain[2 * k + 1] = have_pair ? p->nums[2 * k + 1] : s.domain[2 * k];
      int shape_dims = s.kind == ShapeKind::Curve ? 1 : s.kind == ShapeKind::Surface ? 2 : 3;
      if (k >= shape_dims) s.domain[2 * k + 1] = s.domain[2 * k];
    }
  }

  void appearance(Shape& s, const vrml::Node* app) {
    if (!app) return;
    if (const vrml::Node* mat = child(*app, "material"); mat && mat->type == "FMaterial") {
      s.material_node = mat;
      CompiledField c;
      if (compile(*mat, "diffuseColor", Role::Point, c)) {
        set_time(c, *mat, s.fraction);
        s.colour = std::move(c);
      }
      for (const char* f : {"ambientIntensity", "emissiveColor", "shininess", "specularColor", "transparency"}) {
        CompiledField o;
        if (compile(*mat, f, Role::Point, o)) {
          set_time(o, *mat, s.fraction);
          s.material.push_back(std::move(o));
        }
      }
    }
    if (const vrml::Node* tex = child(*app, "texture3D"); tex && tex->type == "FTexture3D") {
      CompiledField c;
      if (compile(*tex, "definition", Role::Point, c)) {
        set_time(c, *tex, s.fraction);
        s.texture = std::move(c);
      }
    }
  }

  const vrml::Scene& scene_;
  const ModelOptions& opts_;
  frontend::DiagnosticSink& diag_;
  SceneModel& out_;
  std::map<const frontend::SourceFile*, std::vector<std::string>> lines_;  // per file, for carets
  std::vector<std::vector<vrml::NodePtr>>& expanded_ = out_.expanded;
  size_t walked_ = 0;  // nodes visited, PROTO bodies and USEs included (kMaxExpandedNodes)
  bool too_large_ = false;
};

}  // namespace

ShapeCost shape_cost(const Shape& s) {
  return shape_cost(s.kind, {double(s.resolution[0]), double(s.resolution[1]), double(s.resolution[2])});
}

bool build_scene_model(const vrml::Scene& scene, const ModelOptions& opts, frontend::DiagnosticSink& diag,
                       SceneModel& out) {
  return Builder(scene, opts, diag, out).run();
}

bool inside_group(const SceneModel& m, int group, int top) {
  for (int g = group; g >= 0; g = m.groups[static_cast<size_t>(g)].parent)
    if (g == top) return true;
  return false;
}

}  // namespace fscript::scene
