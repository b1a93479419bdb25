// Uniform dual contouring: samples, Hermite data on sign-change edges (batched evaluation), a QEF
// vertex per dual cell, a quad per edge wound so that its normal leaves the solid.
#include "runtime/mesh/dual_contour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "runtime/mesh/parametric.h"
#include "runtime/mesh/qef.h"

namespace fscript::mesh {
namespace {

constexpr int kRefineSteps = 4;  // regula falsi steps per crossing
// How far (in cells) a vertex may leave its cell, inside the box: a sharp corner whose tip pokes
// into a cell without a sample inside is placed by its neighbours' planes, just outside them
// (unit_dual_contour: corners of a turned cube within 0.1 of a cell; 1 cell away when kept in).
constexpr double kReach = 0.5;

// Samples at cell centres, indices -1 .. n per axis (the outer layer is padding, always outside).
struct Lattice {
  int n[3];
  double lo[3], h[3];
  double coord(int a, int i) const { return lo[a] + (i + 0.5) * h[a]; }
  size_t at(int i, int j, int k) const {
    return (static_cast<size_t>(k + 1) * (n[1] + 2) + static_cast<size_t>(j + 1)) * (n[0] + 2) + static_cast<size_t>(i + 1);
  }
  bool padding(const int s[3]) const {
    for (int a = 0; a < 3; ++a)
      if (s[a] < 0 || s[a] >= n[a]) return true;
    return false;
  }
  // Dual cells: the cube between samples c .. c + 1, c from -1 to n - 1 per axis.
  size_t cell(const int c[3]) const {
    return (static_cast<size_t>(c[2] + 1) * (n[1] + 1) + static_cast<size_t>(c[1] + 1)) * (n[0] + 1) + static_cast<size_t>(c[0] + 1);
  }
};

struct Crossing {
  int s[3];  // the edge's lower sample
  int axis;
  bool lower_inside;
  double p[3], normal[3];
};

// f over a list of points, in one batch.
bool eval_points(const Field& f, const std::vector<std::array<double, 3>>& pts, std::vector<float>& out,
                 backends::RuntimeError& err) {
  std::vector<float> x(pts.size()), y(pts.size()), z(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) x[i] = float(pts[i][0]), y[i] = float(pts[i][1]), z[i] = float(pts[i][2]);
  out.resize(pts.size());
  return pts.empty() || f.eval(x.data(), y.data(), z.data(), pts.size(), out.data(), err);
}

bool sample(const Field& f, const Lattice& g, std::vector<float>& v, backends::RuntimeError& err) {
  v.assign(static_cast<size_t>(g.n[0] + 2) * (g.n[1] + 2) * (g.n[2] + 2), -1.0f);
  std::vector<float> x, y, z, out(static_cast<size_t>(g.n[0]) * g.n[1]);
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) x.push_back(float(g.coord(0, i))), y.push_back(float(g.coord(1, j)));
  for (int k = 0; k < g.n[2]; ++k) {
    z.assign(x.size(), float(g.coord(2, k)));
    if (!f.eval(x.data(), y.data(), z.data(), x.size(), out.data(), err)) return false;
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) v[g.at(i, j, k)] = out[static_cast<size_t>(j) * g.n[0] + i];
  }
  return true;
}

