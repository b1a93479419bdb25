// Scene fields. Set operations fold left over the children: union max, intersection min,
// subtraction min(f, -g), blends f + g +- sqrt(f^2 + g^2) + a0 / (1 + (f/a1)^2 + (g/a2)^2).
// An FTransform's affine matrix M moves its result: implicit children are evaluated at M^-1 p,
// parametric results are mapped by M.
#include "engine/scene/shape_field.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "engine/driver/driver.h"
#include "engine/mesh/local_field.h"
#include "runtime/math/math.h"
#include "runtime/support/scratch.h"

namespace fscript::scene {

ShapeField::ShapeField(const Shape& s, double fraction)
    : s_(s), geometry_t_(node_time(fraction, s.geometry.span0, s.geometry.span1)),
      texture_t_(s.texture ? node_time(fraction, s.texture->span0, s.texture->span1) : 0) {}

bool ShapeField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                      backends::RuntimeError& err) const {
  mesh::KernelField geometry(*s_.geometry.kernel, static_cast<float>(geometry_t_));
  if (!geometry.eval(x, y, z, n, out, err)) return false;
  if (!s_.texture) return true;
  // Displacement texture: the point kernel (x, y, z, u, v, w, t) -> d, added to f.
  std::vector<float> t(n, static_cast<float>(texture_t_));
  std::vector<float> d(n), r(n), g(n), b(n);
  const float* in[7] = {x, y, z, x, y, z, t.data()};
  float* outs[4] = {d.data(), r.data(), g.data(), b.data()};
  if (!s_.texture->kernel->eval_batch(in, outs, n, err)) return false;
  for (size_t i = 0; i < n; ++i) out[i] += d[i];
  return true;
}

bool ShapeField::eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                           backends::RuntimeError& err) const {
  if (s_.texture) return Field::eval_rows(x, count, y, z, rows, out, err);  // the texture takes points
  mesh::KernelField geometry(*s_.geometry.kernel, static_cast<float>(geometry_t_));
  return geometry.eval_rows(x, count, y, z, rows, out, err);
}

math::Interval ShapeField::bound(const mesh::Box3& b) const {
  if (!can_bound()) return math::Interval::everything();
  math::Interval f =
      mesh::kernel_bound(*s_.geometry.intervals, b, {math::Interval::point(static_cast<float>(geometry_t_))});
  if (!s_.texture) return f;
  std::vector<math::Interval> uvw_t;  // the texture sees (x, y, z, u, v, w, t) with u, v, w = x, y, z
  for (int a = 0; a < 3; ++a) uvw_t.push_back({b.lo[a], b.hi[a], false});
  uvw_t.push_back(math::Interval::point(static_cast<float>(texture_t_)));
  return math::iv::add(f, mesh::kernel_bound(*s_.texture->intervals, b, uvw_t));
}

bool ShapeField::has_gradient() const { return !s_.texture && s_.geometry.gradient && s_.geometry.gradient->get(); }

bool ShapeField::eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                               backends::RuntimeError& err) const {
  mesh::KernelField geometry(*s_.geometry.kernel, static_cast<float>(geometry_t_), nullptr,
                             s_.geometry.gradient->get());
  return geometry.eval_gradient(x, y, z, n, out, err);
}

ShapeField::~ShapeField() = default;

const ir::IntervalTape* ShapeField::value_tape() const { return s_.texture ? nullptr : s_.geometry.intervals.get(); }

const ir::IntervalTape* ShapeField::gradient_tape() const {
  return has_gradient() ? s_.geometry.gradient->tape() : nullptr;
}

const mesh::LocalTapes* ShapeField::tapes() const {
  if (s_.texture || !s_.geometry.intervals) return nullptr;
  std::call_once(local_once_, [this] {
    mesh::GradientTape gradient;
    if (has_gradient()) gradient = [this] { return s_.geometry.gradient->tape(); };
    local_ = std::make_unique<mesh::LocalTapes>(*s_.geometry.intervals, static_cast<float>(geometry_t_),
                                                std::move(gradient));
  });
  return local_.get();
}

