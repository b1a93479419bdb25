// Marching tetrahedra with refinement. Grid point (i, j, k), i in [-1, n], sits at
// lo + (i + 0.5) * h: points -1 and n lie half a cell outside the box and are the padding, so an
// edge from the padding to an inside point crosses the box face exactly at its midpoint.
// Threads march contiguous z-slabs; a slab refers to the vertices on the plane it shares with the
// slab below by placeholders, resolved when the slabs are merged in order, so the mesh is the
// same, vertex for vertex, as a single-threaded run. Refinement and normals split the vertices.
#include "engine/mesh/marching_tetrahedra.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "engine/mesh/sample_pruning.h"
#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
constexpr uint32_t kNone = UINT32_MAX;
constexpr uint32_t kPlaceholder = 0x80000000u;  // ids from here on name a vertex of the slab below

// The 19 edges of the Kuhn split of a cube (corner bits: 1 = +x, 2 = +y, 4 = +z) are the pairs
// (lo, lo | d) with lo & d == 0 and d != 0; for each of the 256 inside/outside corner masks the
// table lists the triangles as triples of those edges, oriented from the inside corners toward the
// outside ones. Orientation is decided once here on the unit cube with vertices at edge midpoints:
// a positive scaling of the axes keeps the sign, so it holds for every cell and every refinement.
struct CubeTable {
  uint8_t lo[19], dir[19];
  uint32_t used[256];                       // bit e: edge e carries a vertex
  uint8_t count[256];                       // triangles
  std::array<std::array<uint8_t, 3>, 12> tris[256];

  CubeTable() {
    int id[8][8], n = 0;
    for (int l = 0; l < 8; ++l)
      for (int d = 1; d < 8; ++d)
        if (!(l & d) && (l | d) < 8)
          lo[n] = static_cast<uint8_t>(l), dir[n] = static_cast<uint8_t>(d), id[l][l | d] = n++;
    for (int mask = 0; mask < 256; ++mask) {
      used[mask] = 0, count[mask] = 0;
      for (const auto& tet : kTets) add_tet(mask, tet, id);
    }
  }

 private:
  static std::array<double, 3> corner(int c) { return {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)}; }

  void add_tet(int mask, const int (&tet)[4], const int (&id)[8][8]) {
    int ins[4], outs[4], ni = 0, no = 0;
    for (int v : tet) ((mask >> v) & 1 ? ins[ni++] : outs[no++]) = v;
    if (ni == 0 || ni == 4) return;
    auto edge = [&](int a, int b) { return id[a & b][a | b]; };  // tet corners are nested: a & b is the lower
    if (ni == 1 || ni == 3) {
      int apex = ni == 1 ? ins[0] : outs[0];
      int* others = ni == 1 ? outs : ins;
      emit(mask, edge(apex, others[0]), edge(apex, others[1]), edge(apex, others[2]), ins, ni, outs, no);
      return;
    }
    int a = edge(ins[0], outs[0]), b = edge(ins[0], outs[1]), c = edge(ins[1], outs[1]), d = edge(ins[1], outs[0]);
    emit(mask, a, b, c, ins, ni, outs, no);
    emit(mask, a, c, d, ins, ni, outs, no);
  }

  std::array<double, 3> midpoint(int e) const {
    auto a = corner(lo[e]), b = corner(lo[e] | dir[e]);
    return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
  }

  void emit(int mask, int a, int b, int c, const int* ins, int ni, const int* outs, int no) {
    std::array<double, 3> dir_out{0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      for (int v = 0; v < no; ++v) dir_out[k] += corner(outs[v])[k] / no;
      for (int v = 0; v < ni; ++v) dir_out[k] -= corner(ins[v])[k] / ni;
    }
    auto pa = midpoint(a), pb = midpoint(b), pc = midpoint(c);
    double nrm[3] = {(pb[1] - pa[1]) * (pc[2] - pa[2]) - (pb[2] - pa[2]) * (pc[1] - pa[1]),
                     (pb[2] - pa[2]) * (pc[0] - pa[0]) - (pb[0] - pa[0]) * (pc[2] - pa[2]),
                     (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0])};
    bool keep = nrm[0] * dir_out[0] + nrm[1] * dir_out[1] + nrm[2] * dir_out[2] >= 0;
    tris[mask][count[mask]++] = {uint8_t(a), uint8_t(keep ? b : c), uint8_t(keep ? c : b)};
    used[mask] |= 1u << a | 1u << b | 1u << c;
  }
};

