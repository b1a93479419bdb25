// Marching tetrahedra with refinement. Grid point (i, j, k), i in [-1, n], sits at
// lo + (i + 0.5) * h: points -1 and n lie half a cell outside the box and are the padding, so an
// edge from the padding to an inside point crosses the box face exactly at its midpoint.
// Threads march contiguous z-slabs; a slab refers to the vertices on the plane it shares with the
// slab below by placeholders, resolved when the slabs are merged in order, so the mesh is the
// same, vertex for vertex, as a single-threaded run. Refinement and normals split the vertices.
#include "runtime/mesh/implicit.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace fscript::mesh {
namespace {

constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
constexpr size_t kBatch = 8192;
constexpr uint32_t kNone = UINT32_MAX;
constexpr uint32_t kPlaceholder = 0x80000000u;  // ids from here on name a vertex of the slab below

struct Grid {
  int nx, ny, nz;  // samples inside the box per axis
  double lo[3], h[3];
  bool padding(int i, int j, int k) const { return i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz; }
  double coord(int axis, int i) const { return lo[axis] + (i + 0.5) * h[axis]; }
  size_t plane_size() const { return static_cast<size_t>(nx + 2) * (ny + 2); }
  size_t in_plane(int i, int j) const { return static_cast<size_t>(j + 1) * (nx + 2) + static_cast<size_t>(i + 1); }
};

bool evaluate(const Field& f, const std::vector<float>& xs, const std::vector<float>& ys, const std::vector<float>& zs,
              std::vector<float>& out, backend::RuntimeError& err) {
  out.resize(xs.size());
  for (size_t b = 0; b < xs.size(); b += kBatch) {
    size_t m = std::min(kBatch, xs.size() - b);
    if (!f.eval(xs.data() + b, ys.data() + b, zs.data() + b, m, out.data() + b, err)) return false;
  }
  return true;
}

// The grid edge a vertex lies on: from an inside point to an outside one.
struct Edge {
  std::array<int, 3> in, out;
  float fin, fout, t;
  bool cap;  // the outside point is padding: the vertex sits on the box face
};

Vec3 position(const Grid& g, const Edge& e, float t) {
  Vec3 p;
  for (int a = 0; a < 3; ++a) {
    double pin = g.coord(a, e.in[a]), pout = g.coord(a, e.out[a]);
    p[a] = static_cast<float>(pin + t * (pout - pin));
  }
  return p;
}

// Marches cube layers [k0, k1). Vertices are local; those on plane k0 (made by the slab below,
// when k0 > -1) are placeholders into `boundary`.
class Slab {
 public:
  Slab(const Grid& g, const Field& f, int k0, int k1) : g_(g), f_(f), k0_(k0), k1_(k1) {}

  bool run(backend::RuntimeError& err) {
    size_t plane = g_.plane_size();
    cache_lo_.assign(plane * 7, kNone);
    cache_hi_.assign(plane * 7, kNone);
    std::vector<uint8_t> quad_lo, quad_hi;
    if (!sample(k0_, values_lo_, err) || !sample(k0_ + 1, values_hi_, err)) return false;
    quads(values_lo_, quad_lo);
    quads(values_hi_, quad_hi);
    for (int k = k0_; k < k1_; ++k) {
      z_ = k;
      for (int j = -1; j < g_.ny; ++j) {
        size_t base = g_.in_plane(-1, j);
        for (int i = -1; i < g_.nx; ++i, ++base) {
          unsigned mask = quad_lo[base] | quad_hi[base] << 4;
          if (mask == 0 || mask == 0xFF) continue;  // no surface in this cube
          bool corners[8];
          for (int c = 0; c < 8; ++c) corners[c] = (mask >> c) & 1;
          for (const auto& tet : kTets) tetrahedron(i, j, k, tet, corners);
        }
      }
      // Move up one layer: the upper values, masks and edge cache become the lower ones.
      std::swap(cache_lo_, cache_hi_);
      std::swap(dirty_lo_, dirty_hi_);
      for (size_t d : dirty_hi_) cache_hi_[d] = kNone;
      dirty_hi_.clear();
      std::swap(values_lo_, values_hi_);
      std::swap(quad_lo, quad_hi);
      if (k + 1 < k1_) {
        if (!sample(k + 2, values_hi_, err)) return false;
        quads(values_hi_, quad_hi);
      }
    }
    return true;
  }