std::shared_ptr<const mesh::Field> ShapeField::local(const mesh::Box3& b) const {
  const mesh::LocalTapes* t = tapes();
  return t ? t->at(b) : nullptr;
}

void ShapeField::bounds(const mesh::Box3* boxes, size_t n, math::Interval* out) const {
  if (s_.texture || !s_.geometry.intervals) return Field::bounds(boxes, n, out);
  mesh::tape_bounds(*s_.geometry.intervals, static_cast<float>(geometry_t_), boxes, n, out);
}

void ShapeField::bounds_and_locals(const mesh::Box3* boxes, size_t n, math::Interval* out,
                                   const mesh::WantsLocal& wants, std::shared_ptr<const mesh::Field>* locals) const {
  if (const mesh::LocalTapes* t = tapes()) return t->bounds_and_locals(boxes, n, out, wants, locals);
  Field::bounds_and_locals(boxes, n, out, wants, locals);
}

void ShapeField::expect_points(uint64_t points) const {
  if (s_.geometry.kernel) s_.geometry.kernel->expect_points(points);
}

bool ShapeField::can_bound() const { return s_.geometry.intervals && (!s_.texture || s_.texture->intervals); }

namespace {

// The components of one affine field: compiled FScript (evaluated at t, the point kernel's value),
// numbers, or the default.
bool affine_values(const Group& g, const char* field, size_t count, const double* fallback, double* out,
                   backends::RuntimeError& err) {
  for (const auto& [name, parts] : g.affine) {
    if (name != field) continue;
    for (size_t k = 0; k < count; ++k) {
      if (k >= parts.size()) {
        out[k] = fallback[k];
        continue;
      }
      float zero = 0, t = static_cast<float>(parts[k].t), o[4] = {0, 0, 0, 0};
      const float* in[7] = {&zero, &zero, &zero, &zero, &zero, &zero, &t};
      float* outs[4] = {&o[0], &o[1], &o[2], &o[3]};
      if (!parts[k].kernel->eval_batch(in, outs, 1, err)) return false;
      out[k] = o[0];
    }
    return true;
  }
  const vrml::Value* v = g.node->get(field);
  bool numbers = v && v->type != vrml::FieldType::SFString;
  for (size_t k = 0; k < count; ++k) out[k] = numbers && v->nums.size() > k ? v->nums[k] : fallback[k];
  return true;
}

void apply(const Mat4& m, float& x, float& y, float& z) {
  double p[3] = {x, y, z}, q[3];
  for (int r = 0; r < 3; ++r) q[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
  x = static_cast<float>(q[0]), y = static_cast<float>(q[1]), z = static_cast<float>(q[2]);
}

// The box holding m p (computed in double, rounded to float) for every p of b: the corners' hull in
// double, widened far beyond double rounding, then rounded outward to float.
mesh::Box3 moved_box(const Mat4& m, const mesh::Box3& b) {
  mesh::Box3 out;
  for (int r = 0; r < 3; ++r) {
    double lo = m[12 + r], hi = m[12 + r], size = std::fabs(m[12 + r]);
    for (int a = 0; a < 3; ++a) {
      double p = m[4 * a + r] * b.lo[a], q = m[4 * a + r] * b.hi[a];
      lo += std::min(p, q), hi += std::max(p, q), size += std::max(std::fabs(p), std::fabs(q));
    }
    lo -= 1e-9 * size, hi += 1e-9 * size;
    float flo = static_cast<float>(lo), fhi = static_cast<float>(hi);
    out.lo[r] = static_cast<double>(flo) > lo ? std::nextafter(flo, -INFINITY) : flo;
    out.hi[r] = static_cast<double>(fhi) < hi ? std::nextafter(fhi, INFINITY) : fhi;
  }
  return out;
}

// f + g +- sqrt(f^2 + g^2) + a0 / (1 + (f/a1)^2 + (g/a2)^2) as eval computes it (in double, then
// rounded to float). The first part rises with f and with g (its partial derivatives are
// 1 +- f / sqrt(f^2 + g^2) >= 0), so its corners bound it exactly, where interval arithmetic
// would lose the link between f and sqrt(f^2 + g^2) and bound nothing; the bump lies between its
// values at the largest and the smallest squares. Widened far beyond the rounding of eval (f + g is
// summed in float, the rest in double).
math::Interval blend_bound(math::Interval f, math::Interval g, double sign, double a0, double a1, double a2) {
  if (f.empty() || g.empty()) return math::Interval::nan_only();
  double fl = f.lo, fh = f.hi, gl = g.lo, gh = g.hi;
  if (!std::isfinite(fl) || !std::isfinite(fh) || !std::isfinite(gl) || !std::isfinite(gh) || a1 == 0 || a2 == 0)
    return math::Interval::everything();
  auto part = [sign](double x, double y) { return x + y + sign * std::sqrt(x * x + y * y); };
  auto squares = [](double lo, double hi, double a) {  // the range of (v / a)^2 for v in [lo, hi]
    double p = (lo / a) * (lo / a), q = (hi / a) * (hi / a);
    return std::pair<double, double>{lo <= 0 && hi >= 0 ? 0 : std::min(p, q), std::max(p, q)};
  };
  auto [f2lo, f2hi] = squares(fl, fh, a1);
  auto [g2lo, g2hi] = squares(gl, gh, a2);
  double b1 = a0 / (1 + f2hi + g2hi), b2 = a0 / (1 + f2lo + g2lo);
  double lo = part(fl, gl) + std::min(b1, b2), hi = part(fh, gh) + std::max(b1, b2);
  double slack = 1e-6 * (3 * std::max({std::fabs(fl), std::fabs(fh), std::fabs(gl), std::fabs(gh)}) + std::fabs(a0));
  if (!std::isfinite(lo) || !std::isfinite(hi)) return math::Interval::everything();
  return {std::nextafter(static_cast<float>(lo - slack), -INFINITY),
          std::nextafter(static_cast<float>(hi + slack), INFINITY), f.nan || g.nan};
}

}  // namespace

bool group_matrix(const Group& g, Mat4& out, backends::RuntimeError& err) {
  static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1}, no_turn[4] = {0, 0, 1, 0};
  double t[3], r[4], s[3], sr[4], c[3];
  if (!affine_values(g, "translation", 3, zero, t, err) || !affine_values(g, "rotation", 4, no_turn, r, err) ||
      !affine_values(g, "scale", 3, one, s, err) || !affine_values(g, "scaleOrientation", 4, no_turn, sr, err) ||
      !affine_values(g, "center", 3, zero, c, err))
    return false;
  out = vrml_transform(t, r, s, sr, c);
  return true;
}

