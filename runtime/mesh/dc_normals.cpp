// Vertex normals of dual-contoured meshes (dc_normals.h): gradients in batches on every thread,
// then the corners sorted into one vertex per side of each sharp feature.
#include "runtime/mesh/dc_normals.h"

#include <algorithm>
#include <cmath>

#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

// Minus the gradient at each vertex, normalised; (0, 0, 0) where there is none (not finite, or zero).
bool gradients(const Field& f, double step, int threads, const Mesh& m, std::vector<Vec3>& out, std::vector<float>& dist,
               backends::RuntimeError& err) {
  const size_t n = m.positions.size();
  out.assign(n, Vec3{0, 0, 0});
  dist.assign(n, 0);
  int parts = std::max(1, std::min<int>(threads, static_cast<int>(n / 4096) + 1));
  const bool analytic = f.has_gradient();
  return support::run_parts(parts, [&](int k, backends::RuntimeError& e) {
    size_t begin = n * static_cast<size_t>(k) / static_cast<size_t>(parts), end = n * static_cast<size_t>(k + 1) / static_cast<size_t>(parts);
    constexpr size_t kBatch = kEvalBatch / 6;
    std::vector<float> xs(6 * kBatch), ys(6 * kBatch), zs(6 * kBatch), vals(6 * kBatch), g(4 * kBatch);
    for (size_t b0 = begin; b0 < end; b0 += kBatch) {
      size_t c = std::min(kBatch, end - b0);
      if (stop_if_cancelled(e)) return false;
      EvalTimer timed;
      if (analytic) {
        for (size_t q = 0; q < c; ++q) xs[q] = m.positions[b0 + q][0], ys[q] = m.positions[b0 + q][1], zs[q] = m.positions[b0 + q][2];
        float* const o[4] = {g.data(), g.data() + c, g.data() + 2 * c, g.data() + 3 * c};
        if (!f.eval_gradient(xs.data(), ys.data(), zs.data(), c, o, e)) return false;
        for (size_t q = 0; q < c; ++q) {
          for (int a = 0; a < 3; ++a) out[b0 + q][static_cast<size_t>(a)] = -o[1 + a][q];
          dist[b0 + q] = o[0][q];
        }
      } else {
        size_t p = 0;
        for (int a = 0; a < 3; ++a)
          for (int s = -1; s <= 1; s += 2)
            for (size_t q = 0; q < c; ++q, ++p) {
              Vec3 v = m.positions[b0 + q];
              v[static_cast<size_t>(a)] += static_cast<float>(s * step);
              xs[p] = v[0], ys[p] = v[1], zs[p] = v[2];
            }
        if (!f.eval(xs.data(), ys.data(), zs.data(), p, vals.data(), e)) return false;
        for (size_t q = 0; q < c; ++q) {
          float mean = 0;
          for (int a = 0; a < 3; ++a) {
            out[b0 + q][static_cast<size_t>(a)] = -(vals[(2 * a + 1) * c + q] - vals[2 * a * c + q]) / static_cast<float>(2 * step);
            mean += vals[(2 * a + 1) * c + q] + vals[2 * a * c + q];
          }
          dist[b0 + q] = mean / 6;
        }
      }
      for (size_t q = b0; q < b0 + c; ++q) {  // f over the gradient's length: how far the surface is
        Vec3& d = out[q];
        float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (len > 0 && std::isfinite(len)) d = {d[0] / len, d[1] / len, d[2] / len}, dist[q] /= len;
        else d = {0, 0, 0}, dist[q] = 0;
        if (!std::isfinite(dist[q])) dist[q] = 0;
      }
    }
    return true;
  }, err);
}

constexpr uint32_t kNoCopy = ~uint32_t{0};

Vec3 face_normal(const Mesh& m, const std::array<uint32_t, 3>& t) {
  const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
  float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  float n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !std::isfinite(len)) return {0, 0, 0};
  return {n[0] / len, n[1] / len, n[2] / len};
}

}  // namespace