const CubeTable& cube_table() {
  static const CubeTable table;
  return table;
}

struct Grid {
  int nx, ny, nz;  // samples inside the box per axis
  double lo[3], h[3];
  bool padding(int i, int j, int k) const { return i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz; }
  double coord(int axis, int i) const { return lo[axis] + (i + 0.5) * h[axis]; }
  size_t plane_size() const { return static_cast<size_t>(nx + 2) * (ny + 2); }
  size_t in_plane(int i, int j) const { return static_cast<size_t>(j + 1) * (nx + 2) + static_cast<size_t>(i + 1); }
};

bool evaluate(const Field& f, const float* xs, const float* ys, const float* zs, size_t n, float* out,
              backends::RuntimeError& err) {
  EvalTimer timer;
  for (size_t b = 0; b < n; b += kEvalBatch)
    if (!f.eval(xs + b, ys + b, zs + b, std::min(kEvalBatch, n - b), out + b, err)) return false;
  return true;
}

// The grid edge a vertex lies on: from the inside point `in` one step to the outside point.
struct Edge {
  int32_t in[3];
  int8_t step[3];
  bool cap;  // the outside point is padding: the vertex sits on the box face
  float fin, fout, t;
};

inline Vec3 position(const Grid& g, const Edge& e, float t) {
  Vec3 p;
  for (int a = 0; a < 3; ++a) p[a] = static_cast<float>(g.coord(a, e.in[a]) + t * e.step[a] * g.h[a]);
  return p;
}

// Marches cube layers [k0, k1). Vertices are local; those on plane k0 (made by the slab below,
// when k0 > -1) are placeholders into `boundary`.
class Slab {
 public:
  Slab(const Grid& g, const Field& f, const BrickMap* bricks, int k0, int k1, support::ProgressJob* progress)
      : g_(g), f_(f), bricks_(bricks), progress_(progress), k0_(k0), k1_(k1) {}

  bool run(backends::RuntimeError& err) {
    size_t plane = g_.plane_size();
    cache_lo_.assign(plane * 7, kNone);
    cache_hi_.assign(plane * 7, kNone);
    values_lo_.assign(plane, -1.0f);
    values_hi_.assign(plane, -1.0f);
    exact_lo_.assign(plane, 1);
    exact_hi_.assign(plane, 1);
    plane_coordinates();
    std::vector<uint8_t> quad_lo(plane, 0), quad_hi(plane, 0);
    if (!sample(k0_, values_lo_, exact_lo_, inexact_lo_, err) ||
        !sample(k0_ + 1, values_hi_, exact_hi_, inexact_hi_, err))
      return false;
    quads(values_lo_, quad_lo);
    quads(values_hi_, quad_hi);
    for (int k = k0_; k < k1_; ++k) {
      z_ = k;
      if (progress_) progress_->advance(1);
      if ((inexact_lo_ || inexact_hi_) && !settle(quad_lo, quad_hi, err)) return false;
      for (int j = -1; j < g_.ny; ++j) {
        size_t base = g_.in_plane(-1, j);
        for (int i = -1; i < g_.nx; ++i, ++base) {
          if (i + 8 <= g_.nx && uniform8(quad_lo.data() + base, quad_hi.data() + base)) {
            i += 7, base += 7;  // eight cubes with no surface
            continue;
          }
          unsigned mask = quad_lo[base] | quad_hi[base] << 4;
          if (mask != 0 && mask != 0xFF) cube(i, j, base, mask);
        }
      }
      // Move up one layer: the upper values, masks and edge cache become the lower ones.
      std::swap(cache_lo_, cache_hi_);
      std::swap(dirty_lo_, dirty_hi_);
      for (size_t d : dirty_hi_) cache_hi_[d] = kNone;
      dirty_hi_.clear();
      std::swap(values_lo_, values_hi_);
      std::swap(exact_lo_, exact_hi_);
      std::swap(inexact_lo_, inexact_hi_);
      std::swap(quad_lo, quad_hi);
      if (k + 1 < k1_) {
        if (!sample(k + 2, values_hi_, exact_hi_, inexact_hi_, err)) return false;
        quads(values_hi_, quad_hi);
      }
    }
    return true;
  }