bool invert_affine(const Mat4& m, Mat4& out) {
  // m[col * 4 + row]; the 3x3 part [[a b c] [d e f] [g h i]] by its adjugate.
  double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], i = m[10];
  double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  if (!std::isfinite(det) || std::fabs(det) < 1e-300) return false;
  double inv[3][3] = {{(e * i - f * h) / det, -(b * i - c * h) / det, (b * f - c * e) / det},
                      {-(d * i - f * g) / det, (a * i - c * g) / det, -(a * f - c * d) / det},
                      {(d * h - e * g) / det, -(a * h - b * g) / det, (a * e - b * d) / det}};
  out = identity();
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) out[col * 4 + r] = inv[r][col];
    out[12 + r] = -(inv[r][0] * m[12] + inv[r][1] * m[13] + inv[r][2] * m[14]);
  }
  return true;
}

namespace {

// The children of an FTransform as fields (Self: GroupField or GroupParametric): a nested
// FTransform recursively, a shape through `leaf`. Every shape below goes to `shapes`, a problem to
// `invalid`; `implicit` is the kind of shape the group takes.
template <typename Self, typename Kid, typename Leaf>
void gather_children(const SceneModel& m, const Group& g, bool implicit, std::vector<std::unique_ptr<Kid>>& kids,
                     std::vector<const Shape*>& shapes, std::string& invalid, Leaf leaf) {
  for (auto [is_group, index] : g.children) {
    if (is_group) {
      auto f = std::make_unique<Self>(m, index);
      std::string why;
      if (!f->valid(why)) invalid = why;
      shapes.insert(shapes.end(), f->shapes().begin(), f->shapes().end());
      kids.push_back(std::move(f));
    } else {
      const Shape& s = m.shapes[index];
      if ((s.kind == ShapeKind::Implicit) != implicit)
        invalid = "an FTransform cannot mix implicit and parametric children";
      shapes.push_back(&s);
      kids.push_back(leaf(s));
    }
  }
  if (kids.empty()) invalid = "an FTransform without FShape children";
}

}  // namespace