// Every sign-change edge; a real edge gets its crossing by regula falsi and its normal from the
// gradient (central differences, a tenth of a cell), an edge into the padding gets the box face.
bool crossings(const Field& f, const Lattice& g, const std::vector<float>& v, std::vector<Crossing>& out,
               backends::RuntimeError& err) {
  std::vector<size_t> real;
  std::vector<double> lo_t, hi_t, lo_f, hi_f;  // bracket along the edge (t in [0, 1]) and f there
  for (int k = -1; k <= g.n[2]; ++k)
    for (int j = -1; j <= g.n[1]; ++j)
      for (int i = -1; i <= g.n[0]; ++i)
        for (int a = 0; a < 3; ++a) {
          int s[3] = {i, j, k}, t[3] = {i, j, k};
          if (++t[a] > g.n[a]) continue;
          float fs = v[g.at(s[0], s[1], s[2])], ft = v[g.at(t[0], t[1], t[2])];
          if ((fs > 0) == (ft > 0)) continue;
          Crossing c{{i, j, k}, a, fs > 0, {0, 0, 0}, {0, 0, 0}};
          for (int b = 0; b < 3; ++b) c.p[b] = g.coord(b, s[b]);
          if (g.padding(s) || g.padding(t)) {  // the box face, facing out of the solid
            bool upper_pad = g.padding(t);
            c.p[a] = upper_pad ? g.lo[a] + g.n[a] * g.h[a] : g.lo[a];
            c.normal[a] = upper_pad ? 1 : -1;
          } else {
            real.push_back(out.size());
            lo_t.push_back(0), hi_t.push_back(1), lo_f.push_back(fs), hi_f.push_back(ft);
          }
          out.push_back(c);
        }
  std::vector<std::array<double, 3>> pts(real.size());
  std::vector<float> fv;
  auto at = [&](size_t r, double t) {
    const Crossing& c = out[real[r]];
    std::array<double, 3> p{c.p[0], c.p[1], c.p[2]};
    p[c.axis] += t * g.h[c.axis];
    return p;
  };
  auto false_position = [&](size_t r) {  // where the chord through the bracket's ends crosses zero
    double d = lo_f[r] - hi_f[r];
    return d != 0 ? lo_t[r] + (hi_t[r] - lo_t[r]) * lo_f[r] / d : 0.5 * (lo_t[r] + hi_t[r]);
  };
  for (int step = 0; step < kRefineSteps; ++step) {
    std::vector<double> t(real.size());
    for (size_t r = 0; r < real.size(); ++r) t[r] = false_position(r), pts[r] = at(r, t[r]);
    if (!eval_points(f, pts, fv, err)) return false;
    for (size_t r = 0; r < real.size(); ++r) {
      bool same_as_lo = (fv[r] > 0) == (lo_f[r] > 0);
      (same_as_lo ? lo_t[r] : hi_t[r]) = t[r];
      (same_as_lo ? lo_f[r] : hi_f[r]) = fv[r];
    }
  }
  std::vector<std::array<double, 3>> probes;
  for (size_t r = 0; r < real.size(); ++r) {
    auto p = at(r, std::clamp(false_position(r), 0.0, 1.0));
    std::copy(p.begin(), p.end(), out[real[r]].p);
    for (int a = 0; a < 3; ++a)
      for (int sgn : {1, -1}) {
        auto q = p;
        q[a] += sgn * 0.1 * g.h[a];
        probes.push_back(q);
      }
  }
  if (!eval_points(f, probes, fv, err)) return false;
  for (size_t r = 0; r < real.size(); ++r)
    for (int a = 0; a < 3; ++a)  // minus the gradient: out of the solid (inside is f > 0)
      out[real[r]].normal[a] = -(double(fv[6 * r + 2 * a]) - fv[6 * r + 2 * a + 1]) / (0.2 * g.h[a]);
  return true;
}

// Manifold dual contouring: one vertex per sheet of surface in a cell. On the cell's boundary the
// inside corners join along cube edges and the outside corners across faces too (so neighbouring
// cells, which see the same signs on their shared face, cut it the same way); the regions of inside
// and of outside corners then tile the cube's boundary like a tree, and every sheet is the loop
// between one inside region and one outside region. A crossing (its inside corner, its outside
// corner) names its sheet; a cell the surface crosses twice gets two vertices, not one pinched by
// both sheets. Regions are named by their lowest corner.
struct CellSigns {
  uint8_t in_group[8], out_group[8];
};