  std::vector<Edge> edges;                       // edges[v] made local vertex v
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<size_t> boundary;                  // placeholder n names cache slot boundary[n] of plane k0
  const std::vector<uint32_t>& top_cache() const { return cache_lo_; }  // plane k1's slots, after run()
  size_t evaluated = 0;  // grid samples evaluated
  bool unsound = false;  // a decided point's value had the other sign than its brick's bound

 private:
  // The x and y of every sample of a plane, row by row; only z changes from plane to plane.
  void plane_coordinates() {
    size_t n = static_cast<size_t>(g_.nx) * g_.ny;
    xs_.resize(n), ys_.resize(n), zs_.resize(n), f_out_.resize(n);
    size_t p = 0;
    for (int j = 0; j < g_.ny; ++j)
      for (int i = 0; i < g_.nx; ++i, ++p)
        xs_[p] = static_cast<float>(g_.coord(0, i)), ys_[p] = static_cast<float>(g_.coord(1, j));
  }

  // Fills the inside of `plane` with f on layer k; the padding ring stays at -1 (outside). Points of
  // decided bricks get +1 or -1 and exact[p] = 0 (`inexact` counts them): settle() evaluates those a
  // surface cube touches.
  bool sample(int k, std::vector<float>& plane, std::vector<uint8_t>& exact, size_t& inexact,
              backends::RuntimeError& err) {
    inexact = 0;
    std::fill(exact.begin(), exact.end(), uint8_t{1});
    if (k < 0 || k >= g_.nz) {
      std::fill(plane.begin(), plane.end(), -1.0f);
      return true;
    }
    float z = static_cast<float>(g_.coord(2, k));
    if (!bricks_ || bricks_->layer_open(k / BrickMap::kBrick)) {
      std::fill(zs_.begin(), zs_.end(), z);
      if (!evaluate_rows(z, err)) return false;
      evaluated += xs_.size();
      for (int j = 0; j < g_.ny; ++j)
        std::copy_n(f_out_.data() + static_cast<size_t>(j) * g_.nx, g_.nx, plane.data() + g_.in_plane(0, j));
      return true;
    }
    todo_.clear();
    constexpr int B = BrickMap::kBrick;
    for (int bj = 0; bj * B < g_.ny; ++bj)
      for (int bi = 0; bi * B < g_.nx; ++bi) {
        BrickClass c = bricks_->at(bi, bj, k / B);
        int i1 = std::min(g_.nx, bi * B + B), j1 = std::min(g_.ny, bj * B + B);
        size_t w = static_cast<size_t>(i1 - bi * B);
        for (int j = bj * B; j < j1; ++j) {
          size_t p = g_.in_plane(bi * B, j);
          if (c == BrickClass::Open) {
            todo_.push_back({static_cast<uint32_t>(p), static_cast<uint32_t>(w)});
            continue;
          }
          std::fill_n(plane.data() + p, w, c == BrickClass::Inside ? 1.0f : -1.0f);
          std::fill_n(exact.data() + p, w, uint8_t{0});
          inexact += w;
        }
      }
    return evaluate_points(plane, z, err);
  }

  // f_out_ = f on the plane at height z, as rows (the plane's xs_ and ys_ are row by row).
  bool evaluate_rows(float z, backends::RuntimeError& err) {
    EvalTimer timer;
    size_t nx = static_cast<size_t>(g_.nx), per = std::max<size_t>(1, kEvalBatch / nx);
    row_y_.resize(static_cast<size_t>(g_.ny)), row_z_.assign(static_cast<size_t>(g_.ny), z);
    for (size_t j = 0; j < row_y_.size(); ++j) row_y_[j] = ys_[j * nx];
    for (size_t j = 0; j < row_y_.size(); j += per) {
      size_t rows = std::min(per, row_y_.size() - j);
      if (!f_.eval_rows(xs_.data(), nx, row_y_.data() + j, row_z_.data() + j, rows, f_out_.data() + j * nx, err))
        return false;
    }
    return true;
  }