GroupField::GroupField(const SceneModel& m, int group) : m_(m), g_(m.groups[group]) {
  backends::RuntimeError err;
  if (!group_matrix(g_, matrix_, err)) invalid_ = "the FTransform's affine fields: " + err.message;
  else if (!invert_affine(matrix_, inverse_)) invalid_ = "the FTransform's scale is zero: it has no volume";
  moved_ = matrix_ != identity();
  gather_children<GroupField>(m, g_, true, kids_, shapes_, invalid_,
                              [](const Shape& s) { return std::make_unique<ShapeField>(s); });
}

void GroupField::part_tapes(bool gradient, std::vector<const ir::IntervalTape*>& out) const {
  for (const auto& k : kids_) k->part_tapes(gradient, out);
  if (!gradient && g_.op_kernel && g_.op_kernel->intervals) out.push_back(g_.op_kernel->intervals.get());
}

bool GroupField::valid(std::string& why) const {
  why = invalid_;
  return invalid_.empty();
}

std::array<double, 6> GroupField::box() const {
  std::array<double, 6> b = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  auto grow = [&b](const std::array<double, 6>& d) {
    for (int a = 0; a < 3; ++a)
      b[2 * a] = std::min(b[2 * a], d[2 * a]), b[2 * a + 1] = std::max(b[2 * a + 1], d[2 * a + 1]);
  };
  size_t k = 0;
  for (auto [is_group, index] : g_.children) {  // nested boxes come back in this group's frame
    if (k >= kids_.size()) break;
    grow(is_group ? static_cast<const GroupField&>(*kids_[k]).box() : m_.shapes[index].domain);
    ++k;
  }
  if (!moved_ || b[0] > b[1]) return b;
  std::array<double, 6> moved = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (int corner = 0; corner < 8; ++corner) {
    float p[3] = {float(b[corner & 1]), float(b[2 + ((corner >> 1) & 1)]), float(b[4 + ((corner >> 2) & 1)])};
    apply(matrix_, p[0], p[1], p[2]);
    for (int a = 0; a < 3; ++a)
      moved[2 * a] = std::min(moved[2 * a], double(p[a])), moved[2 * a + 1] = std::max(moved[2 * a + 1], double(p[a]));
  }
  return moved;
}

std::array<int, 3> GroupField::cells() const {
  std::array<int, 3> c = {1, 1, 1};
  for (const Shape* s : shapes_)
    for (int a = 0; a < 3; ++a) c[a] = std::max(c[a], s->resolution[a]);
  return c;
}

const Shape* GroupField::first_shape() const { return shapes_.empty() ? nullptr : shapes_.front(); }

void GroupField::to_local(const float*& x, const float*& y, const float*& z, size_t n, float* room) const {
  if (!moved_) return;
  float *lx = room, *ly = room + n, *lz = room + 2 * n;
  std::copy_n(x, n, lx), std::copy_n(y, n, ly), std::copy_n(z, n, lz);
  for (size_t i = 0; i < n; ++i) apply(inverse_, lx[i], ly[i], lz[i]);
  x = lx, y = ly, z = lz;
}

bool GroupField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                      backends::RuntimeError& err) const {
  support::ScratchFloats room(moved_ ? 3 * n : 0);
  to_local(x, y, z, n, room.get());
  if (kids_.empty()) {  // an empty group holds nothing: outside everywhere
    std::fill_n(out, n, -1.0f);
    return true;
  }
  if (g_.op_kernel) return eval_operator(x, y, z, n, out, err);
  // The first child straight into out and the others into one buffer left uninitialised: zeroing
  // and copying per batch cost as much as the folds themselves.
  support::ScratchFloats rest(n * (kids_.size() - 1));
  auto vals = [&](size_t k) { return k == 0 ? out : rest.get() + n * (k - 1); };
  for (size_t k = 0; k < kids_.size(); ++k)
    if (!kids_[k]->eval(x, y, z, n, vals(k), err)) return false;
  fold(out, rest.get(), n);
  return true;
}

