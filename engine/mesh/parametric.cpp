// Parametric sampling, welding and vertex normals.
#include "engine/mesh/parametric.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/mesh/field.h"

namespace fscript::mesh {
namespace {

float lerp(double a, double b, int i, int n) { return static_cast<float>(n > 0 ? a + (b - a) * i / n : a); }

bool evaluate(const ParametricJob& job, const std::vector<std::array<float, 3>>& uvw, std::vector<Vec3>& xyz,
              backends::RuntimeError& err) {
  size_t n = uvw.size();
  std::vector<float> u(n), v(n), w(n), x(n), y(n), z(n);
  for (size_t i = 0; i < n; ++i) u[i] = uvw[i][0], v[i] = uvw[i][1], w[i] = uvw[i][2];
  EvalTimer timer;
  for (size_t b = 0; b < n; b += kEvalBatch) {
    size_t m = std::min(kEvalBatch, n - b);
    if (!job.field->eval(u.data() + b, v.data() + b, w.data() + b, m, x.data() + b, y.data() + b, z.data() + b, err))
      return false;
  }
  xyz.resize(n);
  for (size_t i = 0; i < n; ++i) xyz[i] = {x[i], y[i], z[i]};
  return true;
}

// A surface's grid (as patch() lays it out: v by rows, u along each) as rows of u.
bool evaluate_surface(const ParametricJob& job, std::vector<Vec3>& xyz, backends::RuntimeError& err) {
  int na = job.intervals[0], nb = job.intervals[1];
  size_t count = static_cast<size_t>(na) + 1, rows = static_cast<size_t>(nb) + 1;
  std::vector<float> u(count), v(rows), w(rows, static_cast<float>(job.domain[4])), x(count * rows), y(x.size()),
      z(x.size());
  for (int i = 0; i <= na; ++i) u[static_cast<size_t>(i)] = lerp(job.domain[0], job.domain[1], i, na);
  for (int j = 0; j <= nb; ++j) v[static_cast<size_t>(j)] = lerp(job.domain[2], job.domain[3], j, nb);
  EvalTimer timer;
  for (size_t j = 0, per = std::max<size_t>(1, kEvalBatch / count); j < rows; j += per) {
    size_t r = std::min(per, rows - j), at = j * count;
    if (!job.field->eval_rows(u.data(), count, v.data() + j, w.data() + j, r, x.data() + at, y.data() + at,
                              z.data() + at, err))
      return false;
  }
  xyz.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) xyz[i] = {x[i], y[i], z[i]};
  return true;
}

// dP/du x dP/dv by central differences at each vertex's (u, v), a hundredth of an interval apart;
// kept where the cross product is clearly non-zero and agrees in side with the faces' normal
// (face_normals_to_vertices ran first), so poles and creases keep the face average.
bool derivative_normals(const ParametricJob& job, Mesh& m, backends::RuntimeError& err) {
  size_t n = m.positions.size();
  double hu = 0.01 * (job.domain[1] - job.domain[0]) / std::max(1, job.intervals[0]);
  double hv = 0.01 * (job.domain[3] - job.domain[2]) / std::max(1, job.intervals[1]);
  if (n == 0 || m.params.size() != n || !(hu > 0) || !(hv > 0)) return true;
  std::vector<std::array<float, 3>> uvw;
  uvw.reserve(4 * n);
  for (int k = 0; k < 4; ++k)
    for (const auto& p : m.params) {
      std::array<float, 3> q = {p[0], p[1], p[2]};
      q[k / 2] += static_cast<float>((k % 2 ? 1 : -1) * (k / 2 ? hv : hu));
      uvw.push_back(q);
    }
  std::vector<Vec3> xyz;
  if (!evaluate(job, uvw, xyz, err)) return false;
  for (size_t i = 0; i < n; ++i) {
    Vec3 du, dv;
    for (int a = 0; a < 3; ++a) du[a] = xyz[n + i][a] - xyz[i][a], dv[a] = xyz[3 * n + i][a] - xyz[2 * n + i][a];
    Vec3 c = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
    float len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    float scale = std::sqrt(du[0] * du[0] + du[1] * du[1] + du[2] * du[2]) *
        std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
    const Vec3& face = m.normals[i];
    if (!(len > 1e-3f * scale) || !std::isfinite(len)) continue;
    Vec3 d = {c[0] / len, c[1] / len, c[2] / len};
    if (d[0] * face[0] + d[1] * face[1] + d[2] * face[2] > 0.5f) m.normals[i] = d;
  }
  return true;
}

void keep_params(const std::vector<std::array<float, 3>>& uvw, Mesh& m) {
  m.params.clear();
  for (const auto& p : uvw) m.params.push_back({p[0], p[1], p[2]});
}

// One grid patch: axis a varies along rows, axis b along columns, the third fixed at `fixed`.
void patch(const ParametricJob& job, int a, int b, int c, double fixed, bool flip,
           std::vector<std::array<float, 3>>& uvw, std::vector<std::array<uint32_t, 3>>& tris) {
  int na = job.intervals[a], nb = job.intervals[b];
  uint32_t base = static_cast<uint32_t>(uvw.size());
  for (int j = 0; j <= nb; ++j)
    for (int i = 0; i <= na; ++i) {
      std::array<float, 3> p{};
      p[a] = lerp(job.domain[2 * a], job.domain[2 * a + 1], i, na);
      p[b] = lerp(job.domain[2 * b], job.domain[2 * b + 1], j, nb);
      p[c] = static_cast<float>(fixed);
      uvw.push_back(p);
    }
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      uint32_t p00 = base + j * (na + 1) + i, p10 = p00 + 1, p01 = p00 + (na + 1), p11 = p01 + 1;
      if (!flip) {
        tris.push_back({p00, p10, p11});
        tris.push_back({p00, p11, p01});
      } else {
        tris.push_back({p00, p11, p10});
        tris.push_back({p00, p01, p11});
      }
    }
}

}  // namespace