  // plane[p] = f at the runs of points todo_ lists (padded plane indices) on the plane at height z.
  bool evaluate_points(std::vector<float>& plane, float z, backends::RuntimeError& err) {
    size_t n = 0, row = static_cast<size_t>(g_.nx + 2);
    for (const Run& r : todo_) n += r.length;
    gx_.resize(n), gy_.resize(n), gz_.assign(n, z), gout_.resize(n);
    size_t q = 0;
    for (const Run& r : todo_) {
      size_t i = r.start % row - 1, j = r.start / row - 1;
      std::copy_n(xs_.data() + i, r.length, gx_.data() + q);
      std::fill_n(gy_.data() + q, r.length, ys_[j * static_cast<size_t>(g_.nx)]);
      q += r.length;
    }
    if (!evaluate(f_, gx_.data(), gy_.data(), gz_.data(), n, gout_.data(), err)) return false;
    q = 0;
    for (const Run& r : todo_) std::copy_n(gout_.data() + q, r.length, plane.data() + r.start), q += r.length;
    evaluated += n;
    return true;
  }

  // Every corner of every cube of the current layer with a sign change gets its real value: the
  // march reads values only there. The bound decided the sign, so only the value changes; a sign
  // that changes is a bug in a bound, and the job re-runs dense.
  bool settle(const std::vector<uint8_t>& quad_lo, const std::vector<uint8_t>& quad_hi, backends::RuntimeError& err) {
    const size_t row = static_cast<size_t>(g_.nx + 2);
    std::vector<uint32_t> pending[2];
    std::vector<uint8_t>* exact[2] = {&exact_lo_, &exact_hi_};
    for (int j = -1; j < g_.ny; ++j) {
      size_t base = g_.in_plane(-1, j);
      for (int i = -1; i < g_.nx; ++i, ++base) {
        if (i + 8 <= g_.nx && uniform8(quad_lo.data() + base, quad_hi.data() + base)) {
          i += 7, base += 7;
          continue;
        }
        unsigned mask = quad_lo[base] | quad_hi[base] << 4;
        if (mask == 0 || mask == 0xFF) continue;
        for (int c = 0; c < 8; ++c) {
          size_t p = base + (c & 1) + ((c >> 1) & 1) * row;
          uint8_t& e = (*exact[c >> 2])[p];
          if (e == 0) e = 2, pending[c >> 2].push_back(static_cast<uint32_t>(p));
        }
      }
    }
    std::vector<float>* values[2] = {&values_lo_, &values_hi_};
    size_t* inexact[2] = {&inexact_lo_, &inexact_hi_};
    for (int h = 0; h < 2; ++h) {
      if (pending[h].empty()) continue;
      std::vector<float> marks;
      todo_.clear();
      for (uint32_t p : pending[h]) marks.push_back((*values[h])[p]), todo_.push_back({p, 1});
      if (!evaluate_points(*values[h], static_cast<float>(g_.coord(2, z_ + h)), err)) return false;
      for (size_t q = 0; q < pending[h].size(); ++q) {
        if (((*values[h])[pending[h][q]] > 0) != (marks[q] > 0)) unsound = true;
        (*exact[h])[pending[h][q]] = 1;
      }
      *inexact[h] -= pending[h].size();
    }
    if (unsound) err.message = "internal error: an interval bound disagreed with the function";
    return !unsound;
  }

  // quad[p]: bits for p, p+x, p+y, p+x+y inside (NaN and 0 are outside). Two flat passes over
  // bytes, which the compiler vectorizes.
  void quads(const std::vector<float>& plane, std::vector<uint8_t>& quad) {
    const size_t row = static_cast<size_t>(g_.nx + 2), n = plane.size();
    inside_.resize(n + row + 1);
    uint8_t* in = inside_.data();
    const float* v = plane.data();
    for (size_t p = 0; p < n; ++p) in[p] = v[p] > 0;
    std::fill(in + n, in + n + row + 1, uint8_t{0});
    uint8_t* q = quad.data();
    for (size_t p = 0; p < n; ++p)
      q[p] = static_cast<uint8_t>(in[p] | in[p + 1] << 1 | in[p + row] << 2 | in[p + row + 1] << 3);
  }

  // Eight consecutive cubes all outside or all inside.
  static bool uniform8(const uint8_t* lo, const uint8_t* hi) {
    uint64_t a, b;
    std::memcpy(&a, lo, 8);
    std::memcpy(&b, hi, 8);
    return (a | b) == 0 || (a == 0x0F0F0F0F0F0F0F0Full && b == a);
  }

  void cube(int i, int j, size_t base, unsigned mask) {
    const CubeTable& t = cube_table();
    uint32_t v[19];
    for (uint32_t used = t.used[mask]; used; used &= used - 1) {
      int e = __builtin_ctz(used);
      v[e] = edge_vertex(i, j, base, t.lo[e], t.dir[e]);
    }
    for (int q = 0; q < t.count[mask]; ++q) {
      const auto& tri = t.tris[mask][q];
      triangles.push_back({v[tri[0]], v[tri[1]], v[tri[2]]});
    }
  }