// `flips`: bit 2 * axis + side set where the face decides the other way (its inside corners join).
CellSigns cell_signs(unsigned inside, unsigned flips) {
  int in_parent[8], out_parent[8];
  for (int c = 0; c < 8; ++c) in_parent[c] = out_parent[c] = c;
  auto find = [](int* parent, int x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  auto join = [&](int* parent, int a, int b) {
    a = find(parent, a), b = find(parent, b);
    parent[std::max(a, b)] = std::min(a, b);
  };
  for (int c = 0; c < 8; ++c)
    for (int d = c + 1; d < 8; ++d) {
      unsigned diff = static_cast<unsigned>(c ^ d), both_in = (inside >> c) & (inside >> d) & 1u;
      bool both_out = !((inside >> c) & 1u) && !((inside >> d) & 1u);
      if (__builtin_popcount(diff) == 1) {
        if (both_in) join(in_parent, c, d);
        if (both_out) join(out_parent, c, d);
      } else if (__builtin_popcount(diff) == 2) {  // a face diagonal: the face's own choice
        int axis = __builtin_ctz(~diff & 7u), side = (c >> axis) & 1;
        bool flipped = (flips >> (2 * axis + side)) & 1u;
        if (both_in && flipped) join(in_parent, c, d);
        if (both_out && !flipped) join(out_parent, c, d);
      }
    }
  CellSigns s;
  for (int c = 0; c < 8; ++c) s.in_group[c] = static_cast<uint8_t>(find(in_parent, c)), s.out_group[c] = static_cast<uint8_t>(find(out_parent, c));
  return s;
}

const CellSigns& signs_of(unsigned inside, unsigned flips) {
  static const auto table = [] {
    std::vector<CellSigns> t(256 * 64);
    for (unsigned m = 0; m < 256; ++m)
      for (unsigned f = 0; f < 64; ++f) t[m * 64 + f] = cell_signs(m, f);
    return t;
  }();
  return table[inside * 64 + flips];
}

unsigned inside_mask(const Lattice& g, const std::vector<float>& v, const int cell[3]) {
  unsigned m = 0;
  for (int c = 0; c < 8; ++c)
    m |= static_cast<unsigned>(v[g.at(cell[0] + (c & 1), cell[1] + ((c >> 1) & 1), cell[2] + ((c >> 2) & 1))] > 0) << c;
  return m;
}

// The faces of `cell` decided the other way. A face whose two inside corners lie on a diagonal, and
// are joined through the rest of the cell on both of its sides, is crossed by a tube of outside too
// thin for the grid: cut the usual way, the two cells' sheets would meet along both of the face's
// segments and share an edge four triangles use. Flipped, the tube is closed off on each side instead.
unsigned face_flips(const Lattice& g, const std::vector<float>& v, const int cell[3], unsigned inside) {
  unsigned flips = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      int on_face[4], n = 0;
      for (int c = 0; c < 8; ++c)
        if (((c >> axis) & 1) == side && ((inside >> c) & 1u)) on_face[n++ & 3] = c;
      if (n != 2 || __builtin_popcount(static_cast<unsigned>(on_face[0] ^ on_face[1])) != 2) continue;
      int other[3] = {cell[0], cell[1], cell[2]};
      other[axis] += side ? 1 : -1;
      if (other[axis] < -1 || other[axis] >= g.n[axis]) continue;
      const CellSigns& here = signs_of(inside, 0);
      const CellSigns& there = signs_of(inside_mask(g, v, other), 0);
      int p = on_face[0] ^ (1 << axis), q = on_face[1] ^ (1 << axis);  // the same samples, seen from there
      if (here.in_group[on_face[0]] == here.in_group[on_face[1]] && there.in_group[p] == there.in_group[q])
        flips |= 1u << (2 * axis + side);
    }
  return flips;
}

// The sheet of `cell` that the crossing between corners `in` and `out` lies on: 0 .. 63.
int sheet_of(const Lattice& g, const std::vector<float>& v, const int cell[3], int in, int out) {
  unsigned inside = inside_mask(g, v, cell);
  const CellSigns& s = signs_of(inside, face_flips(g, v, cell, inside));
  return s.in_group[in] * 8 + s.out_group[out];
}

// The four dual cells around an edge, in the order that winds the quad around +axis.
void cells_of(const Crossing& c, int out[4][3]) {
  int b = (c.axis + 1) % 3, d = (c.axis + 2) % 3;
  const int step[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int q = 0; q < 4; ++q) {
    for (int a = 0; a < 3; ++a) out[q][a] = c.s[a];
    out[q][b] -= step[q][0], out[q][d] -= step[q][1];
  }
}

}  // namespace

