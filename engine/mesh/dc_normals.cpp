// Vertex normals of dual-contoured meshes (dc_normals.h): gradients in batches on every thread,
// then the corners sorted into one vertex per side of each sharp feature.
#include "engine/mesh/dc_normals.h"

#include <algorithm>
#include <cmath>

#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

bool on_box(const Vec3& p, const Projection& onto) {
  bool on = false;
  for (size_t a = 0; a < 3; ++a)
    on |= std::abs(p[a] - onto.box[2 * a]) <= onto.box_eps || std::abs(p[a] - onto.box[2 * a + 1]) <= onto.box_eps;
  return on;
}

// Vertex q's normal from minus its gradient `d` and its value `v`; (0, 0, 0) where there is none (not
// finite, or zero). Then the Newton step: a vertex farther from the surface than `onto.beyond`
// (v over the gradient's length), and no farther than `onto.most`, steps onto it along the normal.
void normal_and_step(Vec3 d, float v, const Projection& onto, Vec3& p, Vec3& normal) {
  float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0) || !std::isfinite(len)) {
    normal = {0, 0, 0};
    return;
  }
  normal = {d[0] / len, d[1] / len, d[2] / len};
  float dist = v / len;
  if (!(std::abs(dist) > onto.beyond) || !(std::abs(dist) <= onto.most) || on_box(p, onto)) return;
  for (size_t a = 0; a < 3; ++a) p[a] += dist * normal[a];
}

// Every vertex's normal (normal_and_step), in batches on every thread: the field's own gradient,
// else central differences `step` apart. Written straight into the mesh: no array per vertex but
// the normals themselves, as the pages a large mesh touches cost as much as the arithmetic.
bool gradients(const Field& f, double step, int threads, const Projection& onto, Mesh& m, backends::RuntimeError& err) {
  const size_t n = m.positions.size();
  m.normals.reserve(n + n / 8);  // room for the vertices split along sharp features
  m.normals.resize(n);
  int parts = std::max(1, std::min<int>(threads, static_cast<int>(n / 4096) + 1));
  const bool analytic = f.has_gradient();
  return support::run_parts(
      parts,
      [&](int k, backends::RuntimeError& e) {
        size_t begin = n * static_cast<size_t>(k) / static_cast<size_t>(parts),
               end = n * static_cast<size_t>(k + 1) / static_cast<size_t>(parts);
        constexpr size_t kBatch = kEvalBatch / 6;
        std::vector<float> xs(6 * kBatch), ys(6 * kBatch), zs(6 * kBatch), vals(6 * kBatch), g(4 * kBatch);
        for (size_t b0 = begin; b0 < end; b0 += kBatch) {
          size_t c = std::min(kBatch, end - b0);
          if (stop_if_cancelled(e)) return false;
          EvalTimer timed;
          if (analytic) {
            for (size_t q = 0; q < c; ++q)
              xs[q] = m.positions[b0 + q][0], ys[q] = m.positions[b0 + q][1], zs[q] = m.positions[b0 + q][2];
            float* const o[4] = {g.data(), g.data() + c, g.data() + 2 * c, g.data() + 3 * c};
            if (!f.eval_gradient(xs.data(), ys.data(), zs.data(), c, o, e)) return false;
            for (size_t q = 0; q < c; ++q)
              normal_and_step({-o[1][q], -o[2][q], -o[3][q]}, o[0][q], onto, m.positions[b0 + q], m.normals[b0 + q]);
            continue;
          }
          size_t p = 0;
          for (size_t a = 0; a < 3; ++a)
            for (int s = -1; s <= 1; s += 2)
              for (size_t q = 0; q < c; ++q, ++p) {
                Vec3 v = m.positions[b0 + q];
                v[a] += static_cast<float>(s * step);
                xs[p] = v[0], ys[p] = v[1], zs[p] = v[2];
              }
          if (!f.eval(xs.data(), ys.data(), zs.data(), p, vals.data(), e)) return false;
          for (size_t q = 0; q < c; ++q) {
            Vec3 d;
            float mean = 0;
            for (size_t a = 0; a < 3; ++a) {
              d[a] = -(vals[(2 * a + 1) * c + q] - vals[2 * a * c + q]) / static_cast<float>(2 * step);
              mean += vals[(2 * a + 1) * c + q] + vals[2 * a * c + q];
            }
            normal_and_step(d, mean / 6, onto, m.positions[b0 + q], m.normals[b0 + q]);
          }
        }
        return true;
      },
      err);
}