bool KernelParametric::eval(const float* u, const float* v, const float* w, size_t n, float* x, float* y, float* z,
                            backends::RuntimeError& err) const {
  if (stop_if_cancelled(err)) return false;
  std::vector<float> t(n, t_);
  const float* in[4] = {u, v, w, t.data()};
  float* out[3] = {x, y, z};
  return k_.eval_batch(in, out, n, err);
}

bool KernelParametric::eval_rows(const float* u, size_t count, const float* v, const float* w, size_t rows, float* x,
                                 float* y, float* z, backends::RuntimeError& err) const {
  if (stop_if_cancelled(err)) return false;
  std::vector<float> t(rows, t_);
  const float* rest[3] = {v, w, t.data()};
  float* out[3] = {x, y, z};
  return k_.eval_rows(u, count, rest, rows, out, err);
}

bool ParametricField::eval_rows(const float* u, size_t count, const float* v, const float* w, size_t rows, float* x,
                                float* y, float* z, backends::RuntimeError& err) const {
  size_t n = count * rows;
  std::vector<float> us(n), vs(n), ws(n);
  for (size_t r = 0; r < rows; ++r)
    for (size_t i = 0; i < count; ++i) us[r * count + i] = u[i], vs[r * count + i] = v[r], ws[r * count + i] = w[r];
  return eval(us.data(), vs.data(), ws.data(), n, x, y, z, err);
}

bool polygonize_parametric(const ParametricJob& job, Mesh& out, backends::RuntimeError& err) {
  out = Mesh{};
  if (!job.field) {
    err.message = "the parametric polygonizer needs a map (u, v, w) -> (x, y, z)";
    return false;
  }
  std::vector<std::array<float, 3>> uvw;
  if (job.kind == ParametricKind::Curve) {
    int n = std::max(1, job.intervals[0]);
    out.polylines.emplace_back();
    for (int i = 0; i <= n; ++i) {
      uvw.push_back({lerp(job.domain[0], job.domain[1], i, n), static_cast<float>(job.domain[2]),
                     static_cast<float>(job.domain[4])});
      out.polylines[0].push_back(static_cast<uint32_t>(i));
    }
    keep_params(uvw, out);
    return evaluate(job, uvw, out.positions, err);
  }
  if (job.kind == ParametricKind::Surface) {
    patch(job, 0, 1, 2, job.domain[4], false, uvw, out.triangles);
  } else {
    for (int c = 0; c < 3; ++c) {
      int a = (c + 1) % 3, b = (c + 2) % 3;
      patch(job, a, b, c, job.domain[2 * c], true, uvw, out.triangles);
      patch(job, a, b, c, job.domain[2 * c + 1], false, uvw, out.triangles);
    }
  }
  if (!(job.kind == ParametricKind::Surface ? evaluate_surface(job, out.positions, err)
                                            : evaluate(job, uvw, out.positions, err)))
    return false;
  keep_params(uvw, out);
  float size = 0;
  for (const auto& p : out.positions)
    for (float v : p)
      if (std::isfinite(v)) size = std::max(size, std::fabs(v));
  weld(out, std::max(size, 1e-6f) * 1e-5f);
  face_normals_to_vertices(out);
  return job.kind != ParametricKind::Surface || derivative_normals(job, out, err);
}

void weld(Mesh& m, float tol) {
  // Quantise to the tolerance and merge points of the same cell (and its neighbours' exact match).
  std::map<std::array<long long, 3>, uint32_t> cells;
  std::vector<uint32_t> remap(m.positions.size());
  std::vector<Vec3> kept, kept_params;
  bool params = m.params.size() == m.positions.size();
  for (size_t i = 0; i < m.positions.size(); ++i) {
    std::array<long long, 3> key;
    for (int a = 0; a < 3; ++a) key[a] = std::isfinite(m.positions[i][a]) ? std::llround(m.positions[i][a] / tol) : 0;
    auto [it, fresh] = cells.try_emplace(key, static_cast<uint32_t>(kept.size()));
    if (fresh) {
      kept.push_back(m.positions[i]);
      if (params) kept_params.push_back(m.params[i]);
    }
    remap[i] = it->second;
  }
  std::vector<std::array<uint32_t, 3>> tris;
  for (auto t : m.triangles) {
    std::array<uint32_t, 3> r = {remap[t[0]], remap[t[1]], remap[t[2]]};
    if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2]) tris.push_back(r);
  }
  for (auto& l : m.polylines)
    for (auto& v : l) v = remap[v];
  m.positions = std::move(kept);
  if (params) m.params = std::move(kept_params);
  m.triangles = std::move(tris);
  m.normals.clear();
}

void face_normals_to_vertices(Mesh& m) {
  m.normals.assign(m.positions.size(), Vec3{0, 0, 0});
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    Vec3 n = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
              (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
              (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    for (uint32_t v : t)
      for (int k = 0; k < 3; ++k) m.normals[v][k] += n[k];
  }
  for (auto& n : m.normals) {
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0)
      for (float& v : n) v /= len;
  }
}

}  // namespace fscript::mesh