  // The vertex on the grid edge from corner `lo` of cube (i, j, z_) in direction d: cached per
  // (grid point, direction) in the two current z-layers.
  uint32_t edge_vertex(int i, int j, size_t base, int lo, int d) {
    const size_t row = static_cast<size_t>(g_.nx + 2);
    size_t point = base + (lo & 1) + ((lo >> 1) & 1) * row;
    bool low_layer = !(lo & 4);
    size_t index = point * 7 + static_cast<size_t>(d - 1);
    uint32_t& slot = (low_layer ? cache_lo_ : cache_hi_)[index];
    if (slot != kNone) return slot;
    (low_layer ? dirty_lo_ : dirty_hi_).push_back(index);
    if (low_layer && z_ == k0_ && k0_ > -1 && d < 4) {  // on the plane the slab below owns
      slot = kPlaceholder | static_cast<uint32_t>(boundary.size());
      boundary.push_back(index);
      return slot;
    }
    slot = static_cast<uint32_t>(edges.size());
    int a[3] = {i + (lo & 1), j + ((lo >> 1) & 1), z_ + ((lo >> 2) & 1)};
    size_t other = point + (d & 1) + ((d >> 1) & 1) * row;
    float fa = (low_layer ? values_lo_ : values_hi_)[point];
    float fb = (low_layer && !(d & 4) ? values_lo_ : values_hi_)[other];
    Edge e;
    int sign = fa > 0 ? 1 : -1;
    for (int k = 0; k < 3; ++k) {
      int dk = (d >> k) & 1;
      e.in[k] = fa > 0 ? a[k] : a[k] + dk;
      e.step[k] = static_cast<int8_t>(sign * dk);
    }
    e.fin = fa > 0 ? fa : fb;
    e.fout = fa > 0 ? fb : fa;
    e.cap = g_.padding(e.in[0] + e.step[0], e.in[1] + e.step[1], e.in[2] + e.step[2]);
    double t = e.cap ? 0.5 : (std::isfinite(e.fout) ? e.fin / (static_cast<double>(e.fin) - e.fout) : 0.5);
    e.t = static_cast<float>(std::clamp(t, 0.0, 1.0));
    edges.push_back(e);
    return slot;
  }

  const Grid& g_;
  const Field& f_;
  const BrickMap* bricks_;  // null: every point is sampled
  support::ProgressJob* progress_;
  int k0_, k1_, z_ = 0;
  std::vector<uint32_t> cache_lo_, cache_hi_;
  std::vector<size_t> dirty_lo_, dirty_hi_;
  std::vector<float> values_lo_, values_hi_, xs_, ys_, zs_, f_out_, gx_, gy_, gz_, gout_, row_y_, row_z_;
  std::vector<uint8_t> inside_, exact_lo_, exact_hi_;
  size_t inexact_lo_ = 0, inexact_hi_ = 0;
  struct Run {
    uint32_t start, length;  // padded plane index of the first point; points along x
  };
  std::vector<Run> todo_;
};

// Runs fn(begin, end) over [0, n) split into `threads` contiguous parts; false if any part fails.
template <class Fn>
bool split(size_t n, int threads, Fn fn, backends::RuntimeError& err) {
  int t = std::max(1, std::min<int>(threads, static_cast<int>(std::max<size_t>(1, n / 4096))));
  size_t parts = static_cast<size_t>(t);
  return support::run_parts(
      t,
      [&](int k, backends::RuntimeError& e) {
        return fn(n * static_cast<size_t>(k) / parts, n * static_cast<size_t>(k + 1) / parts, e);
      },
      err);
}

