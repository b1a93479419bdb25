// Scene fields. Set operations fold left over the children: union max, intersection min,
// subtraction min(f, -g), blends f + g +- sqrt(f^2 + g^2) + a0 / (1 + (f/a1)^2 + (g/a2)^2).
#include "runtime/scene/shape_field.h"

#include <algorithm>
#include <cmath>

#include "runtime/math/math.h"

namespace fscript::scene {

bool ShapeField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                      backend::RuntimeError& err) const {
  mesh::KernelField geometry(*s_.geometry.kernel, static_cast<float>(s_.geometry.t));
  if (!geometry.eval(x, y, z, n, out, err)) return false;
  if (!s_.texture) return true;
  // Displacement texture: the point kernel (x, y, z, u, v, w, t) -> d, added to f.
  std::vector<float> t(n, static_cast<float>(s_.texture->t));
  std::vector<float> d(n), r(n), g(n), b(n);
  const float* in[7] = {x, y, z, x, y, z, t.data()};
  float* outs[4] = {d.data(), r.data(), g.data(), b.data()};
  if (!s_.texture->kernel->eval_batch(in, outs, n, err)) return false;
  for (size_t i = 0; i < n; ++i) out[i] += d[i];
  return true;
}

GroupField::GroupField(const SceneModel& m, int group) : m_(m), g_(m.groups[group]) {
  for (auto [is_group, index] : g_.children) {
    if (is_group) {
      auto f = std::make_unique<GroupField>(m, index);
      std::string why;
      if (!f->valid(why)) invalid_ = why;
      for (const Shape* s : f->shapes_) shapes_.push_back(s);
      kids_.push_back(std::move(f));
    } else {
      const Shape& s = m.shapes[index];
      if (s.kind != ShapeKind::Implicit)
        invalid_ = "operations over parametric shapes (per coordinate) are not built yet";
      shapes_.push_back(&s);
      kids_.push_back(std::make_unique<ShapeField>(s));
    }
  }
  if (kids_.empty()) invalid_ = "an FTransform without FShape children";
}

bool GroupField::valid(std::string& why) const {
  why = invalid_;
  return invalid_.empty();
}

std::array<double, 6> GroupField::box() const {
  std::array<double, 6> b = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (const Shape* s : shapes_)
    for (int a = 0; a < 3; ++a) {
      b[2 * a] = std::min(b[2 * a], s->domain[2 * a]);
      b[2 * a + 1] = std::max(b[2 * a + 1], s->domain[2 * a + 1]);
    }
  return b;
}

std::array<int, 3> GroupField::cells() const {
  std::array<int, 3> c = {1, 1, 1};
  for (const Shape* s : shapes_)
    for (int a = 0; a < 3; ++a) c[a] = std::max(c[a], s->resolution[a]);
  return c;
}

const Shape* GroupField::first_shape() const { return shapes_.empty() ? nullptr : shapes_.front(); }

bool GroupField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                      backend::RuntimeError& err) const {
  std::vector<std::vector<float>> vals(kids_.size(), std::vector<float>(n));
  for (size_t k = 0; k < kids_.size(); ++k)
    if (!kids_[k]->eval(x, y, z, n, vals[k].data(), err)) return false;
  std::string op = g_.operation.empty() ? "union" : g_.operation;
  if (g_.op_kernel) {  // analytical: inputs f, g, f1..f16, t
    std::vector<float> zero(n, 0.0f), t(n, static_cast<float>(g_.op_kernel->t));
    std::vector<const float*> in;
    in.push_back(vals[0].data());
    in.push_back(kids_.size() > 1 ? vals[1].data() : zero.data());
    for (int k = 0; k < kMaxOperands; ++k) in.push_back(k < static_cast<int>(kids_.size()) ? vals[k].data() : zero.data());
    in.push_back(t.data());
    float* outs[1] = {out};
    return g_.op_kernel->kernel->eval_batch(in.data(), outs, n, err);
  }
  const vrml::Value* p = g_.node->get("parameters");
  double a0 = p && p->nums.size() > 0 ? p->nums[0] : 0, a1 = p && p->nums.size() > 1 ? p->nums[1] : 1,
         a2 = p && p->nums.size() > 2 ? p->nums[2] : 1;
  std::copy(vals[0].begin(), vals[0].end(), out);
  for (size_t k = 1; k < kids_.size(); ++k)
    for (size_t i = 0; i < n; ++i) {
      float f = out[i], g = vals[k][i];
      if (op == "intersection") out[i] = math::min(f, g);
      else if (op == "subtraction" || op == "difference") out[i] = math::min(f, -g);
      else if (op == "blend_union" || op == "blend_intersection") {
        double sign = op == "blend_union" ? 1 : -1;
        double fa = f / a1, ga = g / a2;
        out[i] = static_cast<float>(f + g + sign * std::sqrt(double(f) * f + double(g) * g) + a0 / (1 + fa * fa + ga * ga));
      } else {
        out[i] = math::max(f, g);  // union (and any unknown name, reported when the model was built)
      }
    }
  return true;
}

}  // namespace fscript::scene