constexpr uint32_t kNoCopy = ~uint32_t{0};

bool same(const Vec3& a, const Vec3& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
float dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The triangle's normal, not normalised, and its length (0 where it has none).
Vec3 face_normal(const Mesh& m, const std::array<uint32_t, 3>& t, float& len) {
  const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
  float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  Vec3 n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  len = std::sqrt(dot(n, n));
  if (!(len > 0) || !std::isfinite(len)) len = 0;
  return n;
}

// A triangle with a corner whose gradient is not within the angle of its face: the corners in
// `own` keep their vertex's gradient, the others take `side`.
struct Rough {
  uint32_t t;
  uint8_t own;
  Vec3 side;
};

// The triangles that are not smooth, with what each corner takes; `keeps` marks the vertices with a
// corner that takes the vertex's own gradient.
std::vector<Rough> rough_triangles(const Mesh& m, float cos_crease, std::vector<uint8_t>& keeps) {
  std::vector<Rough> rough;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    float len;
    Vec3 fn = face_normal(m, tri, len);
    float fits[3], limit = cos_crease * len;  // fits scaled by len: no division for most triangles
    uint8_t own = 0;
    for (int k = 0; k < 3; ++k) {
      fits[k] = len > 0 ? dot(m.normals[tri[static_cast<size_t>(k)]], fn) : 0;
      own |= static_cast<uint8_t>((len > 0 && fits[k] >= limit) << k);
    }
    if (own == 7) {  // smooth: most triangles
      keeps[tri[0]] = keeps[tri[1]] = keeps[tri[2]] = 1;
      continue;
    }
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (fits[k] > fits[best]) best = k;
    for (int k = 0; k < 3; ++k)
      if (own >> k & 1) keeps[tri[static_cast<size_t>(k)]] = 1;
    Vec3 side = own >> best & 1 ? m.normals[tri[static_cast<size_t>(best)]]
        : len > 0               ? Vec3{fn[0] / len, fn[1] / len, fn[2] / len}
                                : Vec3{0, 0, 0};
    rough.push_back({static_cast<uint32_t>(t), own, side});
  }
  return rough;
}

}  // namespace

bool gradient_vertex_normals(const Field& f, double step, double crease, int threads, const Projection& onto, Mesh& m,
                             backends::RuntimeError& err) {
  if (!gradients(f, step, threads, onto, m, err)) return false;
  // Half the crease angle: a gradient taken by differences across a sharp edge blends both sides
  // (45 degrees from each at a right angle), and must not pass for either.
  const float cos_crease = static_cast<float>(std::cos(crease / 2));
  // A vertex keeps its gradient where one of its corners takes it; one whose corners all take
  // another normal takes the first of those. Every other normal a vertex's corners take is a
  // copy of the vertex (few: sharp features are lines), appended after the vertices.
  const size_t n = m.positions.size();
  std::vector<uint8_t> keeps(n, 0);  // 1: its gradient stays, 2: the first other normal replaced it
  std::vector<Rough> rough = rough_triangles(m, cos_crease, keeps);
  if (rough.empty()) return true;
  struct Copy {
    Vec3 normal;
    uint32_t next, from;
  };
  std::vector<Copy> copies;
  std::vector<uint32_t> first_copy(n, kNoCopy);  // per vertex: its first copy in `copies`
  for (const Rough& r : rough)
    for (size_t k = 0; k < 3; ++k) {
      uint32_t& v = m.triangles[r.t][k];
      if (r.own >> k & 1) continue;
      if (keeps[v] == 0) {
        keeps[v] = 2, m.normals[v] = r.side;
        continue;
      }
      if (same(m.normals[v], r.side)) continue;
      uint32_t& head = first_copy[v];
      uint32_t c = head;
      while (c != kNoCopy && !same(copies[c].normal, r.side)) c = copies[c].next;
      if (c == kNoCopy) {
        c = static_cast<uint32_t>(copies.size());
        copies.push_back({r.side, head, v});
        head = c;
      }
      v = static_cast<uint32_t>(n) + c;
    }
  if (copies.empty()) return true;
  m.positions.reserve(n + copies.size()), m.normals.reserve(n + copies.size());
  m.split_from.resize(n);
  for (uint32_t i = 0; i < n; ++i) m.split_from[i] = i;
  m.split_from.reserve(n + copies.size());
  for (const Copy& c : copies)
    m.positions.push_back(m.positions[c.from]), m.normals.push_back(c.normal), m.split_from.push_back(c.from);
  return true;
}

}  // namespace fscript::mesh