bool gradient_vertex_normals(const Field& f, double step, double crease, int threads, const Projection& onto, Mesh& m,
                             backends::RuntimeError& err) {
  std::vector<Vec3> grad;
  std::vector<float> dist;
  if (!gradients(f, step, threads, m, grad, dist, err)) return false;
  // A vertex farther from the surface than `onto.beyond` (f over the gradient's length) steps onto
  // it along its normal, up to `onto.most`; not one on a face of the box, whose surface is the box.
  for (size_t v = 0; v < m.positions.size(); ++v) {
    float d = dist[v];
    if (!(std::abs(d) > onto.beyond) || !(std::abs(d) <= onto.most)) continue;
    Vec3& p = m.positions[v];
    bool on_box = false;
    for (int a = 0; a < 3; ++a)
      on_box |= std::abs(p[static_cast<size_t>(a)] - onto.box[2 * a]) <= onto.box_eps ||
                std::abs(p[static_cast<size_t>(a)] - onto.box[2 * a + 1]) <= onto.box_eps;
    if (on_box) continue;
    for (int a = 0; a < 3; ++a) p[static_cast<size_t>(a)] += d * grad[v][static_cast<size_t>(a)];
  }
  // Half the crease angle: a gradient taken by differences across a sharp edge blends both sides
  // (45 degrees from each at a right angle), and must not pass for either.
  const float cos_crease = static_cast<float>(std::cos(crease / 2));
  // Per corner: its vertex's gradient where that is within the angle of its face; else (a vertex on
  // a sharp edge, whose gradient is the other side's or a blend) the gradient of the triangle's
  // vertex that matches its face best, where one does (a vertex inside the same side), else the
  // face's own normal (a triangle across the edge). One vertex per distinct normal at each vertex:
  // the first keeps the index, the others (few: sharp features are lines) are appended.
  const size_t n = m.positions.size();
  m.normals.resize(n);
  std::vector<uint8_t> used(n, 0);
  struct Copy {
    Vec3 normal;
    uint32_t id, next, from;
  };
  std::vector<Copy> copies;
  std::vector<uint32_t> first_copy(n, kNoCopy);  // per vertex: its first copy in `copies`
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    auto& tri = m.triangles[t];
    Vec3 fn = face_normal(m, tri);
    float fits[3];
    int best = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& g = grad[tri[static_cast<size_t>(k)]];
      fits[k] = g[0] * fn[0] + g[1] * fn[1] + g[2] * fn[2];
      if (fits[k] > fits[best]) best = k;
    }
    if (fits[0] >= cos_crease && fits[1] >= cos_crease && fits[2] >= cos_crease) {  // smooth: most triangles
      bool done = true;
      for (uint32_t v : tri) {
        if (used[v] && m.normals[v] != grad[v]) done = false;
        else used[v] = 1, m.normals[v] = grad[v];
      }
      if (done) continue;
    }
    Vec3 side = fits[best] >= cos_crease ? grad[tri[static_cast<size_t>(best)]] : fn;
    for (int k = 0; k < 3; ++k) {
      uint32_t& v = tri[static_cast<size_t>(k)];
      const Vec3& want = fits[k] >= cos_crease ? grad[v] : side;
      if (!used[v] || m.normals[v] == want) {
        used[v] = 1, m.normals[v] = want;
        continue;
      }
      uint32_t& head = first_copy[v];
      uint32_t c = head;
      while (c != kNoCopy && copies[c].normal != want) c = copies[c].next;
      if (c == kNoCopy) {
        c = static_cast<uint32_t>(copies.size());
        copies.push_back({want, static_cast<uint32_t>(n + c), head, v});
        head = c;
      }
      v = copies[c].id;
    }
  }
  // The copies go after the vertices, in one step (growing the arrays copy by copy moved them all).
  if (copies.empty()) return true;
  m.positions.reserve(n + copies.size()), m.normals.reserve(n + copies.size());
  m.split_from.resize(n);
  for (uint32_t i = 0; i < n; ++i) m.split_from[i] = i;
  m.split_from.reserve(n + copies.size());
  for (const Copy& c : copies) m.positions.push_back(m.positions[c.from]), m.normals.push_back(c.normal), m.split_from.push_back(c.from);
  return true;
}

}  // namespace fscript::mesh
