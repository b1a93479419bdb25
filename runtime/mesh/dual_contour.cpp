// Dual contouring: samples, Hermite data on sign-change edges (batched evaluation), a QEF vertex per
// sheet of each dual cell, cells merged by the octree, a polygon per edge wound to leave the solid.
#include "runtime/mesh/dual_contour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "runtime/mesh/dc_octree.h"
#include "runtime/mesh/flat_index.h"
#include "runtime/mesh/octree.h"

namespace fscript::mesh {
namespace {

constexpr int kRefineSteps = 4;  // regula falsi steps per crossing
// The central differences' step, in cells: a crossing closer than this to a sharp edge gets a normal
// blended from both faces (the QEF then misplaces the edge's vertices), so small, but large enough
// that float rounding of the samples stays far below the differences.
constexpr double kProbe = 0.01;

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
  EvalTimer timed;
  return pts.empty() || f.eval(x.data(), y.data(), z.data(), pts.size(), out.data(), err);
}

// Every sample of the open bricks (every sample without a brick map); a sample of a decided brick
// gets +1 or -1 for its sign and `decided` set, until its value is needed (exact_ends).
bool sample(const Field& f, const BrickMap* bricks, Lattice& g, std::vector<uint8_t>& decided, size_t& evaluated,
            backends::RuntimeError& err) {
  size_t total = static_cast<size_t>(g.n[0] + 2) * (g.n[1] + 2) * (g.n[2] + 2);
  g.f.assign(total, -1.0f);
  decided.assign(total, 0);
  std::vector<float> x, y, z, out;
  std::vector<size_t> where;
  constexpr int B = BrickMap::kBrick;
  std::vector<float> xs(static_cast<size_t>(g.n[0]));
  for (int i = 0; i < g.n[0]; ++i) xs[static_cast<size_t>(i)] = float(g.coord(0, i));
  for (int k = 0; k < g.n[2]; ++k) {
    x.clear(), y.clear(), where.clear();
    for (int j = 0; j < g.n[1]; ++j)
      for (int i0 = 0; i0 < g.n[0]; i0 += B) {  // a brick's run of the row at a time
        int i1 = std::min(i0 + B, g.n[0]);
        BrickClass c = bricks ? bricks->at(i0 / B, j / B, k / B) : BrickClass::Open;
        size_t at = g.at(i0, j, k), n = static_cast<size_t>(i1 - i0);
        if (c == BrickClass::Open) {
          x.insert(x.end(), xs.begin() + i0, xs.begin() + i1);
          y.insert(y.end(), n, float(g.coord(1, j)));
          for (size_t q = 0; q < n; ++q) where.push_back(at + q);
        } else {
          std::fill_n(g.f.begin() + static_cast<std::ptrdiff_t>(at), n, c == BrickClass::Inside ? 1.0f : -1.0f);
          std::fill_n(decided.begin() + static_cast<std::ptrdiff_t>(at), n, uint8_t{1});
        }
      }
    z.assign(x.size(), float(g.coord(2, k)));
    out.resize(x.size());
    EvalTimer timed;
    if (!x.empty() && !f.eval(x.data(), y.data(), z.data(), x.size(), out.data(), err)) return false;
    for (size_t q = 0; q < where.size(); ++q) g.f[where[q]] = out[q];
    evaluated += x.size();
  }
  return true;
}

// Every sign-change edge of the lattice, padding included, as its lower sample and axis.
std::vector<Crossing> sign_changes(const Lattice& g) {
  std::vector<uint8_t> in(g.f.size());
  for (size_t q = 0; q < in.size(); ++q) in[q] = g.f[q] > 0;
  const size_t stride[3] = {1, static_cast<size_t>(g.n[0] + 2), static_cast<size_t>(g.n[0] + 2) * (g.n[1] + 2)};
  std::vector<Crossing> out;
  const size_t len = stride[1];
  auto constant = [&](size_t row) {  // the row's samples all on one side, that of its first
    return std::find(in.begin() + static_cast<std::ptrdiff_t>(row), in.begin() + static_cast<std::ptrdiff_t>(row + len),
                     in[row] ^ 1) == in.begin() + static_cast<std::ptrdiff_t>(row + len);
  };
  for (int k = -1; k <= g.n[2]; ++k)
    for (int j = -1; j <= g.n[1]; ++j) {
      size_t row = g.at(-1, j, k);
      bool last[3] = {false, j == g.n[1], k == g.n[2]};
      // Most rows are far from the surface: no change along them or to the rows above and behind.
      if (constant(row) && (last[1] || (in[row + stride[1]] == in[row] && constant(row + stride[1]))) &&
          (last[2] || (in[row + stride[2]] == in[row] && constant(row + stride[2]))))
        continue;
      for (int i = -1; i <= g.n[0]; ++i) {
        size_t q = row + static_cast<size_t>(i + 1);
        last[0] = i == g.n[0];
        for (int a = 0; a < 3; ++a)
          if (!last[a] && in[q] != in[q + stride[a]]) out.push_back(Crossing{{i, j, k}, a, in[q] != 0, {0, 0, 0}, {0, 0, 0}});
      }
    }
  return out;
}

// The values at the ends of the crossing edges that lie in decided bricks, so regula falsi starts
// from the same brackets as on the dense lattice (the same mesh). False when a value contradicts its
// brick's bound (the caller samples densely instead).
bool exact_ends(const Field& f, Lattice& g, std::vector<uint8_t>& decided, const std::vector<Crossing>& xs, size_t& evaluated,
                bool& sound, backends::RuntimeError& err) {
  std::vector<size_t> where;
  for (const Crossing& c : xs)
    for (int end = 0; end < 2; ++end) {
      int s[3] = {c.s[0], c.s[1], c.s[2]};
      s[c.axis] += end;
      size_t at = g.at(s[0], s[1], s[2]);
      if (g.padding(s) || decided[at] != 1) continue;
      decided[at] = 2;
      where.push_back(at);
    }
  std::vector<std::array<double, 3>> pts;
  for (size_t at : where) {
    size_t nx = static_cast<size_t>(g.n[0] + 2), ny = static_cast<size_t>(g.n[1] + 2);
    int i = static_cast<int>(at % nx) - 1, j = static_cast<int>(at / nx % ny) - 1, k = static_cast<int>(at / (nx * ny)) - 1;
    pts.push_back({g.coord(0, i), g.coord(1, j), g.coord(2, k)});
  }
  std::vector<float> fv;
  if (!eval_points(f, pts, fv, err)) return false;
  evaluated += pts.size();
  for (size_t q = 0; q < where.size(); ++q) {
    sound = sound && (fv[q] > 0) == (g.f[where[q]] > 0);
    g.f[where[q]] = fv[q];
  }
  return true;
}

// One component of the gradient at a point on the surface (f = 0 there) from its probes `step`
// either side: central where both are defined, one-sided where one is, 0 where neither.
double gradient(float plus, float minus, double step) {
  bool p = std::isfinite(plus), m = std::isfinite(minus);
  if (p && m) return (double(plus) - minus) / (2 * step);
  return p ? plus / step : m ? -minus / step : 0.0;
}

// Hermite data for every crossing: a real edge gets its crossing by regula falsi and its normal from
// the gradient (central differences, kProbe cells), an edge into the padding gets the box face.
bool hermite(const Field& f, const Lattice& g, std::vector<Crossing>& out, backends::RuntimeError& err) {
  const std::vector<float>& v = g.f;
  std::vector<size_t> real;
  std::vector<double> lo_t, hi_t, lo_f, hi_f;  // bracket along the edge (t in [0, 1]) and f there
  for (size_t e = 0; e < out.size(); ++e) {
    Crossing& c = out[e];
    int a = c.axis, s[3] = {c.s[0], c.s[1], c.s[2]}, t[3] = {c.s[0], c.s[1], c.s[2]};
    ++t[a];
    for (int b = 0; b < 3; ++b) c.p[b] = g.coord(b, s[b]);
    if (g.padding(s) || g.padding(t)) {  // the box face, facing out of the solid
      bool upper_pad = g.padding(t);
      c.p[a] = upper_pad ? g.end(a) : g.lo[a];
      c.normal[a] = upper_pad ? 1 : -1;
    } else {
      real.push_back(e);
      lo_t.push_back(0), hi_t.push_back(1), lo_f.push_back(v[g.at(s[0], s[1], s[2])]), hi_f.push_back(v[g.at(t[0], t[1], t[2])]);
    }
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
    double d = lo_f[r] - hi_f[r];  // NaN or infinite where the function is undefined: bisect instead
    return d != 0 && std::isfinite(d) ? lo_t[r] + (hi_t[r] - lo_t[r]) * lo_f[r] / d : 0.5 * (lo_t[r] + hi_t[r]);
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
        q[a] += sgn * kProbe * g.h[a];
        probes.push_back(q);
      }
  }
  if (!eval_points(f, probes, fv, err)) return false;
  for (size_t r = 0; r < real.size(); ++r) {
    Crossing& c = out[real[r]];
    for (int a = 0; a < 3; ++a) c.normal[a] = -gradient(fv[6 * r + 2 * a], fv[6 * r + 2 * a + 1], kProbe * g.h[a]);
    if (!(std::abs(c.normal[0]) + std::abs(c.normal[1]) + std::abs(c.normal[2]) > 0))
      c.normal[c.axis] = c.lower_inside ? 1 : -1;  // no gradient at all: the edge's own direction
  }
  return true;
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

// The sheets the crossings touch, each with the planes of its crossings; ids[e] names
// the sheets of crossing e's four cells, in winding order.
std::vector<SheetVertex> sheets(const Lattice& g, const std::vector<Crossing>& xs, std::vector<std::array<uint32_t, 4>>& ids) {
  FlatIndex sheet_id(xs.size());
  std::vector<SheetVertex> out;
  ids.clear();
  for (const Crossing& c : xs) {
    int cells[4][3], inside[3] = {c.s[0], c.s[1], c.s[2]};
    if (!c.lower_inside) ++inside[c.axis];
    cells_of(c, cells);
    std::array<uint32_t, 4> id;
    for (int q = 0; q < 4; ++q) {
      const int* cell = cells[q];
      int in = (inside[0] - cell[0]) | (inside[1] - cell[1]) << 1 | (inside[2] - cell[2]) << 2;
      uint64_t key = uint64_t(g.cell(cell)) * 64 + uint64_t(sheet_of(g, cell, in, in ^ (1 << c.axis)));
      auto [sheet, fresh] = sheet_id.try_emplace(key, static_cast<uint32_t>(out.size()));
      if (fresh) out.push_back(SheetVertex{{cell[0], cell[1], cell[2]}, Qef{}});
      out[sheet].qef.add(c.p, c.normal);
      id[static_cast<size_t>(q)] = sheet;
    }
    ids.push_back(id);
  }
  return out;
}

// One polygon per crossing over its cells' output vertices, wound to face out of the solid; where
// merged cells repeat a vertex the quad becomes a triangle, or nothing inside a merged cell.
void polygons(const std::vector<Crossing>& xs, const std::vector<std::array<uint32_t, 4>>& ids,
              const std::vector<uint32_t>& vertex_of, Mesh& out) {
  for (size_t e = 0; e < xs.size(); ++e) {
    uint32_t ring[4];
    int n = 0;
    for (int q = 0; q < 4; ++q) {
      uint32_t v = vertex_of[ids[e][static_cast<size_t>(q)]];
      if (n == 0 || ring[n - 1] != v) ring[n++] = v;
    }
    if (n > 1 && ring[n - 1] == ring[0]) --n;
    if (n < 3) continue;
    if (!xs[e].lower_inside) std::reverse(ring, ring + n);  // the solid above: the polygon faces -axis
    out.triangles.push_back({ring[0], ring[1], ring[2]});
    if (n == 4) out.triangles.push_back({ring[0], ring[2], ring[3]});
  }
}

// The lattice sampled (pruned by the field's bounds when it has them) and its Hermite data.
bool sample_crossings(const ImplicitJob& job, Lattice& g, std::vector<Crossing>& xs, backends::RuntimeError& err) {
  std::unique_ptr<BrickMap> bricks = job_bricks(job);
  PruneStats st = bricks ? bricks->stats() : PruneStats{};
  st.points = static_cast<size_t>(g.n[0]) * g.n[1] * g.n[2];
  std::vector<uint8_t> decided;
  bool sound = true;
  bool ok = sample(*job.field, bricks.get(), g, decided, st.evaluated, err);
  if (ok) xs = sign_changes(g);
  ok = ok && exact_ends(*job.field, g, decided, xs, st.evaluated, sound, err);
  if (ok && !sound) {  // a bound the function contradicts: the dense lattice instead
    ++st.fallbacks;
    st.evaluated = 0;
    ok = sample(*job.field, nullptr, g, decided, st.evaluated, err);
    if (ok) xs = sign_changes(g);
  }
  add_prune_totals(st);
  if (job.stats) *job.stats = st;
  return ok && hermite(*job.field, g, xs, err);
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
  std::vector<Crossing> xs;
  if (!sample_crossings(job, g, xs, err)) return false;
  std::vector<std::array<uint32_t, 4>> ids;
  std::vector<SheetVertex> sv = sheets(g, xs, ids);
  MergedVertices mv = merge_cells(g, sv, job.mesher.tolerance);
  out.positions.reserve(mv.positions.size());
  for (const auto& p : mv.positions) out.positions.push_back({float(p[0]), float(p[1]), float(p[2])});
  polygons(xs, ids, mv.of_sheet, out);
  double h = std::min({g.h[0], g.h[1], g.h[2]});
  stats.cells = mv.positions.size();
  stats.merged = mv.merged;
  stats.triangles = out.triangles.size();
  for (double r : mv.rms) stats.max_error = std::max(stats.max_error, r / h);
  // No vertex normals: a vertex on a sharp edge has no one normal, and its faces' mean would shade
  // both sides wrong; without them every output is shaded flat (glTF and VRML97 viewers too).
  return true;
}

void DualContourStats::add(const DualContourStats& o) {
  cells += o.cells, merged += o.merged, triangles += o.triangles, jobs += o.jobs;
  max_error = std::max(max_error, o.max_error);
}

namespace {
std::mutex totals_lock;  // frames are meshed in parallel
DualContourStats totals;
}  // namespace

DualContourStats dual_contour_totals() {
  std::lock_guard<std::mutex> hold(totals_lock);
  return totals;
}

bool polygonize(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err) {
  DualContourStats st;
  switch (job.mesher.kind) {
    case Mesher::MarchingTetrahedra: return polygonize_implicit(job, out, err);
    case Mesher::DualContouring: {
      if (!dual_contour(job, out, st, err)) return false;
      st.jobs = 1;
      std::lock_guard<std::mutex> hold(totals_lock);
      totals.add(st);
      return true;
    }
  }
  return false;
}

}  // namespace fscript::mesh