  std::vector<Vec3> positions;
  std::vector<Edge> edges;                       // edges[v] made local vertex v
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<size_t> boundary;                  // placeholder n names cache slot boundary[n] of plane k0
  const std::vector<uint32_t>& top_cache() const { return cache_lo_; }  // plane k1's slots, after run()

 private:
  bool sample(int k, std::vector<float>& plane, backend::RuntimeError& err) {
    plane.assign(g_.plane_size(), -1.0f);
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
    if (!evaluate(f_, xs_, ys_, zs_, f_out_, err)) return false;
    size_t p = 0;
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i) plane[g_.in_plane(i, j)] = f_out_[p++];
    return true;
  }

  // quad[p]: bits for p, p+x, p+y, p+x+y inside (NaN and 0 are outside).
  void quads(const std::vector<float>& plane, std::vector<uint8_t>& quad) const {
    const size_t row = static_cast<size_t>(g_.nx + 2);
    quad.assign(plane.size(), 0);
    for (size_t p = 0; p + row + 1 < plane.size(); ++p)
      quad[p] = static_cast<uint8_t>((plane[p] > 0) | (plane[p + 1] > 0) << 1 | (plane[p + row] > 0) << 2 |
                                     (plane[p + row + 1] > 0) << 3);
  }

  float value(const std::array<int, 3>& p) const {
    return (p[2] == z_ ? values_lo_ : values_hi_)[g_.in_plane(p[0], p[1])];
  }

  std::array<int, 3> corner(int i, int j, int k, int c) const { return {i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)}; }

  // Every tetrahedron edge joins a grid point to a neighbour p + d, d in {0,1}^3 \ 0 (the Kuhn
  // split orders each tetrahedron's corners componentwise): vertices are cached per (lower point,
  // direction) in the two current z-layers.
  uint32_t edge_vertex(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    bool a_low = a[0] <= b[0] && a[1] <= b[1] && a[2] <= b[2];
    const std::array<int, 3>& lo = a_low ? a : b;
    const std::array<int, 3>& hi = a_low ? b : a;
    int dir = (hi[0] - lo[0]) + 2 * (hi[1] - lo[1]) + 4 * (hi[2] - lo[2]) - 1;
    bool low_layer = lo[2] == z_;
    size_t index = g_.in_plane(lo[0], lo[1]) * 7 + dir;
    uint32_t& slot = (low_layer ? cache_lo_ : cache_hi_)[index];
    if (slot != kNone) return slot;
    (low_layer ? dirty_lo_ : dirty_hi_).push_back(index);
    if (low_layer && lo[2] == k0_ && k0_ > -1 && dir < 3) {  // on the plane the slab below owns
      slot = kPlaceholder | static_cast<uint32_t>(boundary.size());
      boundary.push_back(index);
      return slot;
    }
    slot = static_cast<uint32_t>(positions.size());
    Edge e;
    bool a_in = value(a) > 0;
    e.in = a_in ? a : b;
    e.out = a_in ? b : a;
    e.fin = value(e.in);
    e.fout = value(e.out);
    e.cap = g_.padding(e.out[0], e.out[1], e.out[2]);
    double t = e.cap ? 0.5 : (std::isfinite(e.fout) ? e.fin / (e.fin - e.fout) : 0.5);
    e.t = static_cast<float>(std::clamp(t, 0.0, 1.0));
    edges.push_back(e);
    positions.push_back(position(g_, e, e.t));
    return slot;
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

  // Faces point from the inside corners toward the outside ones (outward normals).
  void emit(uint32_t a, uint32_t b, uint32_t c, const std::array<int, 3> (&p)[4], const int* ins, int ni,
            const int* outs, int no) {
    std::array<double, 3> dir = {0, 0, 0}, pa, pb, pc;
    for (int a2 = 0; a2 < 3; ++a2) {
      for (int v = 0; v < no; ++v) dir[a2] += g_.coord(a2, p[outs[v]][a2]) / no;
      for (int v = 0; v < ni; ++v) dir[a2] -= g_.coord(a2, p[ins[v]][a2]) / ni;
    }
    pa = approx(a), pb = approx(b), pc = approx(c);
    double n[3] = {(pb[1] - pa[1]) * (pc[2] - pa[2]) - (pb[2] - pa[2]) * (pc[1] - pa[1]),
                   (pb[2] - pa[2]) * (pc[0] - pa[0]) - (pb[0] - pa[0]) * (pc[2] - pa[2]),
                   (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0])};
    double dot = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
    if (dot >= 0) triangles.push_back({a, b, c});
    else triangles.push_back({a, c, b});
  }

  // The midpoint of the vertex's grid edge: orientation only, and the same whether the vertex is
  // this slab's or a placeholder, so every thread count decides every triangle alike.
  std::array<double, 3> approx(uint32_t v) const {
    if (!(v & kPlaceholder)) {
      const Edge& e = edges[v];
      std::array<double, 3> m;
      for (int a = 0; a < 3; ++a) m[a] = 0.5 * (g_.coord(a, e.in[a]) + g_.coord(a, e.out[a]));
      return m;
    }
    size_t slot = boundary[v & ~kPlaceholder];
    size_t point = slot / 7;
    int dir = static_cast<int>(slot % 7) + 1;
    int i = static_cast<int>(point % (g_.nx + 2)) - 1, j = static_cast<int>(point / (g_.nx + 2)) - 1;
    return {g_.coord(0, i) + 0.5 * (dir & 1) * g_.h[0], g_.coord(1, j) + 0.5 * ((dir >> 1) & 1) * g_.h[1], g_.coord(2, k0_)};
  }

  const Grid& g_;
  const Field& f_;
  int k0_, k1_, z_ = 0;
  std::vector<uint32_t> cache_lo_, cache_hi_;
  std::vector<size_t> dirty_lo_, dirty_hi_;
  std::vector<float> values_lo_, values_hi_, xs_, ys_, zs_, f_out_;
};

