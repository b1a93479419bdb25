// Uniform dual contouring: closed, oriented, 2-manifold meshes with the right Euler characteristic;
// vertices on the surface; the sharp corners of a cube turned off the grid axes kept within a tenth
// of a cell (marching tetrahedra rounds them off); a solid cut by the box closed by the box faces.
#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "engine/mesh/dual_contour.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "tests/unit/field_helpers.h"

using namespace fscript;
using test::FnField;
using test::job;
using test::Turn;

namespace {

// Dual contouring of `f` over the job, which must succeed, and the mesh a closed, oriented,
// 2-manifold surface of genus 0.
mesh::Mesh closed_dc(const mesh::ImplicitJob& j, mesh::DualContourStats& st) {
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(mesh::dual_contour(j, m, st, err));
  auto t = mesh::topology(m);
  CHECK(t.watertight);
  CHECK(t.oriented);
  CHECK(t.manifold);
  CHECK(t.euler == 2);
  return m;
}

}  // namespace

TEST_CASE("dual contouring: a sphere is closed, oriented, of genus 0, its vertices on the surface") {
  FnField sphere([](double x, double y, double z) { return 0.7 - std::sqrt(x * x + y * y + z * z); });
  mesh::DualContourStats st;
  mesh::Mesh m = closed_dc(job(sphere, 32), st);
  double h = 2.0 / 32, worst = 0;
  for (const auto& p : m.positions)
    worst = std::max(worst, std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 0.7));
  CHECK(worst < 0.1 * h);
  // Faces leave the solid.
  size_t outward = 0;
  for (const auto& t : m.triangles) {
    const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    float n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                  (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                  (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    outward += n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) > 0;
  }
  CHECK(outward == m.triangles.size());
  // Each vertex's normal is the gradient's, within 1 degree of the true normal (radial), and the
  // smooth sphere needs no vertex split for it.
  REQUIRE(m.normals.size() == m.positions.size());
  CHECK(m.split_from.empty());
  double cos_worst = 1;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const auto &p = m.positions[v], &n = m.normals[v];
    double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    cos_worst = std::min(cos_worst, (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / len);
  }
  CHECK(cos_worst > std::cos(M_PI / 180));
  CHECK(st.cells == m.positions.size());
}