// Rows stay rows for the children unless the FTransform moves them (then they are points).
bool GroupField::eval_rows(const float* x, size_t count, const float* y, const float* z, size_t rows, float* out,
                           backends::RuntimeError& err) const {
  if (moved_ || kids_.empty() || g_.op_kernel) return Field::eval_rows(x, count, y, z, rows, out, err);
  size_t n = count * rows;
  support::ScratchFloats rest(n * (kids_.size() - 1));
  for (size_t k = 0; k < kids_.size(); ++k)
    if (!kids_[k]->eval_rows(x, count, y, z, rows, k == 0 ? out : rest.get() + n * (k - 1), err)) return false;
  fold(out, rest.get(), n);
  return true;
}

GroupField::SetOp GroupField::set_op() const {
  SetOp s;
  const std::string& op = g_.operation;
  s.kind = op == "intersection"                           ? SetOp::Intersection
      : op == "subtraction" || op == "difference"         ? SetOp::Subtraction
      : op == "blend_union" || op == "blend_intersection" ? SetOp::Blend
                                                          : SetOp::Union;  // and any unknown name, reported
  s.sign = op == "blend_union" ? 1 : -1;
  const vrml::Value* p = g_.node->get("parameters");
  s.a0 = p && p->nums.size() > 0 ? p->nums[0] : 0, s.a1 = p && p->nums.size() > 1 ? p->nums[1] : 1;
  s.a2 = p && p->nums.size() > 2 ? p->nums[2] : 1;
  return s;
}

void GroupField::fold(float* out, const float* rest, size_t n) const {
  auto vals = [&](size_t k) { return rest + n * (k - 1); };
  const SetOp op = set_op();
  for (size_t k = 1; k < kids_.size(); ++k) {
    const float* g = vals(k);
    if (op.kind == SetOp::Intersection) {
      for (size_t i = 0; i < n; ++i) out[i] = math::min(out[i], g[i]);
    } else if (op.kind == SetOp::Subtraction) {
      for (size_t i = 0; i < n; ++i) out[i] = math::min(out[i], -g[i]);
    } else if (op.kind == SetOp::Blend) {
      for (size_t i = 0; i < n; ++i) {
        float f = out[i], h = g[i];  // f + h is a float sum, the rest double
        double fa = f / op.a1, ga = h / op.a2;
        out[i] = static_cast<float>(f + h + op.sign * std::sqrt(double(f) * f + double(h) * h) +
                                    op.a0 / (1 + fa * fa + ga * ga));
      }
    } else {
      for (size_t i = 0; i < n; ++i) out[i] = math::max(out[i], g[i]);  // union (and any unknown name, reported)
    }
  }
}

bool GroupField::has_gradient() const {
  if (!invalid_.empty() || g_.op_kernel || kids_.empty()) return false;
  return std::all_of(kids_.begin(), kids_.end(), [](const auto& k) { return k->has_gradient(); });
}

bool GroupField::eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                               backends::RuntimeError& err) const {
  support::ScratchFloats room(moved_ ? 3 * n : 0);
  to_local(x, y, z, n, room.get());
  if (!kids_[0]->eval_gradient(x, y, z, n, out, err)) return false;
  support::ScratchFloats buf(4 * n);
  float* const g[4] = {buf.get(), buf.get() + n, buf.get() + 2 * n, buf.get() + 3 * n};
  for (size_t k = 1; k < kids_.size(); ++k) {
    if (!kids_[k]->eval_gradient(x, y, z, n, g, err)) return false;
    fold_gradient(out, g, n);
  }
  if (!moved_) return true;
  for (size_t i = 0; i < n; ++i) {  // d/dp_j = sum over i of d/dl_i dl_i/dp_j, with l = M^-1 p
    double l[3] = {out[1][i], out[2][i], out[3][i]};
    for (int j = 0; j < 3; ++j)
      out[1 + j][i] =
          static_cast<float>(l[0] * inverse_[4 * j] + l[1] * inverse_[4 * j + 1] + l[2] * inverse_[4 * j + 2]);
  }
  return true;
}