// Runs fn(begin, end) over [0, n) split into `threads` contiguous parts; false if any part fails.
template <class Fn>
bool split(size_t n, int threads, Fn fn, backend::RuntimeError& err) {
  int t = std::max(1, std::min<int>(threads, static_cast<int>(std::max<size_t>(1, n / 4096))));
  std::vector<backend::RuntimeError> errs(t);
  std::vector<char> ok(t, 1);
  std::vector<std::thread> pool;
  for (int k = 1; k < t; ++k) pool.emplace_back([&, k] { ok[k] = fn(n * k / t, n * (k + 1) / t, errs[k]); });
  ok[0] = fn(0, n / t, errs[0]);
  for (auto& th : pool) th.join();
  for (int k = 0; k < t; ++k)
    if (!ok[k]) {
      err = errs[k];
      return false;
    }
  return true;
}

// Regula falsi on the real function along each interior edge, every vertex in batches.
bool refine(const Grid& g, const Field& f, std::vector<Edge>& edges, Mesh& m, int steps, int threads,
            backend::RuntimeError& err) {
  return split(edges.size(), threads, [&](size_t b, size_t e, backend::RuntimeError& er) {
    std::vector<size_t> todo;
    for (size_t v = b; v < e; ++v)
      if (!edges[v].cap && std::isfinite(edges[v].fout)) todo.push_back(v);
    std::vector<float> lo(todo.size(), 0.0f), hi(todo.size(), 1.0f), flo(todo.size()), fhi(todo.size());
    for (size_t q = 0; q < todo.size(); ++q) flo[q] = edges[todo[q]].fin, fhi[q] = edges[todo[q]].fout;
    std::vector<float> xs, ys, zs, out;
    for (int step = 0; step < steps && !todo.empty(); ++step) {
      xs.clear(), ys.clear(), zs.clear();
      for (size_t v : todo) {
        Vec3 p = position(g, edges[v], edges[v].t);
        xs.push_back(p[0]), ys.push_back(p[1]), zs.push_back(p[2]);
      }
      if (!evaluate(f, xs, ys, zs, out, er)) return false;
      for (size_t q = 0; q < todo.size(); ++q) {
        Edge& ed = edges[todo[q]];
        float val = out[q], t = ed.t;
        if (!std::isfinite(val)) continue;
        if (val > 0) lo[q] = t, flo[q] = val;
        else hi[q] = t, fhi[q] = val;
        float denom = flo[q] - fhi[q];
        float next = denom != 0 ? lo[q] + (hi[q] - lo[q]) * flo[q] / denom : 0.5f * (lo[q] + hi[q]);
        ed.t = std::clamp(next, lo[q], hi[q]);
      }
    }
    for (size_t v = b; v < e; ++v) m.positions[v] = position(g, edges[v], edges[v].t);
    return true;
  }, err);
}

