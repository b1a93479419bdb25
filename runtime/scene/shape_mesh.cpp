// Shapes to meshes.
#include "runtime/scene/shape_mesh.h"

#include <algorithm>
#include <cmath>

#include "runtime/mesh/implicit.h"
#include "runtime/mesh/parametric.h"
#include "runtime/scene/shape_field.h"

namespace fscript::scene {

mesh::Vec3 pattern_colour(const vrml::Node* material, float value) {
  const vrml::Value* keys = material ? material->get("patternKey") : nullptr;
  const vrml::Value* cols = material ? material->get("patternColor") : nullptr;
  size_t n = keys && cols ? std::min(keys->nums.size(), cols->nums.size() / 3) : 0;
  if (n == 0 || !std::isfinite(value)) {
    float g = std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 0.0f;
    return {g, g, g};
  }
  auto colour = [&](size_t i) {
    return mesh::Vec3{static_cast<float>(cols->nums[3 * i]), static_cast<float>(cols->nums[3 * i + 1]),
                      static_cast<float>(cols->nums[3 * i + 2])};
  };
  if (value <= keys->nums[0]) return colour(0);
  for (size_t i = 1; i < n; ++i)
    if (value <= keys->nums[i]) {
      double span = keys->nums[i] - keys->nums[i - 1];
      float f = span > 0 ? static_cast<float>((value - keys->nums[i - 1]) / span) : 1.0f;
      mesh::Vec3 a = colour(i - 1), b = colour(i);
      return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
    }
  return colour(n - 1);
}

namespace {

bool colour_vertices(const Shape& s, mesh::Mesh& m, backend::RuntimeError& err) {
  if (!s.colour || m.positions.empty()) return true;
  size_t n = m.positions.size();
  std::vector<std::vector<float>> in(7, std::vector<float>(n));
  bool params = m.params.size() == n;
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      in[a][i] = m.positions[i][a];
      in[3 + a][i] = params ? m.params[i][a] : m.positions[i][a];
    }
  std::fill(in[6].begin(), in[6].end(), static_cast<float>(s.colour->t));
  std::vector<std::vector<float>> out(4, std::vector<float>(n));
  const float* ins[7];
  for (int k = 0; k < 7; ++k) ins[k] = in[k].data();
  float* outs[4] = {out[0].data(), out[1].data(), out[2].data(), out[3].data()};
  if (!s.colour->kernel->eval_batch(ins, outs, n, err)) return false;
  m.colours.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (s.colour->rgb) {
      for (int k = 0; k < 3; ++k) {
        float c = out[1 + k][i];
        m.colours[i][k] = std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 0.0f;
      }
    } else {
      m.colours[i] = pattern_colour(s.material_node, out[0][i]);
    }
  }
  return true;
}

// FMaterial's other strings, evaluated once per frame at the centre of the shape's domain (the
// VRML97 Material holds one value per shape): scalars take the script's value, colours its r, g, b
// (or the value as a grey level). No FMaterial: no material (the viewer's default).
bool evaluate_material(const Shape& s, mesh::Mesh& m, backend::RuntimeError& err) {
  if (!s.material_node) return true;
  mesh::Material mat;
  for (const auto& f : s.material) {
    float centre[3];
    for (int a = 0; a < 3; ++a) centre[a] = static_cast<float>(0.5 * (s.domain[2 * a] + s.domain[2 * a + 1]));
    float t = static_cast<float>(f.t), out[4] = {0, 0, 0, 0};
    const float* in[7] = {&centre[0], &centre[1], &centre[2], &centre[0], &centre[1], &centre[2], &t};
    float* outs[4] = {&out[0], &out[1], &out[2], &out[3]};
    if (!f.kernel->eval_batch(in, outs, 1, err)) return false;
    auto unit = [](float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; };
    mesh::Vec3 colour = f.rgb ? mesh::Vec3{unit(out[1]), unit(out[2]), unit(out[3])}
                              : mesh::Vec3{unit(out[0]), unit(out[0]), unit(out[0])};
    if (f.field == "ambientIntensity") mat.ambient_intensity = unit(out[0]);
    else if (f.field == "shininess") mat.shininess = unit(out[0]);
    else if (f.field == "transparency") mat.transparency = unit(out[0]);
    else if (f.field == "emissiveColor") mat.emissive = colour;
    else if (f.field == "specularColor") mat.specular = colour;
  }
  m.material = mat;
  return true;
}

void transform(const Mat4& t, mesh::Mesh& m) {
  static const Mat4 identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (t == identity) return;
  for (auto& p : m.positions) {
    mesh::Vec3 q;
    for (int r = 0; r < 3; ++r)
      q[r] = static_cast<float>(t[r] * p[0] + t[4 + r] * p[1] + t[8 + r] * p[2] + t[12 + r]);
    p = q;
  }
  for (auto& n : m.normals) {
    mesh::Vec3 q;
    for (int r = 0; r < 3; ++r) q[r] = static_cast<float>(t[r] * n[0] + t[4 + r] * n[1] + t[8 + r] * n[2]);
    float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (len > 0)
      for (float& v : q) v /= len;
    n = q;
  }
}

}  // namespace

bool mesh_shape(const Shape& s, mesh::Mesh& out, backend::RuntimeError& err, bool world, int threads) {
  if (!s.geometry.kernel) {
    err.message = "the shape has no compiled geometry";
    return false;
  }
  bool ok;
  if (s.kind == ShapeKind::Implicit) {
    ShapeField field(s);
    mesh::ImplicitJob job;
    job.field = &field;
    job.box = s.domain;
    job.cells = s.resolution;
    job.threads = threads;
    ok = mesh::polygonize_implicit(job, out, err);
  } else {
    mesh::ParametricJob job;
    job.kernel = s.geometry.kernel.get();
    job.kind = s.kind == ShapeKind::Curve ? mesh::ParametricKind::Curve
             : s.kind == ShapeKind::Surface ? mesh::ParametricKind::Surface : mesh::ParametricKind::Solid;
    job.domain = s.domain;
    job.intervals = s.resolution;
    job.t = static_cast<float>(s.geometry.t);
    ok = mesh::polygonize_parametric(job, out, err);
  }
  if (!ok || !colour_vertices(s, out, err) || !evaluate_material(s, out, err)) return false;
  if (world) transform(s.transform, out);
  return true;
}

bool mesh_group(const SceneModel& m, int group, mesh::Mesh& out, backend::RuntimeError& err, bool world,
                int threads) {
  GroupField field(m, group);
  std::string why;
  if (!field.valid(why)) {
    err.message = why;
    return false;
  }
  mesh::ImplicitJob job;
  job.field = &field;
  job.box = field.box();
  job.cells = field.cells();
  job.threads = threads;
  if (!mesh::polygonize_implicit(job, out, err)) return false;
  const Shape* first = field.first_shape();
  if (first && (!colour_vertices(*first, out, err) || !evaluate_material(*first, out, err))) return false;
  if (first && world) transform(first->transform, out);
  return true;
}

}  // namespace fscript::scene