void GroupField::fold_gradient(float* const out[4], const float* const g[4], size_t n) const {
  const SetOp op = set_op();
  const double a0 = op.a0, a1 = op.a1, a2 = op.a2, sign = op.sign;
  const bool blend = op.kind == SetOp::Blend, subtract = op.kind == SetOp::Subtraction;
  for (size_t i = 0; i < n; ++i) {
    float f = out[0][i], h = subtract ? -g[0][i] : g[0][i];
    double hs = subtract ? -1 : 1;
    if (blend) {  // the derivative of fold's formula in f and in h
      double fa = f / a1, ga = h / a2, r = std::sqrt(double(f) * f + double(h) * h), d = 1 + fa * fa + ga * ga;
      double df = 1 + sign * f / r - a0 * 2 * fa / a1 / (d * d), dh = 1 + sign * h / r - a0 * 2 * ga / a2 / (d * d);
      out[0][i] = static_cast<float>(f + h + sign * r + a0 / d);
      for (int a = 1; a < 4; ++a) out[a][i] = static_cast<float>(df * out[a][i] + dh * g[a][i]);
      continue;
    }
    bool min = op.kind == SetOp::Intersection || subtract;
    out[0][i] = min ? math::min(f, h) : math::max(f, h);
    if (min ? h < f : h > f)
      for (int a = 1; a < 4; ++a) out[a][i] = static_cast<float>(hs * g[a][i]);
  }
}

bool GroupField::eval_operator(const float* x, const float* y, const float* z, size_t n, float* out,
                               backends::RuntimeError& err) const {
  std::vector<std::vector<float>> vals(kids_.size(), std::vector<float>(n));
  for (size_t k = 0; k < kids_.size(); ++k)
    if (!kids_[k]->eval(x, y, z, n, vals[k].data(), err)) return false;
  // Inputs f, g, f1..f16, t.
  std::vector<float> zero(n, 0.0f), t(n, static_cast<float>(g_.op_kernel->t));
  std::vector<const float*> in;
  in.push_back(vals[0].data());
  in.push_back(kids_.size() > 1 ? vals[1].data() : zero.data());
  for (int k = 0; k < kMaxOperands; ++k)
    in.push_back(k < static_cast<int>(kids_.size()) ? vals[k].data() : zero.data());
  in.push_back(t.data());
  float* outs[1] = {out};
  return g_.op_kernel->kernel->eval_batch(in.data(), outs, n, err);
}

bool GroupField::can_bound() const {
  if (!invalid_.empty() || (g_.op_kernel && !g_.op_kernel->intervals)) return false;
  return std::all_of(kids_.begin(), kids_.end(), [](const auto& k) { return k->can_bound(); });
}

// The same fold as eval, on intervals.
math::Interval GroupField::bound(const mesh::Box3& box) const {
  if (!can_bound()) return math::Interval::everything();
  mesh::Box3 b = moved_ ? moved_box(inverse_, box) : box;
  std::vector<math::Interval> vals;
  for (const auto& k : kids_) vals.push_back(k->bound(b));
  const math::Interval zero = math::Interval::point(0);
  if (g_.op_kernel) {  // inputs f, g, f1..f16, t
    std::vector<math::Interval> in = {vals[0], vals.size() > 1 ? vals[1] : zero};
    for (size_t k = 0; k < static_cast<size_t>(kMaxOperands); ++k) in.push_back(k < vals.size() ? vals[k] : zero);
    in.push_back(math::Interval::point(static_cast<float>(g_.op_kernel->t)));
    thread_local ir::IntervalEval ev;
    g_.op_kernel->intervals->eval(in, ev);
    return ev.outputs.empty() ? math::Interval::everything() : ev.outputs[0];
  }
  const SetOp op = set_op();
  math::Interval out = vals[0];
  for (size_t k = 1; k < vals.size(); ++k) {
    if (op.kind == SetOp::Intersection) out = math::iv::min(out, vals[k]);
    else if (op.kind == SetOp::Subtraction) out = math::iv::min(out, math::iv::neg(vals[k]));
    else if (op.kind == SetOp::Blend) out = blend_bound(out, vals[k], op.sign, op.a0, op.a1, op.a2);
    else out = math::iv::max(out, vals[k]);
  }
  return out;
}