TEST_CASE("dual contouring: a cube turned off the axes keeps its corners sharp") {
  Turn turn;
  test::GradField cube(
      [&](double x, double y, double z) {
        double p[3] = {x, y, z}, q[3];
        turn.apply(p, q, true);
        return 0.5 - std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2])});
      },
      [&](double x, double y, double z, double g[3]) {  // minus the outward normal of the face max picks
        double p[3] = {x, y, z}, q[3], d[3] = {0, 0, 0};
        turn.apply(p, q, true);
        int k = 0;
        for (int a = 1; a < 3; ++a)
          if (std::abs(q[a]) > std::abs(q[k])) k = a;
        d[k] = q[k] > 0 ? -1 : 1;
        turn.apply(d, g, false);
      });
  // The farthest of the cube's eight corners from its nearest vertex of `m`.
  auto worst_corner = [&](const mesh::Mesh& m) {
    double worst = 0;
    for (int c = 0; c < 8; ++c) {
      double corner[3] = {c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5}, w[3], best = 1e9;
      turn.apply(corner, w, false);
      for (const auto& p : m.positions) best = std::min(best, std::hypot(p[0] - w[0], p[1] - w[1], p[2] - w[2]));
      worst = std::max(worst, best);
    }
    return worst;
  };
  for (int cells : {24, 40}) {
    mesh::DualContourStats st;
    mesh::Mesh m = closed_dc(job(cube, cells), st);
    double h = 2.0 / cells, worst = worst_corner(m);
    INFO(cells << " cells: worst corner " << worst / h << " of a cell");
    CHECK(worst < 0.1 * h);
    // Marching tetrahedra on the same grid rounds the corners off by far more.
    mesh::Mesh mt;
    backends::RuntimeError err;
    REQUIRE(mesh::polygonize_implicit(job(cube, cells), mt, err));
    CHECK(worst_corner(mt) > 2 * worst);
    CHECK(m.triangles.size() < mt.triangles.size());
    // Its faces stay flat: every triangle lying in a face of the cube has that face's normal at
    // all three corners, the vertices on edges and corners split into one per face they join.
    REQUIRE(m.normals.size() == m.positions.size());
    double cos_worst = 1;
    size_t flat = 0;
    for (const auto& t : m.triangles) {
      const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
      double n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                     (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                     (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])},
             q[3];
      double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(len > 0)) continue;
      for (double& x : n) x /= len;
      turn.apply(n, q, true);  // in the cube's own axes
      int axis = 0;
      for (int k = 1; k < 3; ++k)
        if (std::abs(q[k]) > std::abs(q[axis])) axis = k;
      if (std::abs(q[axis]) < std::cos(M_PI / 180)) continue;  // not in a face: a chamfer across an edge
      double face[3] = {0, 0, 0}, w[3];
      face[axis] = q[axis] > 0 ? 1 : -1;
      turn.apply(face, w, false);
      ++flat;
      for (uint32_t v : t)
        cos_worst = std::min(cos_worst, w[0] * m.normals[v][0] + w[1] * m.normals[v][1] + w[2] * m.normals[v][2]);
    }
    INFO(flat << " triangles in the faces; worst corner normal " << std::acos(std::min(1.0, cos_worst)) * 180 / M_PI
              << " degrees off its face");
    CHECK(flat > m.triangles.size() / 2);
    CHECK(cos_worst > std::cos(M_PI / 180));
    CHECK(m.positions.size() > st.cells);  // split at the edges
  }
}

TEST_CASE("dual contouring: a solid cut by the box is closed by the box faces") {
  FnField ball([](double x, double y, double z) { return 1.2 - std::sqrt(x * x + y * y + z * z); });
  mesh::DualContourStats st;
  mesh::Mesh m = closed_dc(job(ball, 20), st);
  size_t on_faces = 0;
  for (const auto& p : m.positions) {
    for (float c : p) CHECK(std::abs(c) <= 1.0f + 1e-6f);
    on_faces += std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) > 1.0f - 1e-6f;
  }
  CHECK(on_faces > 100);  // the caps lie on the faces, their edges on the box's edges
}

TEST_CASE("dual contouring: a gyroid too fine for the grid still gives a closed 2-manifold mesh") {
  // Where the grid cannot resolve the surface, cells hold several sheets, and thin tubes cross
  // ambiguous faces: one vertex per cell would pinch them, one per sheet would double an edge.
  for (double periods : {2.0, 4.0, 6.0, 7.5})
    for (int cells : {10, 13, 16, 19, 22, 31}) {
      double k = 3.14159265358979 * periods;
      FnField gyroid([k](double x, double y, double z) {
        return std::sin(k * x) * std::cos(k * y) + std::sin(k * y) * std::cos(k * z) +
            std::sin(k * z) * std::cos(k * x);
      });
      mesh::Mesh m;
      mesh::DualContourStats st;
      backends::RuntimeError err;
      REQUIRE(mesh::dual_contour(job(gyroid, cells), m, st, err));
      auto t = mesh::topology(m);
      INFO(periods << " periods, " << cells << " cells");
      CHECK(t.watertight);
      CHECK(t.oriented);
      CHECK(t.manifold);
      CHECK(t.degenerate_triangles == 0);
    }
}

