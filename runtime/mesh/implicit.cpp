// Marching tetrahedra with refinement. Grid point (i, j, k), i in [-1, n], sits at
// lo + (i + 0.5) * h: points -1 and n lie half a cell outside the box and are the padding, so an
// edge from the padding to an inside point crosses the box face exactly at its midpoint.
#include "runtime/mesh/implicit.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace fscript::mesh {
namespace {

constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
constexpr size_t kBatch = 8192;

struct Grid {
  int nx, ny, nz;       // samples inside the box per axis
  double lo[3], h[3];
  // Padded index space: (i + 1) in [0, nx + 2).
  size_t index(int i, int j, int k) const {
    return (static_cast<size_t>(k + 1) * (ny + 2) + static_cast<size_t>(j + 1)) * (nx + 2) + static_cast<size_t>(i + 1);
  }
  bool padding(int i, int j, int k) const { return i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz; }
  double coord(int axis, int i) const { return lo[axis] + (i + 0.5) * h[axis]; }
};

// Evaluates the field at many points, batch by batch.
class Evaluator {
 public:
  explicit Evaluator(const Field& f) : f_(f) {}
  bool run(const std::vector<float>& xs, const std::vector<float>& ys, const std::vector<float>& zs,
           std::vector<float>& out, backend::RuntimeError& err) {
    out.resize(xs.size());
    for (size_t b = 0; b < xs.size(); b += kBatch) {
      size_t m = std::min(kBatch, xs.size() - b);
      if (!f_.eval(xs.data() + b, ys.data() + b, zs.data() + b, m, out.data() + b, err)) return false;
    }
    return true;
  }

 private:
  const Field& f_;
};

class Polygonizer {
 public:
  Polygonizer(const ImplicitJob& job, Mesh& out) : job_(job), out_(out), eval_(*job.field) {
    g_.nx = std::max(1, job.cells[0]);
    g_.ny = std::max(1, job.cells[1]);
    g_.nz = std::max(1, job.cells[2]);
    int n[3] = {g_.nx, g_.ny, g_.nz};
    for (int a = 0; a < 3; ++a) {
      g_.lo[a] = job.box[2 * a];
      g_.h[a] = (job.box[2 * a + 1] - job.box[2 * a]) / n[a];
    }
  }

  bool run(backend::RuntimeError& err) {
    return march(err) && refine(err) && compute_normals(err);
  }

 private:
  // Two z-layers of function values at a time: the memory is two planes, not the whole grid.
  size_t plane_size() const { return static_cast<size_t>(g_.nx + 2) * (g_.ny + 2); }
  size_t in_plane(int i, int j) const { return static_cast<size_t>(j + 1) * (g_.nx + 2) + static_cast<size_t>(i + 1); }

  // Values of layer k (the padding, k outside [0, nz) or i, j outside, is -1: outside).
  bool sample_layer(int k, std::vector<float>& plane, backend::RuntimeError& err) {
    plane.assign(plane_size(), -1.0f);
    if (k < 0 || k >= g_.nz) return true;
    xs_.clear(), ys_.clear(), zs_.clear();
    float z = static_cast<float>(g_.coord(2, k));
    for (int j = 0; j < g_.ny; ++j) {
      float y = static_cast<float>(g_.coord(1, j));
      for (int i = 0; i < g_.nx; ++i) {
        xs_.push_back(static_cast<float>(g_.coord(0, i)));
        ys_.push_back(y);
        zs_.push_back(z);
      }
    }
    if (!eval_.run(xs_, ys_, zs_, f_, err)) return false;
    size_t p = 0;
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) plane[in_plane(i, j)] = f_[p++];
    return true;
  }

  float value(const std::array<int, 3>& p) const {
    const auto& plane = p[2] == layer_z_ ? values_lo_ : values_hi_;
    return plane[in_plane(p[0], p[1])];
  }