bool parametric_group(const SceneModel& m, int group) {
  const Group& g = m.groups[group];
  bool any = false;
  for (auto [is_group, index] : g.children) {
    if (is_group ? !parametric_group(m, index) : m.shapes[index].kind == ShapeKind::Implicit) return false;
    any = true;
  }
  return any;
}

GroupParametric::GroupParametric(const SceneModel& m, int group) : g_(m.groups[group]) {
  backends::RuntimeError err;
  if (!group_matrix(g_, matrix_, err)) invalid_ = "the FTransform's affine fields: " + err.message;
  gather_children<GroupParametric>(m, g_, false, kids_, shapes_, invalid_, [](const Shape& s) {
    return std::make_unique<mesh::KernelParametric>(*s.geometry.kernel, static_cast<float>(s.geometry.t));
  });
  if (!g_.op_kernel && kids_.size() > 1)
    invalid_ = "the set operation '" + (g_.operation.empty() ? std::string("union") : g_.operation) +
        "' over parametric children has no single surface; use type \"analytical\"";
}

bool GroupParametric::valid(std::string& why) const {
  why = invalid_;
  return invalid_.empty();
}

ShapeKind GroupParametric::kind() const {
  auto dims = [](ShapeKind k) { return k == ShapeKind::Curve ? 1 : k == ShapeKind::Surface ? 2 : 3; };
  ShapeKind best = ShapeKind::Curve;
  for (const Shape* s : shapes_)
    if (dims(s->kind) > dims(best)) best = s->kind;
  return best;
}

std::array<double, 6> GroupParametric::domain() const {
  return shapes_.empty() ? std::array<double, 6>{} : shapes_[0]->domain;
}

std::array<int, 3> GroupParametric::intervals() const {
  std::array<int, 3> c = {1, 1, 1};
  for (const Shape* s : shapes_)
    for (int a = 0; a < 3; ++a) c[a] = std::max(c[a], s->resolution[a]);
  return c;
}

bool GroupParametric::eval(const float* u, const float* v, const float* w, size_t n, float* x, float* y, float* z,
                           backends::RuntimeError& err) const {
  // vals[k][c]: coordinate c of child k.
  std::vector<std::array<std::vector<float>, 3>> vals(kids_.size());
  for (size_t k = 0; k < kids_.size(); ++k) {
    for (auto& c : vals[k]) c.resize(n);
    if (!kids_[k]->eval(u, v, w, n, vals[k][0].data(), vals[k][1].data(), vals[k][2].data(), err)) return false;
  }
  float* out[3] = {x, y, z};
  for (int c = 0; c < 3; ++c) {
    if (!g_.op_kernel) {
      std::copy(vals[0][c].begin(), vals[0][c].end(), out[c]);
      continue;
    }
    std::vector<float> zero(n, 0.0f), t(n, static_cast<float>(g_.op_kernel->t));
    std::vector<const float*> in;
    in.push_back(vals[0][c].data());
    in.push_back(kids_.size() > 1 ? vals[1][c].data() : zero.data());
    for (int k = 0; k < kMaxOperands; ++k)
      in.push_back(k < static_cast<int>(kids_.size()) ? vals[k][c].data() : zero.data());
    in.push_back(t.data());
    float* outs[1] = {out[c]};
    if (!g_.op_kernel->kernel->eval_batch(in.data(), outs, n, err)) return false;
  }
  if (matrix_ != identity())
    for (size_t i = 0; i < n; ++i) apply(matrix_, x[i], y[i], z[i]);
  return true;
}

}  // namespace fscript::scene