TEST_CASE("dual contouring: merged cells never pinch two sheets into one vertex") {
  // A cell of one sheet may have an ambiguous face; a node merged over it then met its boundary in
  // two loops and gave their polygons one vertex: two fans at one vertex (the gyroid ∩ sphere).
  const double k = 4 * 3.14159265358979;
  FnField shape([k](double x, double y, double z) {
    double g =
        std::sin(k * x) * std::cos(k * y) + std::sin(k * y) * std::cos(k * z) + std::sin(k * z) * std::cos(k * x);
    return std::min(g, 0.81 - x * x - y * y - z * z);
  });
  size_t pinched = 0;
  for (int cells : {48, 64, 96})
    for (double tolerance : {0.05, 0.1, 0.2, 0.4}) {
      mesh::ImplicitJob j = job(shape, cells);
      j.mesher.tolerance = tolerance;
      mesh::Mesh m;
      mesh::DualContourStats st;
      backends::RuntimeError err;
      REQUIRE(mesh::dual_contour(j, m, st, err));
      auto t = mesh::topology(m);
      INFO(cells << " cells, tolerance " << tolerance);
      CHECK(t.watertight);
      CHECK(t.oriented);
      pinched += !t.manifold;
      CHECK(t.manifold);
    }
  CHECK(pinched == 0);
}

TEST_CASE("dual contouring: a function undefined outside its solid still gives the solid") {
  // sqrt of a negative number is NaN outside the ball of radius 0.8: outside, as for every mesher;
  // crossings toward those samples bisect, and their normals use the side that is defined.
  const double r = std::sqrt(0.63);
  FnField ball([](double x, double y, double z) { return std::sqrt(0.64 - x * x - y * y - z * z) - 0.1; });
  for (double tolerance : {0.0, mesh::MesherOptions::kDefaultTolerance}) {
    mesh::ImplicitJob j = job(ball, 32);
    j.mesher.tolerance = tolerance;
    mesh::DualContourStats st;
    mesh::Mesh m = closed_dc(j, st);
    double h = 2.0 / 32, worst = 0;
    for (const auto& p : m.positions) worst = std::max(worst, std::abs(std::hypot(p[0], p[1], p[2]) - r));
    INFO("tolerance " << tolerance << ": " << m.triangles.size() << " triangles, worst " << worst / h << " of a cell");
    CHECK(worst < 0.1 * h);
    CHECK(m.triangles.size() > 1000);
  }
}

TEST_CASE("dual contouring: blocks of every size and shape, on any number of threads, make one closed mesh") {
  // Lattices whose cells (n + 1 per axis, with the padding) end a 16-cell block exactly, just
  // after, just before, and differently per axis; a sphere with a slab cut through the blocks.
  FnField shape([](double x, double y, double z) {
    return std::min(0.8 - std::sqrt(x * x + y * y + z * z), 0.3 - std::abs(0.6 * x + 0.8 * z - 0.1 * y));
  });
  const std::array<int, 3> sizes[] = {{15, 15, 15}, {16, 16, 16}, {31, 32, 33}, {5, 17, 33}, {33, 5, 17}, {47, 9, 30}};
  for (const auto& n : sizes) {
    mesh::ImplicitJob j = job(shape, 1);
    j.cells = n;
    mesh::DualContourStats st;
    mesh::Mesh one = closed_dc(j, st);
    for (int threads : {2, 5}) {
      j.threads = threads;
      mesh::Mesh many = closed_dc(j, st);
      INFO(n[0] << "x" << n[1] << "x" << n[2] << " cells on " << threads << " threads");
      CHECK(many.positions == one.positions);
      CHECK(many.triangles == one.triangles);
    }
  }
}