bool dual_contour(const ImplicitJob& job, Mesh& out, DualContourStats& stats, backends::RuntimeError& err) {
  out = Mesh{};
  stats = {};
  if (!job.field) {
    err.message = "the dual contouring mesher needs a field";
    return false;
  }
  Lattice g;
  for (int a = 0; a < 3; ++a) {
    g.n[a] = std::max(1, job.cells[static_cast<size_t>(a)]);
    g.lo[a] = job.box[static_cast<size_t>(2 * a)];
    g.h[a] = (job.box[static_cast<size_t>(2 * a + 1)] - g.lo[a]) / g.n[a];
  }
  std::vector<float> v;
  std::vector<Crossing> xs;
  if (!sample(*job.field, g, v, err) || !crossings(*job.field, g, v, xs, err)) return false;
  // One QEF per group of inside corners of each dual cell an edge touches, then its vertex.
  std::unordered_map<uint64_t, uint32_t> vertex_of;
  std::vector<Qef> qefs;
  std::vector<std::array<int, 3>> where;
  std::vector<std::array<uint32_t, 4>> quad_ids;
  for (const Crossing& c : xs) {
    int cells[4][3], inside[3] = {c.s[0], c.s[1], c.s[2]};
    if (!c.lower_inside) ++inside[c.axis];
    cells_of(c, cells);
    std::array<uint32_t, 4> ids;
    for (int q = 0; q < 4; ++q) {
      const int* cell = cells[q];
      int in = (inside[0] - cell[0]) | (inside[1] - cell[1]) << 1 | (inside[2] - cell[2]) << 2;
      uint64_t key = uint64_t(g.cell(cell)) * 64 + uint64_t(sheet_of(g, v, cell, in, in ^ (1 << c.axis)));
      auto [it, fresh] = vertex_of.try_emplace(key, static_cast<uint32_t>(qefs.size()));
      if (fresh) qefs.emplace_back(), where.push_back({cell[0], cell[1], cell[2]});
      qefs[it->second].add(c.p, c.normal);
      ids[static_cast<size_t>(q)] = it->second;
    }
    quad_ids.push_back(ids);
  }
  out.positions.resize(qefs.size());
  for (size_t q = 0; q < qefs.size(); ++q) {
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(g.coord(a, where[q][a]), g.lo[a]);  // a padding cell ends at the box face
      hi[a] = std::min(g.coord(a, where[q][a] + 1), g.lo[a] + g.n[a] * g.h[a]);
    }
    for (int a = 0; a < 3; ++a) {  // a corner whose tip no sample saw still gets its vertex (see kReach)
      lo[a] = std::max(lo[a] - kReach * g.h[a], g.lo[a]);
      hi[a] = std::min(hi[a] + kReach * g.h[a], g.lo[a] + g.n[a] * g.h[a]);
    }
    Qef::Solution s = qefs[q].solve(lo, hi);
    out.positions[q] = {float(s.x[0]), float(s.x[1]), float(s.x[2])};
    stats.max_error = std::max(stats.max_error, s.error);
  }
  stats.cells = qefs.size();
  for (size_t e = 0; e < xs.size(); ++e) {
    const Crossing& c = xs[e];
    const std::array<uint32_t, 4>& id = quad_ids[e];
    if (c.lower_inside) {  // the solid below, the quad faces +axis
      out.triangles.push_back({id[0], id[1], id[2]});
      out.triangles.push_back({id[0], id[2], id[3]});
    } else {
      out.triangles.push_back({id[0], id[2], id[1]});
      out.triangles.push_back({id[0], id[3], id[2]});
    }
  }
  face_normals_to_vertices(out);  // the area-weighted mean of the faces: sharp edges stay sharp in shape
  return true;
}

bool polygonize(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err) {
  DualContourStats st;
  switch (job.mesher) {
    case Mesher::MarchingTetrahedra: return polygonize_implicit(job, out, err);
    case Mesher::DualContouring: return dual_contour(job, out, st, err);
  }
  return false;
}

}  // namespace fscript::mesh