  std::array<int, 3> corner(int i, int j, int k, int c) const { return {i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)}; }

  // Every tetrahedron edge joins a grid point to one of its 7 neighbours p + d, d in {0,1}^3 \ 0
  // (the Kuhn split orders each tetrahedron's corners componentwise). Edge vertices are cached per
  // (lower point, direction) in two z-layers, swapped as the march moves up: no hash map.
  static int direction(const std::array<int, 3>& d) { return d[0] + 2 * d[1] + 4 * d[2] - 1; }
  uint32_t& edge_slot(const std::array<int, 3>& lo, int dir) {
    size_t p = static_cast<size_t>(lo[1] + 1) * (g_.nx + 2) + static_cast<size_t>(lo[0] + 1);
    auto& layer = lo[2] == layer_z_ ? layer_lo_ : layer_hi_;
    return layer[p * 7 + dir];
  }

  // The vertex on the edge between grid points a and b (one inside, one outside).
  uint32_t edge_vertex(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    bool a_low = a[0] <= b[0] && a[1] <= b[1] && a[2] <= b[2];
    const std::array<int, 3>& lo = a_low ? a : b;
    const std::array<int, 3>& hi = a_low ? b : a;
    uint32_t& slot = edge_slot(lo, direction({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));
    if (slot != kNone) return slot;
    slot = static_cast<uint32_t>(out_.positions.size());
    (lo[2] == layer_z_ ? dirty_lo_ : dirty_hi_).push_back(&slot - (lo[2] == layer_z_ ? layer_lo_ : layer_hi_).data());
    Edge e;
    bool a_in = value(a) > 0;  // NaN and 0 are outside
    e.in = a_in ? a : b;
    e.out = a_in ? b : a;
    e.fin = value(e.in);
    e.fout = value(e.out);
    e.cap = g_.padding(e.out[0], e.out[1], e.out[2]);
    double t = e.cap ? 0.5 : (std::isfinite(e.fout) ? e.fin / (e.fin - e.fout) : 0.5);
    e.t = static_cast<float>(std::clamp(t, 0.0, 1.0));
    edges_.push_back(e);
    out_.positions.push_back(position(e, e.t));
    return slot;
  }

  struct Edge {
    std::array<int, 3> in, out;
    float fin, fout, t;
    bool cap;
  };

  Vec3 position(const Edge& e, float t) const {
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
      double pin = g_.coord(a, e.in[a]), pout = g_.coord(a, e.out[a]);
      p[a] = static_cast<float>(pin + t * (pout - pin));
    }
    return p;
  }

  // quad[p]: bits for p, p+x, p+y, p+x+y inside, for one layer.
  void quads(const std::vector<float>& plane, std::vector<uint8_t>& quad) const {
    const size_t row = static_cast<size_t>(g_.nx + 2);
    quad.assign(plane.size(), 0);
    for (size_t p = 0; p + row + 1 < plane.size(); ++p)
      quad[p] = static_cast<uint8_t>((plane[p] > 0) | (plane[p + 1] > 0) << 1 | (plane[p + row] > 0) << 2 |
                                     (plane[p + row + 1] > 0) << 3);
  }

  bool march(backend::RuntimeError& err) {
    layer_lo_.assign(plane_size() * 7, kNone);
    layer_hi_.assign(plane_size() * 7, kNone);
    std::vector<uint8_t> quad_lo, quad_hi;
    if (!sample_layer(-1, values_lo_, err) || !sample_layer(0, values_hi_, err)) return false;
    quads(values_lo_, quad_lo);
    quads(values_hi_, quad_hi);
    for (int k = -1; k < g_.nz; ++k) {
      layer_z_ = k;
      for (int j = -1; j < g_.ny; ++j) {
        size_t base = in_plane(-1, j);
        for (int i = -1; i < g_.nx; ++i, ++base) {
          unsigned mask = quad_lo[base] | quad_hi[base] << 4;
          if (mask == 0 || mask == 0xFF) continue;  // no surface in this cube
          bool corners[8];
          for (int c = 0; c < 8; ++c) corners[c] = (mask >> c) & 1;
          for (const auto& tet : kTets) tetrahedron(i, j, k, tet, corners);
        }
      }
      // Move up one layer: the upper values, masks and edge cache become the lower ones.
      std::swap(layer_lo_, layer_hi_);
      std::swap(dirty_lo_, dirty_hi_);
      for (size_t d : dirty_hi_) layer_hi_[d] = kNone;
      dirty_hi_.clear();
      std::swap(values_lo_, values_hi_);
      std::swap(quad_lo, quad_hi);
      if (k + 1 < g_.nz) {
        if (!sample_layer(k + 2, values_hi_, err)) return false;
        quads(values_hi_, quad_hi);
      }
    }
    return true;
  }

  void tetrahedron(int i, int j, int k, const int (&tet)[4], const bool (&in)[8]) {
    std::array<int, 3> p[4];
    int ins[4], outs[4], ni = 0, no = 0;
    for (int v = 0; v < 4; ++v) {
      p[v] = corner(i, j, k, tet[v]);
      if (in[tet[v]]) ins[ni++] = v;
      else outs[no++] = v;
    }
    if (ni == 0 || ni == 4) return;
    if (ni == 1 || ni == 3) {
      int apex = ni == 1 ? ins[0] : outs[0];
      int* others = ni == 1 ? outs : ins;
      uint32_t a = edge_vertex(p[apex], p[others[0]]), b = edge_vertex(p[apex], p[others[1]]),
               c = edge_vertex(p[apex], p[others[2]]);
      emit(a, b, c, p, ins, ni, outs, no);
      return;
    }
    // Two in, two out: a quad of the four crossing edges, split into two triangles.
    uint32_t a = edge_vertex(p[ins[0]], p[outs[0]]), b = edge_vertex(p[ins[0]], p[outs[1]]),
             c = edge_vertex(p[ins[1]], p[outs[1]]), d = edge_vertex(p[ins[1]], p[outs[0]]);
    emit(a, b, c, p, ins, ni, outs, no);
    emit(a, c, d, p, ins, ni, outs, no);
  }

  // Adds a triangle facing from the inside vertices toward the outside ones (outward normal).
  void emit(uint32_t a, uint32_t b, uint32_t c, const std::array<int, 3> (&p)[4], const int* ins, int ni,
            const int* outs, int no) {
    const Vec3 &A = out_.positions[a], &B = out_.positions[b], &C = out_.positions[c];
    double n[3] = {(B[1] - A[1]) * (C[2] - A[2]) - (B[2] - A[2]) * (C[1] - A[1]),
                   (B[2] - A[2]) * (C[0] - A[0]) - (B[0] - A[0]) * (C[2] - A[2]),
                   (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0])};
    double dir[3] = {0, 0, 0};
    for (int a2 = 0; a2 < 3; ++a2) {
      for (int v = 0; v < no; ++v) dir[a2] += g_.coord(a2, p[outs[v]][a2]) / no;
      for (int v = 0; v < ni; ++v) dir[a2] -= g_.coord(a2, p[ins[v]][a2]) / ni;
    }
    double dot = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
    if (dot >= 0) out_.triangles.push_back({a, b, c});
    else out_.triangles.push_back({a, c, b});
  }

  // Regula falsi on the real function along each interior edge, all edges in one batch per step.
  bool refine(backend::RuntimeError& err) {
    std::vector<size_t> todo;
    for (size_t e = 0; e < edges_.size(); ++e)
      if (!edges_[e].cap && std::isfinite(edges_[e].fout)) todo.push_back(e);
    std::vector<float> lo(edges_.size(), 0.0f), hi(edges_.size(), 1.0f), flo(edges_.size()), fhi(edges_.size());
    for (size_t e : todo) flo[e] = edges_[e].fin, fhi[e] = edges_[e].fout;
    std::vector<float> xs, ys, zs, f;
    for (int step = 0; step < job_.refine_steps && !todo.empty(); ++step) {
      xs.clear(), ys.clear(), zs.clear();
      for (size_t e : todo) {
        Vec3 p = position(edges_[e], edges_[e].t);
        xs.push_back(p[0]), ys.push_back(p[1]), zs.push_back(p[2]);
      }
      if (!eval_.run(xs, ys, zs, f, err)) return false;
      for (size_t q = 0; q < todo.size(); ++q) {
        size_t e = todo[q];
        float v = f[q], t = edges_[e].t;
        if (!std::isfinite(v)) continue;
        if (v > 0) lo[e] = t, flo[e] = v;
        else hi[e] = t, fhi[e] = v;
        float denom = flo[e] - fhi[e];
        float next = denom != 0 ? lo[e] + (hi[e] - lo[e]) * flo[e] / denom : 0.5f * (lo[e] + hi[e]);
        edges_[e].t = std::clamp(next, lo[e], hi[e]);
      }
    }
    for (size_t e = 0; e < edges_.size(); ++e) out_.positions[e] = position(edges_[e], edges_[e].t);
    return true;
  }

  // Normals: minus the gradient (central differences, a tenth of a cell); caps face outward.
  bool compute_normals(backend::RuntimeError& err) {
    size_t n = out_.positions.size();
    out_.normals.assign(n, Vec3{0, 0, 0});
    std::vector<float> xs, ys, zs, f;
    for (int a = 0; a < 3; ++a)
      for (int s = -1; s <= 1; s += 2)
        for (size_t v = 0; v < n; ++v) {
          Vec3 p = out_.positions[v];
          p[a] += static_cast<float>(s * 0.1 * g_.h[a]);
          xs.push_back(p[0]), ys.push_back(p[1]), zs.push_back(p[2]);
        }
    if (!eval_.run(xs, ys, zs, f, err)) return false;
    for (size_t v = 0; v < n; ++v) {
      const Edge& e = edges_[v];
      Vec3 g;
      for (int a = 0; a < 3; ++a) g[a] = -(f[(2 * a + 1) * n + v] - f[2 * a * n + v]) / static_cast<float>(0.2 * g_.h[a]);
      if (e.cap)
        for (int a = 0; a < 3; ++a) g[a] = static_cast<float>(e.out[a] - e.in[a]);
      float len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      if (!(len > 0) || !std::isfinite(len)) {
        for (int a = 0; a < 3; ++a) g[a] = static_cast<float>(e.out[a] - e.in[a]);
        len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      }
      for (int a = 0; a < 3; ++a) out_.normals[v][a] = g[a] / len;
    }
    return true;
  }

  const ImplicitJob& job_;
  Mesh& out_;
  Evaluator eval_;
  Grid g_;
  std::vector<float> values_lo_, values_hi_;  // function values of z-layers k and k+1
  std::vector<float> xs_, ys_, zs_, f_;        // sampling scratch
  static constexpr uint32_t kNone = UINT32_MAX;
  std::vector<uint32_t> layer_lo_, layer_hi_;  // edge vertices by (lower point, direction) in z-layers k, k+1
  std::vector<size_t> dirty_lo_, dirty_hi_;    // slots set in each layer, reset when it is reused
  int layer_z_ = 0;
  std::vector<Edge> edges_;  // edges_[v] made vertex v
};

}  // namespace

bool polygonize_implicit(const ImplicitJob& job, Mesh& out, backend::RuntimeError& err) {
  out = Mesh{};
  if (!job.field) {
    err.message = "the implicit polygonizer needs a field";
    return false;
  }
  return Polygonizer(job, out).run(err);
}

bool KernelField::eval(const float* x, const float* y, const float* z, size_t n, float* out,
                       backend::RuntimeError& err) const {
  std::vector<float> ts(n, t_);
  std::vector<float> extra(k_.num_outputs() > 1 ? n * (k_.num_outputs() - 1) : 0);
  const float* in[4] = {x, y, z, ts.data()};
  std::vector<float*> outs(k_.num_outputs());
  outs[0] = out;
  for (size_t o = 1; o < outs.size(); ++o) outs[o] = extra.data() + (o - 1) * n;
  return k_.eval_batch(in, outs.data(), n, err);
}

}  // namespace fscript::mesh