TEST_CASE("dual contouring: every vertex on the surface of tilted cylinders cut by planes") {
  // Issue 49: where a cut cylinder's rim meets its side at a grazing angle, the QEF's vertex left
  // the surface by up to 0.37 of a cell (the mean stayed near 0.01); a Newton step along the
  // gradient (dc_normals.h) puts each vertex farther than a tenth of a cell back on it.
  const int cells = 64;
  const double h = 2.0 / cells;
  double worst_all = 0;
  for (double angle : {0.2, 0.35, 0.5, 0.7, 0.9, 1.1})
    for (double off : {0.0, 0.013, 0.031}) {
      double ax[3] = {std::sin(angle) * std::cos(0.4), std::sin(angle) * std::sin(0.4), std::cos(angle)};
      auto local = [&](double x, double y, double z, double& t, double& r) {
        double p[3] = {x - off, y - off * 0.5, z + off * 0.7};
        t = p[0] * ax[0] + p[1] * ax[1] + p[2] * ax[2];
        r = std::sqrt(std::max(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - t * t, 0.0));
      };
      FnField cylinder([&](double x, double y, double z) {
        double t, r;
        local(x, y, z, t, r);
        return std::min(0.45 - r, 0.6 - std::abs(t));
      });
      mesh::DualContourStats st;
      mesh::Mesh m = closed_dc(job(cylinder, cells), st);
      double worst = 0;
      for (const auto& q : m.positions) {  // the distance to the capped cylinder's surface
        double t, r;
        local(q[0], q[1], q[2], t, r);
        double dr = r - 0.45, dt = std::abs(t) - 0.6;
        double d = std::hypot(std::max(dr, 0.0), std::max(dt, 0.0)) + std::min(std::max(dr, dt), 0.0);
        worst = std::max(worst, std::abs(d));
      }
      INFO("axis " << angle << " rad off z, offset " << off << ": worst vertex " << worst / h << " of a cell");
      CHECK(worst < 0.1 * h);
      worst_all = std::max(worst_all, worst);
    }
  CHECK(worst_all > 0.02 * h);  // vertices do land off the surface: the bound is not empty
}

namespace {

// The distance from (px, py) to the segment from a to b.
double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  double dx = bx - ax, dy = by - ay, t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

}  // namespace

TEST_CASE("dual contouring: every vertex on the surface of tilted cones cut by a plane") {
  // Where the cap meets the side, the vertex between the two planes sat half a cell inside the
  // rim, on both planes' bisector. With the function's own gradient (as a scene's kernels have it),
  // the Newton step takes it onto the surface the gradient names.
  const int cells = 64;
  const double h = 2.0 / cells, height = 0.7, slope = 0.55, norm = std::sqrt(1 + slope * slope);
  for (double angle : {0.2, 0.5, 0.9, 1.2})
    for (double off : {0.0, 0.013, 0.031}) {
      double ax[3] = {std::sin(angle) * std::cos(0.7), std::sin(angle) * std::sin(0.7), std::cos(angle)};
      auto local = [&](double x, double y, double z, double p[3], double& t, double& r) {
        p[0] = x - off, p[1] = y + off * 0.3, p[2] = z + off * 0.6 + 0.35;
        t = p[0] * ax[0] + p[1] * ax[1] + p[2] * ax[2];
        r = std::sqrt(std::max(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - t * t, 0.0));
      };
      test::GradField cone(
          [&](double x, double y, double z) {
            double p[3], t, r;
            local(x, y, z, p, t, r);
            return std::min((t * slope - r) / norm, height - t);
          },
          [&](double x, double y, double z, double g[3]) {
            double p[3], t, r;
            local(x, y, z, p, t, r);
            bool side = (t * slope - r) / norm < height - t;
            for (int a = 0; a < 3; ++a)
              g[a] = side ? (slope * ax[a] - (r > 0 ? (p[a] - t * ax[a]) / r : 0)) / norm : -ax[a];
          });
      mesh::DualContourStats st;
      mesh::Mesh m;
      backends::RuntimeError err;
      REQUIRE(mesh::dual_contour(job(cone, cells), m, st, err));
      auto t = mesh::topology(m);  // closed; the tip, thinner than a cell, may part from the rest
      CHECK(t.watertight);
      CHECK(t.oriented);
      CHECK(t.manifold);
      double worst = 0;
      for (const auto& q : m.positions) {  // in the plane of the axis: the side and the cap as segments
        double p[3], t, r;
        local(q[0], q[1], q[2], p, t, r);
        worst = std::max(worst,
                         std::min(segment_distance(t, r, 0, 0, height, height * slope),
                                  segment_distance(t, r, height, 0, height, height * slope)));
      }
      INFO("axis " << angle << " rad off z, offset " << off << ": worst vertex " << worst / h << " of a cell");
      CHECK(worst < 0.1 * h);
    }
}

