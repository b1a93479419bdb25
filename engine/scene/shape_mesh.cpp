// Shapes to meshes.
#include "engine/scene/shape_mesh.h"

#include <algorithm>
#include <cmath>

#include "runtime/support/progress.h"
#include "engine/mesh/dc_slabs.h"
#include "engine/mesh/field_profile.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "engine/mesh/parametric.h"
#include "engine/scene/shape_field.h"

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

bool colour_vertices(const Shape& s, mesh::Mesh& m, backends::RuntimeError& err) {
  if (!s.colour || m.positions.empty()) return true;
  return colour_points(s, m.positions, m.params.size() == m.positions.size() ? &m.params : nullptr, m.colours, err);
}

// FMaterial's other strings, evaluated once per frame at the centre of the shape's domain (the
// VRML97 Material holds one value per shape): scalars take the script's value, colours its r, g, b
// (or the value as a grey level). No FMaterial: no material (the viewer's default).
bool evaluate_material(const Shape& s, mesh::Mesh& m, backends::RuntimeError& err) {
  return shape_material(s, m.material, err);
}

}  // namespace

bool shape_material(const Shape& s, std::optional<mesh::Material>& out, backends::RuntimeError& err) {
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
  out = mat;
  return true;
}

bool colour_points(const Shape& s, const std::vector<mesh::Vec3>& points, const std::vector<mesh::Vec3>* params,
                   std::vector<mesh::Vec3>& out, backends::RuntimeError& err) {
  out.clear();
  if (!s.colour || points.empty()) return true;
  size_t n = points.size();
  std::vector<std::vector<float>> in(7, std::vector<float>(n));
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      in[a][i] = points[i][a];
      in[3 + a][i] = params ? (*params)[i][a] : points[i][a];
    }
  std::fill(in[6].begin(), in[6].end(), static_cast<float>(s.colour->t));
  std::vector<std::vector<float>> res(4, std::vector<float>(n));
  const float* ins[7];
  for (int k = 0; k < 7; ++k) ins[k] = in[k].data();
  float* outs[4] = {res[0].data(), res[1].data(), res[2].data(), res[3].data()};
  bool ok;
  {
    mesh::EvalTimer timer;
    ok = mesh::eval_in_batches(*s.colour->kernel, ins, outs, n, err);
  }
  if (!ok) return false;
  out.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (s.colour->rgb) {
      for (int k = 0; k < 3; ++k) {
        float c = res[1 + k][i];
        out[i][k] = std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 0.0f;
      }
    } else {
      out[i] = pattern_colour(s.material_node, res[0][i]);
    }
  }
  return true;
}

namespace {

// A 3D texture on a parametric shape: each point moves by d(x, y, z, u, v, w, t) along its unit
// normal; the normals are then taken from the moved faces.
bool displace(const Shape& s, mesh::Mesh& m, backends::RuntimeError& err) {
  size_t n = m.positions.size();
  if (!s.texture || n == 0 || m.normals.size() != n) return true;
  std::vector<std::vector<float>> in(7, std::vector<float>(n));
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      in[a][i] = m.positions[i][a], in[3 + a][i] = m.params.size() == n ? m.params[i][a] : 0.0f;
  std::fill(in[6].begin(), in[6].end(), static_cast<float>(s.texture->t));
  std::vector<float> d(n), r(n), g(n), b(n);
  const float* ins[7] = {in[0].data(), in[1].data(), in[2].data(), in[3].data(),
                         in[4].data(), in[5].data(), in[6].data()};
  float* outs[4] = {d.data(), r.data(), g.data(), b.data()};
  {
    mesh::EvalTimer timer;
    if (!mesh::eval_in_batches(*s.texture->kernel, ins, outs, n, err)) return false;
  }
  for (size_t i = 0; i < n; ++i)
    if (std::isfinite(d[i]))
      for (int a = 0; a < 3; ++a) m.positions[i][a] += d[i] * m.normals[i][a];
  mesh::face_normals_to_vertices(m);
  return true;
}

}  // namespace