// Regula falsi on the real function along each interior edge, in blocks of vertices so the
// scratch arrays stay in cache; then every vertex gets its position.
bool refine(const Grid& g, const Field& f, std::vector<Edge>& edges, Mesh& m, int steps, int threads,
            backends::RuntimeError& err) {
  m.positions.resize(edges.size());
  return split(
      edges.size(), threads,
      [&](size_t b, size_t e, backends::RuntimeError& er) {
        std::vector<uint32_t> todo;
        std::vector<float> lo, hi, flo, fhi, xs, ys, zs, out;
        for (size_t b0 = b; b0 < e; b0 += kEvalBatch) {
          size_t b1 = std::min(e, b0 + kEvalBatch);
          todo.clear();
          for (size_t v = b0; v < b1; ++v)
            if (!edges[v].cap && std::isfinite(edges[v].fout)) todo.push_back(static_cast<uint32_t>(v));
          size_t n = todo.size();
          lo.assign(n, 0.0f), hi.assign(n, 1.0f), flo.resize(n), fhi.resize(n);
          xs.resize(n), ys.resize(n), zs.resize(n), out.resize(n);
          for (size_t q = 0; q < n; ++q) flo[q] = edges[todo[q]].fin, fhi[q] = edges[todo[q]].fout;
          for (int step = 0; step < steps && n > 0; ++step) {
            for (size_t q = 0; q < n; ++q) {
              Vec3 p = position(g, edges[todo[q]], edges[todo[q]].t);
              xs[q] = p[0], ys[q] = p[1], zs[q] = p[2];
            }
            if (!evaluate(f, xs.data(), ys.data(), zs.data(), n, out.data(), er)) return false;
            for (size_t q = 0; q < n; ++q) {
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
          for (size_t v = b0; v < b1; ++v) m.positions[v] = position(g, edges[v], edges[v].t);
        }
        return true;
      },
      err);
}

// Minus the field's own gradient at vertices b0 .. b0 + n - 1 (ir::gradient_module), into d[3 q ..]
// (xs, ys, zs: the caller's point buffers, of n at least); `usable` false where a vertex has none
// (not finite, or zero): then the block takes differences.
bool gradient_normals(const Field& f, const Mesh& m, size_t b0, size_t n, float* xs, float* ys, float* zs,
                      std::vector<float>& d, backends::RuntimeError& err, bool& usable) {
  thread_local std::vector<float> g;
  g.resize(4 * n);
  for (size_t q = 0; q < n; ++q)
    xs[q] = m.positions[b0 + q][0], ys[q] = m.positions[b0 + q][1], zs[q] = m.positions[b0 + q][2];
  float* const o[4] = {g.data(), g.data() + n, g.data() + 2 * n, g.data() + 3 * n};
  {
    EvalTimer timed;
    if (!f.eval_gradient(xs, ys, zs, n, o, err)) return false;
  }
  usable = true;
  d.resize(3 * n);
  for (size_t q = 0; q < n && usable; ++q) {
    float len2 = 0;
    for (int a = 0; a < 3; ++a) d[3 * q + a] = -o[1 + a][q], len2 += o[1 + a][q] * o[1 + a][q];
    usable = len2 > 0 && std::isfinite(len2);
  }
  return true;
}

// Normals: minus the gradient (the field's own where it has one, else central differences a tenth
// of a cell apart); caps face outward.
bool normals(const Grid& g, const Field& f, const std::vector<Edge>& edges, Mesh& m, int threads,
             backends::RuntimeError& err) {
  m.normals.resize(m.positions.size());
  constexpr size_t kBlock = kEvalBatch / 6;
  const bool analytic = f.has_gradient();
  return split(
      m.positions.size(), threads,
      [&](size_t b, size_t e, backends::RuntimeError& er) {
        std::vector<float> xs(6 * kBlock), ys(6 * kBlock), zs(6 * kBlock), out(6 * kBlock), grad;
        for (size_t b0 = b; b0 < e; b0 += kBlock) {
          size_t n = std::min(kBlock, e - b0), p = 0;
          bool usable = false;
          if (analytic && !gradient_normals(f, m, b0, n, xs.data(), ys.data(), zs.data(), grad, er, usable))
            return false;
          if (!usable) {
            for (int a = 0; a < 3; ++a)
              for (int s = -1; s <= 1; s += 2)
                for (size_t v = b0; v < b0 + n; ++v, ++p) {
                  Vec3 q = m.positions[v];
                  q[a] += static_cast<float>(s * 0.1 * g.h[a]);
                  xs[p] = q[0], ys[p] = q[1], zs[p] = q[2];
                }
            if (!evaluate(f, xs.data(), ys.data(), zs.data(), p, out.data(), er)) return false;
          }
          for (size_t q = 0; q < n; ++q) {
            const Edge& ed = edges[b0 + q];
            std::array<float, 3> d;
            for (int a = 0; a < 3; ++a)
              d[a] = usable ? grad[3 * q + a]
                            : -(out[(2 * a + 1) * n + q] - out[2 * a * n + q]) / static_cast<float>(0.2 * g.h[a]);
            float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (ed.cap || !(len > 0) || !std::isfinite(len)) {
              for (int a = 0; a < 3; ++a) d[a] = static_cast<float>(ed.step[a]);
              len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            }
            for (int a = 0; a < 3; ++a) m.normals[b0 + q][a] = d[a] / len;
          }
        }
        return true;
      },
      err);
}

// Concatenates the slabs in order, resolving each slab's placeholders against the one below.
bool merge(std::vector<Slab>& slabs, Mesh& m, std::vector<Edge>& edges, backends::RuntimeError& err) {
  if (slabs.size() == 1) {  // nothing to resolve
    edges = std::move(slabs[0].edges);
    m.triangles = std::move(slabs[0].triangles);
    return true;
  }
  std::vector<uint32_t> offset(slabs.size(), 0);
  size_t vertices = 0, triangles = 0;
  for (size_t s = 0; s < slabs.size(); ++s) {
    offset[s] = static_cast<uint32_t>(vertices);
    vertices += slabs[s].edges.size(), triangles += slabs[s].triangles.size();
  }
  edges.reserve(vertices);
  m.triangles.reserve(triangles);
  for (size_t s = 0; s < slabs.size(); ++s) {
    edges.insert(edges.end(), slabs[s].edges.begin(), slabs[s].edges.end());
    std::vector<Edge>().swap(slabs[s].edges);
  }
  for (size_t s = 0; s < slabs.size(); ++s) {
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
    std::vector<std::array<uint32_t, 3>>().swap(slabs[s].triangles);
  }
  return true;
}

// Samples and marches the grid in z-slabs, then merges them. A slab whose decided points were
// contradicted by the function sets st.fallbacks (the caller runs again without bricks).
bool march(const Grid& g, const Field& f, const BrickMap* bricks, int threads, support::ProgressJob* progress,
           Mesh& out, std::vector<Edge>& edges, PruneStats& st, backends::RuntimeError& err) {
  // Cube layers -1 .. nz-1, in contiguous slabs of at least 8 layers.
  int layers = g.nz + 1;
  int parts = std::max(1, std::min(threads, layers / 8));
  std::vector<Slab> slabs;
  for (int s = 0; s < parts; ++s)
    slabs.emplace_back(g, f, bricks, -1 + layers * s / parts, -1 + layers * (s + 1) / parts, progress);
  bool ok = support::run_parts(
      parts, [&](int s, backends::RuntimeError& e) { return slabs[static_cast<size_t>(s)].run(e); }, err);
  st.evaluated = 0;
  for (const Slab& s : slabs) st.evaluated += s.evaluated, st.fallbacks += s.unsound;
  if (!ok) return false;
  out = Mesh{};
  edges.clear();
  return merge(slabs, out, edges, err);
}

}  // namespace

std::unique_ptr<BrickMap> job_bricks(const ImplicitJob& job) {
  if (!job.prune || !job.field->can_bound()) return nullptr;
  std::array<std::vector<float>, 3> axis;
  for (size_t a = 0; a < 3; ++a) {
    int n = std::max(1, job.cells[a]);
    double lo = job.box[2 * a], h = (job.box[2 * a + 1] - lo) / n;
    for (int i = 0; i < n; ++i) axis[a].push_back(static_cast<float>(lo + (i + 0.5) * h));
  }
  return std::make_unique<BrickMap>(*job.field, axis, job.threads);
}

bool polygonize_implicit(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err) {
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
  std::unique_ptr<BrickMap> bricks = job_bricks(job);
  PruneStats st = bricks ? bricks->stats() : PruneStats{};
  st.points = static_cast<size_t>(g.nx) * g.ny * g.nz;
  std::vector<Edge> edges;
  if (job.progress) job.progress->set_units(static_cast<uint64_t>(g.nz) + 1);  // cube layers
  bool ok = march(g, *job.field, bricks.get(), job.threads, job.progress, out, edges, st, err);
  if (!ok && st.fallbacks) ok = march(g, *job.field, nullptr, job.threads, job.progress, out, edges, st, err);
  add_prune_totals(st);
  if (job.stats) *job.stats = st;
  return ok && refine(g, *job.field, edges, out, job.refine_steps, job.threads, err) &&
      normals(g, *job.field, edges, out, job.threads, err);
}

}  // namespace fscript::mesh