// Normals: minus the gradient (central differences, a tenth of a cell); caps face outward.
bool normals(const Grid& g, const Field& f, const std::vector<Edge>& edges, Mesh& m, int threads,
             backend::RuntimeError& err) {
  m.normals.assign(m.positions.size(), Vec3{0, 0, 0});
  return split(m.positions.size(), threads, [&](size_t b, size_t e, backend::RuntimeError& er) {
    size_t n = e - b;
    std::vector<float> xs, ys, zs, out;
    for (int a = 0; a < 3; ++a)
      for (int s = -1; s <= 1; s += 2)
        for (size_t v = b; v < e; ++v) {
          Vec3 p = m.positions[v];
          p[a] += static_cast<float>(s * 0.1 * g.h[a]);
          xs.push_back(p[0]), ys.push_back(p[1]), zs.push_back(p[2]);
        }
    if (!evaluate(f, xs, ys, zs, out, er)) return false;
    for (size_t q = 0; q < n; ++q) {
      const Edge& ed = edges[b + q];
      std::array<float, 3> d;
      for (int a = 0; a < 3; ++a) d[a] = -(out[(2 * a + 1) * n + q] - out[2 * a * n + q]) / static_cast<float>(0.2 * g.h[a]);
      float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (ed.cap || !(len > 0) || !std::isfinite(len)) {
        for (int a = 0; a < 3; ++a) d[a] = static_cast<float>(ed.out[a] - ed.in[a]);
        len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      }
      for (int a = 0; a < 3; ++a) m.normals[b + q][a] = d[a] / len;
    }
    return true;
  }, err);
}

// Concatenates the slabs in order, resolving each slab's placeholders against the one below.
bool merge(std::vector<Slab>& slabs, Mesh& m, std::vector<Edge>& edges, backend::RuntimeError& err) {
  std::vector<uint32_t> offset(slabs.size(), 0);
  for (size_t s = 0; s < slabs.size(); ++s) {
    offset[s] = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), slabs[s].positions.begin(), slabs[s].positions.end());
    edges.insert(edges.end(), slabs[s].edges.begin(), slabs[s].edges.end());
  }
  for (size_t s = 0; s < slabs.size(); ++s)
    for (auto t : slabs[s].triangles) {
      for (uint32_t& v : t) {
        if (!(v & kPlaceholder)) {
          v += offset[s];
          continue;
        }
        uint32_t below = s > 0 ? slabs[s - 1].top_cache()[slabs[s].boundary[v & ~kPlaceholder]] : kNone;
        if (below == kNone || (below & kPlaceholder)) {
          err.message = "internal error: a slab boundary vertex has no owner";
          return false;
        }
        v = below + offset[s - 1];
      }
      m.triangles.push_back(t);
    }
  return true;
}

}  // namespace

bool polygonize_implicit(const ImplicitJob& job, Mesh& out, backend::RuntimeError& err) {
  out = Mesh{};
  if (!job.field) {
    err.message = "the implicit polygonizer needs a field";
    return false;
  }
  Grid g;
  g.nx = std::max(1, job.cells[0]);
  g.ny = std::max(1, job.cells[1]);
  g.nz = std::max(1, job.cells[2]);
  int n[3] = {g.nx, g.ny, g.nz};
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = job.box[2 * a];
    g.h[a] = (job.box[2 * a + 1] - job.box[2 * a]) / n[a];
  }
  // Cube layers -1 .. nz-1, in contiguous slabs of at least 8 layers.
  int layers = g.nz + 1;
  int parts = std::max(1, std::min(job.threads, layers / 8));
  std::vector<Slab> slabs;
  for (int s = 0; s < parts; ++s) slabs.emplace_back(g, *job.field, -1 + layers * s / parts, -1 + layers * (s + 1) / parts);
  std::vector<backend::RuntimeError> errs(parts);
  std::vector<char> ok(parts, 1);
  std::vector<std::thread> pool;
  for (int s = 1; s < parts; ++s) pool.emplace_back([&, s] { ok[s] = slabs[s].run(errs[s]); });
  ok[0] = slabs[0].run(errs[0]);
  for (auto& th : pool) th.join();
  for (int s = 0; s < parts; ++s)
    if (!ok[s]) {
      err = errs[s];
      return false;
    }
  std::vector<Edge> edges;
  if (!merge(slabs, out, edges, err)) return false;
  return refine(g, *job.field, edges, out, job.refine_steps, job.threads, err) &&
         normals(g, *job.field, edges, out, job.threads, err);
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