// Positions by the matrix, normals by its inverse transpose (non-uniform scales bend them).
void transform_mesh(const Mat4& t, mesh::Mesh& m) {
  if (t == identity()) return;
  for (auto& p : m.positions) {
    mesh::Vec3 q;
    for (int r = 0; r < 3; ++r) q[r] = static_cast<float>(t[r] * p[0] + t[4 + r] * p[1] + t[8 + r] * p[2] + t[12 + r]);
    p = q;
  }
  Mat4 inv;
  if (!invert_affine(t, inv)) return;
  for (auto& n : m.normals) {
    mesh::Vec3 q;
    for (int r = 0; r < 3; ++r)
      q[r] = static_cast<float>(inv[r * 4] * n[0] + inv[r * 4 + 1] * n[1] + inv[r * 4 + 2] * n[2]);
    float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (len > 0)
      for (float& v : q) v /= len;
    n = q;
  }
  // A mirroring matrix turns the faces inside out: keep them outward.
  double det =
      t[0] * (t[5] * t[10] - t[9] * t[6]) - t[4] * (t[1] * t[10] - t[9] * t[2]) + t[8] * (t[1] * t[6] - t[5] * t[2]);
  if (det < 0)
    for (auto& tri : m.triangles) std::swap(tri[1], tri[2]);
}

// Tells the shape's kernels how many points are ahead (the auto backend compiles natively at once
// when that pays): a dense grid's (of the shape's own dimensions), or a quarter of it where
// interval pruning skips most cells; the gradient kernel (the meshers' normals), a crossing per
// cell of three faces of the grid (a plane across it; the gyroid has four times that). Dual
// contouring of a pruned shape that has local tapes says the geometry's share itself, once its
// octree knows which regions run on tapes of their own (most points of a model of many parts).
void expect_work(const Shape& s, bool prune, bool dual_contoured) {
  uint64_t points = 1, face = 1;
  int dims = s.kind == ShapeKind::Curve ? 1 : s.kind == ShapeKind::Surface ? 2 : 3;
  for (int k = 0; k < dims; ++k) points *= static_cast<uint64_t>(std::max(s.resolution[static_cast<size_t>(k)], 1) + 1);
  for (int k = 0; k < 2; ++k) face *= static_cast<uint64_t>(std::max(s.resolution[static_cast<size_t>(k)], 1) + 1);
  if (s.kind == ShapeKind::Implicit && prune) points /= 4;
  const bool tapes = s.kind == ShapeKind::Implicit && prune && dual_contoured && !s.texture && s.geometry.intervals;
  for (const CompiledField* f :
       {tapes ? nullptr : &s.geometry, s.texture ? &*s.texture : nullptr, s.colour ? &*s.colour : nullptr})
    if (f && f->kernel) f->kernel->expect_points(points);
  if (s.kind == ShapeKind::Implicit && s.geometry.gradient && !s.texture)
    if (const backends::Kernel* g = s.geometry.gradient->get()) g->expect_points(3 * face);
}

// A shard of a still scene (fvrml-run --shard without --frames) makes only the slabs of the shapes
// dual contouring meshes; the merge makes the parametric ones.
// The merge joins their slabs: nothing of theirs is sampled (no native compile pays).
static bool making_slabs(const mesh::MesherOptions& mesher) { return mesher.slabs && !mesher.slabs->joining(); }
static bool joining_slabs(const mesh::MesherOptions& mesher) { return mesher.slabs && mesher.slabs->joining(); }

bool mesh_shape(const Shape& s, mesh::Mesh& out, backends::RuntimeError& err, bool world, int threads, bool prune,
                const mesh::MesherOptions& mesher) {
  if (!s.geometry.kernel) {
    err.message = "the shape has no compiled geometry";
    return false;
  }
  if (making_slabs(mesher) && s.kind != ShapeKind::Implicit) return out = mesh::Mesh{}, true;
  if (!joining_slabs(mesher)) expect_work(s, prune, mesher.kind == mesh::Mesher::DualContouring);
  bool ok;
  support::ProgressJob progress;  // one job of the run's progress line
  if (s.kind == ShapeKind::Implicit) {
    ShapeField field(s);
    mesh::ImplicitJob job;
    job.progress = &progress;
    job.field = &field;
    job.box = s.domain;
    job.cells = s.resolution;
    job.threads = threads;
    job.prune = prune;
    job.mesher = mesher;
    if (mesher.profiler) job.profile = &mesher.profiler->of(s.fshape);
    ok = mesh::polygonize(job, out, err);
  } else {
    mesh::KernelParametric map(*s.geometry.kernel, static_cast<float>(s.geometry.t));
    mesh::ParametricJob job;
    job.field = &map;
    job.kind = s.kind == ShapeKind::Curve ? mesh::ParametricKind::Curve
        : s.kind == ShapeKind::Surface    ? mesh::ParametricKind::Surface
                                          : mesh::ParametricKind::Solid;
    job.domain = s.domain;
    job.intervals = s.resolution;
    ok = mesh::polygonize_parametric(job, out, err) && (s.kind == ShapeKind::Curve || displace(s, out, err));
  }
  if (!ok || !colour_vertices(s, out, err) || !evaluate_material(s, out, err)) return false;
  if (world) transform_mesh(s.transform, out);
  return true;
}