TEST_CASE("dual contouring: every vertex on the surface of turned boxes with a cylinder bored through") {
  // Issue 49's third family of tilted CSG shapes: a box minus a cylinder along one of its axes,
  // turned off the grid and moved by fractions of a cell, measured against the exact boundary
  // (the box's faces, the bore's disc taken out of two of them, and the bore's wall).
  const int cells = 64;
  const double h = 2.0 / cells, rho = 0.22;
  for (double angle : {0.3, 0.6, 1.0})
    for (double off : {0.0, 0.017, 0.029}) {
      double k[3] = {std::sin(angle) * std::cos(1.1), std::sin(angle) * std::sin(1.1), std::cos(angle)};
      double c = std::cos(angle * 0.7), s = std::sin(angle * 0.7), m3[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m3[i][j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
      m3[0][1] -= s * k[2], m3[0][2] += s * k[1], m3[1][0] += s * k[2], m3[1][2] -= s * k[0], m3[2][0] -= s * k[1],
          m3[2][1] += s * k[0];
      auto local = [&](double x, double y, double z, double q[3]) {
        double p[3] = {x - off, y + off * 0.4, z - off * 0.8};
        for (int i = 0; i < 3; ++i) q[i] = m3[0][i] * p[0] + m3[1][i] * p[1] + m3[2][i] * p[2];
      };
      test::GradField shape(
          [&](double x, double y, double z) {
            double q[3];
            local(x, y, z, q);
            return std::min(0.5 - std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2])}),
                            std::hypot(q[0], q[1]) - rho);
          },
          [&](double x, double y, double z, double g[3]) {  // the gradient of the side min takes
            double q[3], d[3] = {0, 0, 0};
            local(x, y, z, q);
            double box = 0.5 - std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2])}), r = std::hypot(q[0], q[1]);
            if (box < r - rho) {
              int a = 0;
              for (int i = 1; i < 3; ++i)
                if (std::abs(q[i]) > std::abs(q[a])) a = i;
              d[a] = q[a] > 0 ? -1 : 1;
            } else if (r > 0) {
              d[0] = q[0] / r, d[1] = q[1] / r;
            }
            for (int i = 0; i < 3; ++i) g[i] = m3[i][0] * d[0] + m3[i][1] * d[1] + m3[i][2] * d[2];
          });
      mesh::DualContourStats st;
      mesh::Mesh m;
      backends::RuntimeError err;
      REQUIRE(mesh::dual_contour(job(shape, cells), m, st, err));
      auto t = mesh::topology(m);
      CHECK(t.watertight);
      CHECK(t.manifold);
      CHECK(t.euler == 0);  // a box with a hole through it
      double worst = 0;
      for (const auto& v : m.positions) {
        double q[3];
        local(v[0], v[1], v[2], q);
        double d = std::hypot(std::hypot(q[0], q[1]) - rho, std::max(std::abs(q[2]) - 0.5, 0.0));  // the bore's wall
        for (int a = 0; a < 3; ++a)
          for (int sign = -1; sign <= 1; sign += 2) {  // the box's faces; the bore's discs out of the z faces
            int u = (a + 1) % 3, w = (a + 2) % 3;
            double pu = std::clamp(q[u], -0.5, 0.5), pw = std::clamp(q[w], -0.5, 0.5),
                   in_plane = std::hypot(q[u] - pu, q[w] - pw);
            if (a == 2 && std::hypot(pu, pw) < rho) in_plane += rho - std::hypot(pu, pw);
            d = std::min(d, std::hypot(q[a] - sign * 0.5, in_plane));
          }
        worst = std::max(worst, d);
      }
      INFO("axis " << angle << " rad off z, offset " << off << ": worst vertex " << worst / h << " of a cell");
      CHECK(worst < 0.1 * h);
    }
}
