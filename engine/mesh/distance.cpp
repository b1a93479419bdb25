// Point-to-mesh distances with a uniform grid over the triangles; point-triangle distance after
// Ericson, "Real-Time Collision Detection", 5.1.5.
#include "engine/mesh/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fscript::mesh {
namespace {

using D3 = std::array<double, 3>;
D3 d3(const Vec3& v) { return {v[0], v[1], v[2]}; }
D3 sub(D3 a, D3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(D3 a, D3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 mad(D3 a, D3 d, double t) { return {a[0] + d[0] * t, a[1] + d[1] * t, a[2] + d[2] * t}; }

D3 closest_on_triangle(D3 p, D3 a, D3 b, D3 c) {
  D3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  D3 bp = sub(p, b);
  double d3v = dot(ab, bp), d4 = dot(ac, bp);
  if (d3v >= 0 && d4 <= d3v) return b;
  double vc = d1 * d4 - d3v * d2;
  if (vc <= 0 && d1 >= 0 && d3v <= 0) return mad(a, ab, d1 / (d1 - d3v));
  D3 cp = sub(p, c);
  double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return mad(a, ac, d2 / (d2 - d6));
  double va = d3v * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3v) >= 0 && (d5 - d6) >= 0) return mad(b, sub(c, b), (d4 - d3v) / ((d4 - d3v) + (d5 - d6)));
  double denom = 1 / (va + vb + vc);
  double v = vb * denom, w = vc * denom;
  return {a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
}

class Grid {
 public:
  // `queries`: how many points will be measured against it. A grid as fine as the denser of the two
  // meshes keeps the candidates per query few when this mesh's triangles are much larger (an
  // adaptive dual contouring mesh against a dense reference: 17 s before, under 1 s after).
  Grid(const Mesh& m, size_t queries) : m_(m) {
    lo_ = {1e300, 1e300, 1e300};
    D3 hi = {-1e300, -1e300, -1e300};
    for (const auto& p : m.positions)
      for (int a = 0; a < 3; ++a) lo_[a] = std::min(lo_[a], double(p[a])), hi[a] = std::max(hi[a], double(p[a]));
    size_t n = std::max<size_t>({1, m.triangles.size(), queries / 2});
    double diag = std::sqrt(dot(sub(hi, lo_), sub(hi, lo_)));
    cell_ = std::max(diag / std::max(1.0, std::cbrt(double(n))), 1e-9);
    for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, int(std::ceil((hi[a] - lo_[a]) / cell_)) + 1);
    cells_.resize(size_t(dims_[0]) * dims_[1] * dims_[2]);
    for (uint32_t t = 0; t < m.triangles.size(); ++t) {
      int lo_c[3], hi_c[3];
      for (int a = 0; a < 3; ++a) {
        double mn = 1e300, mx = -1e300;
        for (uint32_t v : m.triangles[t])
          mn = std::min(mn, double(m.positions[v][a])), mx = std::max(mx, double(m.positions[v][a]));
        lo_c[a] = clampi(a, int((mn - lo_[a]) / cell_));
        hi_c[a] = clampi(a, int((mx - lo_[a]) / cell_));
      }
      for (int z = lo_c[2]; z <= hi_c[2]; ++z)
        for (int y = lo_c[1]; y <= hi_c[1]; ++y)
          for (int x = lo_c[0]; x <= hi_c[0]; ++x) cells_[index(x, y, z)].push_back(t);
    }
  }

  // Distance from p to the nearest triangle (or vertex, for a mesh without triangles).
  double distance(D3 p) const {
    if (m_.triangles.empty()) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& v : m_.positions) best = std::min(best, std::sqrt(dot(sub(p, d3(v)), sub(p, d3(v)))));
      return best;
    }
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = clampi(a, int((p[a] - lo_[a]) / cell_));
    double best = std::numeric_limits<double>::infinity();
    int max_r = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r <= max_r; ++r) {
      // Rings 0 .. r - 1 searched: nothing else is nearer than the boundary of the block they make.
      double margin = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3 && r > 0; ++a)
        margin = std::min({margin, p[a] - (lo_[a] + (c[a] - r + 1) * cell_), lo_[a] + (c[a] + r) * cell_ - p[a]});
      if (r > 0 && best <= margin) break;
      for (int z = c[2] - r; z <= c[2] + r; ++z)
        for (int y = c[1] - r; y <= c[1] + r; ++y)
          for (int x = c[0] - r; x <= c[0] + r; ++x) {
            if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;
            if (x < 0 || y < 0 || z < 0 || x >= dims_[0] || y >= dims_[1] || z >= dims_[2]) continue;
            for (uint32_t t : cells_[index(x, y, z)]) {
              const auto& tri = m_.triangles[t];
              D3 q =
                  closest_on_triangle(p, d3(m_.positions[tri[0]]), d3(m_.positions[tri[1]]), d3(m_.positions[tri[2]]));
              best = std::min(best, std::sqrt(dot(sub(p, q), sub(p, q))));
            }
          }
    }
    return best;
  }

 private:
  int clampi(int a, int v) const { return std::clamp(v, 0, dims_[a] - 1); }
  size_t index(int x, int y, int z) const { return (size_t(z) * dims_[1] + y) * dims_[0] + x; }

  const Mesh& m_;
  D3 lo_;
  double cell_;
  int dims_[3];
  std::vector<std::vector<uint32_t>> cells_;
};

// Samples of a mesh's surface: its vertices and its triangles' centroids.
std::vector<D3> samples(const Mesh& m) {
  std::vector<D3> s;
  for (const auto& p : m.positions) s.push_back(d3(p));
  for (const auto& t : m.triangles) {
    D3 c{0, 0, 0};
    for (uint32_t v : t)
      for (int a = 0; a < 3; ++a) c[a] += m.positions[v][a] / 3.0;
    s.push_back(c);
  }
  return s;
}

void directed(const Mesh& from, const Grid& to, double& max_d, double& mean_d) {
  auto pts = samples(from);
  max_d = 0;
  double sum = 0;
  for (const auto& p : pts) {
    double d = to.distance(p);
    max_d = std::max(max_d, d);
    sum += d;
  }
  mean_d = pts.empty() ? 0 : sum / pts.size();
}

}  // namespace

Distances mesh_distances(const Mesh& a, const Mesh& b) {
  Distances d;
  size_t na = a.positions.size() + a.triangles.size(), nb = b.positions.size() + b.triangles.size();
  Grid ga(a, nb), gb(b, na);
  directed(a, gb, d.max_ab, d.mean_ab);
  directed(b, ga, d.max_ba, d.mean_ba);
  d.hausdorff = std::max(d.max_ab, d.max_ba);
  d.chamfer = 0.5 * (d.mean_ab + d.mean_ba);
  return d;
}

double bbox_diagonal(const Mesh& m) {
  if (m.positions.empty()) return 0;
  D3 lo = d3(m.positions[0]), hi = lo;
  for (const auto& p : m.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double(p[a])), hi[a] = std::max(hi[a], double(p[a]));
  return std::sqrt(dot(sub(hi, lo), sub(hi, lo)));
}

}  // namespace fscript::mesh