namespace {

// An FTransform over parametric children: a union is every child's mesh together (moved by the
// FTransform's matrix); an analytical operation is one parametric map (GroupParametric).
bool mesh_parametric_group(const SceneModel& m, int group, mesh::Mesh& out, backends::RuntimeError& err, int threads,
                           bool prune) {
  const Group& g = m.groups[group];
  std::string op = g.operation.empty() ? "union" : g.operation;
  if (!g.op_kernel && op == "union" && g.children.size() > 1) {
    Mat4 matrix;
    if (!group_matrix(g, matrix, err)) return false;
    for (auto [is_group, index] : g.children) {
      mesh::Mesh part;
      if (!(is_group ? mesh_group(m, index, part, err, false, threads, prune)
                     : mesh_shape(m.shapes[index], part, err, false, threads, prune)))
        return false;
      transform_mesh(matrix, part);
      out.append(part);
    }
    return true;
  }
  GroupParametric field(m, group);
  std::string why;
  if (!field.valid(why)) {
    err.message = why;
    return false;
  }
  mesh::ParametricJob job;
  job.field = &field;
  ShapeKind kind = field.kind();
  job.kind = kind == ShapeKind::Curve ? mesh::ParametricKind::Curve
      : kind == ShapeKind::Surface    ? mesh::ParametricKind::Surface
                                      : mesh::ParametricKind::Solid;
  job.domain = field.domain();
  job.intervals = field.intervals();
  const Shape* first = field.first_shape();
  return mesh::polygonize_parametric(job, out, err) && colour_vertices(*first, out, err) &&
      evaluate_material(*first, out, err);
}

const Shape* first_shape_below(const SceneModel& m, int group) {
  for (auto [is_group, index] : m.groups[group].children) {
    const Shape* s = is_group ? first_shape_below(m, index) : &m.shapes[index];
    if (s) return s;
  }
  return nullptr;
}

}  // namespace

bool mesh_group(const SceneModel& m, int group, mesh::Mesh& out, backends::RuntimeError& err, bool world, int threads,
                bool prune, const mesh::MesherOptions& mesher) {
  out = mesh::Mesh{};
  support::ProgressJob progress;
  for (const Shape& s : m.shapes)
    if (inside_group(m, s.group, group) && !joining_slabs(mesher))
      expect_work(s, prune, false);  // a group's field: no local tapes
  if (parametric_group(m, group)) {
    if (making_slabs(mesher)) return true;
    if (!mesh_parametric_group(m, group, out, err, threads, prune)) return false;
    const Shape* first = first_shape_below(m, group);
    if (first && world) transform_mesh(first->transform, out);
    return true;
  }
  GroupField field(m, group);
  std::string why;
  if (!field.valid(why)) {
    err.message = why;
    return false;
  }
  mesh::ImplicitJob job;
  job.progress = &progress;
  job.field = &field;
  job.box = field.box();
  job.cells = field.cells();
  job.threads = threads;
  job.prune = prune;
  job.mesher = mesher;
  if (mesher.profiler) job.profile = &mesher.profiler->of(m.groups[group].node);
  if (!mesh::polygonize(job, out, err)) return false;
  const Shape* first = field.first_shape();
  if (first && (!colour_vertices(*first, out, err) || !evaluate_material(*first, out, err))) return false;
  if (first && world) transform_mesh(first->transform, out);
  return true;
}

}  // namespace fscript::scene
