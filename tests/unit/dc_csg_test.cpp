// Dual contouring of CSG shapes turned off the grid axes, at 64^3 with the default tolerance: the
// mesh closed, 2-manifold, of the right genus; every vertex within a tenth of a cell of the true
// surface (measured by the nearest sign change of the exact function around it); every point of the
// true sharp edges within a tenth of a cell of the mesh (sampled edges to the nearest triangle);
// at most a quarter of marching tetrahedra's triangles. Smooth shapes: Hausdorff distance to a dense
// reference no worse than marching tetrahedra's at the same resolution.
#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "engine/mesh/distance.h"
#include "engine/mesh/dual_contour.h"
#include "tests/unit/field_helpers.h"

using namespace fscript;
using test::FnField;
using test::Turn;

namespace {

using P3 = std::array<double, 3>;
using Fn = std::function<double(const P3&)>;

double box_sdf(const P3& p, const P3& half) {  // exact, inside positive
  double out = 0, in = -1e300;
  for (int a = 0; a < 3; ++a) {
    double d = std::abs(p[a]) - half[a];
    out += std::max(d, 0.0) * std::max(d, 0.0);
    in = std::max(in, d);
  }
  return out > 0 ? -std::sqrt(out) : -in;
}

P3 rotate_z(const P3& p, double angle) {
  double c = std::cos(angle), s = std::sin(angle);
  return {c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]};
}

// The points t in [0, 1] of a segment, `step` apart.
void segment(const P3& a, const P3& b, double step, std::vector<P3>& out) {
  double len = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
  int n = std::max(1, static_cast<int>(len / step));
  for (int i = 0; i <= n; ++i) {
    double t = double(i) / n;
    out.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])});
  }
}

// The twelve edges of the box [-half, half], keeping the points `keep` accepts.
void box_edges(const P3& half, double step, const std::function<bool(const P3&)>& keep, std::vector<P3>& out) {
  std::vector<P3> all;
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 4; ++c) {
      P3 a, b;
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      a[axis] = -half[axis], b[axis] = half[axis];
      a[u] = b[u] = (c & 1 ? 1 : -1) * half[u];
      a[v] = b[v] = (c & 2 ? 1 : -1) * half[v];
      segment(a, b, step, all);
    }
  for (const P3& p : all)
    if (keep(p)) out.push_back(p);
}

struct CsgShape {
  std::string name;
  Fn f;                  // in the shape's own frame
  std::vector<P3> edges;  // sampled sharp edges, in the shape's own frame
  long euler;
  // The bound on vertex and edge distances, in cells: a tenth, except where one cell holds more
  // features than one vertex per sheet can place (docs/scenes.md, "Known limits").
  double vertex_bound = 0.1, edge_bound = 0.1;
  double edge_gain = 2;  // how many times closer to the edges than marching tetrahedra, at least
};

constexpr int kCells = 64;
constexpr double kH = 2.0 / kCells;
constexpr double kStep = 0.05 * kH;

CsgShape six_half_spaces() {
  CsgShape s{"a cube as six half-spaces",
             [](const P3& p) {
               double f = 1e300;
               for (int a = 0; a < 3; ++a) f = std::min({f, 0.5 - p[a], 0.5 + p[a]});
               return f;
             },
             {},
             2};
  box_edges({0.5, 0.5, 0.5}, kStep, [](const P3&) { return true; }, s.edges);
  return s;
}

CsgShape cube_minus_sphere() {  // a ball of radius 0.6 bitten out of a corner
  const P3 c{0.5, 0.5, 0.5};
  auto ball = [c](const P3& p) { return 0.6 - std::hypot(p[0] - c[0], p[1] - c[1], p[2] - c[2]); };
  CsgShape s{
      "a cube minus a sphere", [ball](const P3& p) { return std::min(box_sdf(p, {0.5, 0.5, 0.5}), -ball(p)); }, {}, 2};
  box_edges({0.5, 0.5, 0.5}, kStep, [ball](const P3& p) { return ball(p) < 0; }, s.edges);
  for (int axis = 0; axis < 3; ++axis)  // a quarter circle on each face through the corner
    for (double t = 0; t <= M_PI / 2; t += kStep / 0.6) {
      P3 p = c;
      p[(axis + 1) % 3] -= 0.6 * std::cos(t), p[(axis + 2) % 3] -= 0.6 * std::sin(t);
      s.edges.push_back(p);
    }
  return s;
}

CsgShape boxes_at_an_angle() {  // the union of two boxes, one turned 35 degrees about z: concave edges too
  const P3 ha{0.5, 0.3, 0.3}, hb{0.3, 0.55, 0.25};
  const double turn = 35 * M_PI / 180;
  auto a = [ha](const P3& p) { return box_sdf(p, ha); };
  auto b = [hb, turn](const P3& p) { return box_sdf(rotate_z(p, -turn), hb); };
  // Where an edge of one box pierces a face of the other, a cell holds a convex edge, a concave edge
  // and their corner: its one vertex misses them by up to 0.2 of a cell, the edges by 0.45.
  CsgShape s{"two boxes at an angle", [a, b](const P3& p) { return std::max(a(p), b(p)); }, {}, 2, 0.2, 0.5, 1.5};
  box_edges(ha, kStep, [b](const P3& p) { return b(p) < 0; }, s.edges);
  std::vector<P3> eb;
  box_edges(hb, kStep, [](const P3&) { return true; }, eb);
  for (const P3& p : eb)
    if (a(rotate_z(p, turn)) < 0) s.edges.push_back(rotate_z(p, turn));
  // Where the faces meet: along each line where a face of one box crosses a face of the other.
  for (double x = -0.8; x <= 0.8; x += kStep)
    for (double y = -0.8; y <= 0.8; y += kStep)
      for (double z : {-0.3, 0.3, -0.25, 0.25}) {  // the top and bottom faces meet the other box's sides
        P3 p{x, y, z};
        if (std::abs(a(p)) < 1e-12 && std::abs(b(p)) < 0.5 * kStep) s.edges.push_back(p);
        if (std::abs(b(p)) < 1e-12 && std::abs(a(p)) < 0.5 * kStep) s.edges.push_back(p);
      }
  return s;
}

CsgShape cut_cylinder() {  // radius 0.4 about z, cut by z = 0.5 and by a plane tilted 20 degrees
  const double tilt = std::tan(20 * M_PI / 180);
  CsgShape s{
      "a cylinder cut by planes",
      [tilt](const P3& p) { return std::min({0.4 - std::hypot(p[0], p[1]), 0.5 - p[2], p[2] - (-0.5 + tilt * p[0])}); },
      {},
      2};
  for (double t = 0; t < 2 * M_PI; t += kStep / 0.4) {
    double x = 0.4 * std::cos(t), y = 0.4 * std::sin(t);
    s.edges.push_back({x, y, 0.5});
    s.edges.push_back({x, y, -0.5 + tilt * x});
  }
  return s;
}

// The field of a shape turned off the axes.
Fn turned(const Fn& f, const Turn& turn) {
  return [f, &turn](const P3& p) {
    P3 q;
    turn.apply(p.data(), q.data(), true);
    return f(q);
  };
}

// The distance from p to the nearest sign change of f, up to `most` (then `most`): the smallest
// sphere around p on which some direction sees the other sign, by bisection on the radius.
double distance_to_surface(const Fn& f, const P3& p, double most) {
  static const std::vector<P3> dirs = [] {
    std::vector<P3> d;
    const int n = 1500;
    for (int i = 0; i < n; ++i) {  // a Fibonacci sphere
      double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = i * M_PI * (3 - std::sqrt(5.0));
      d.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return d;
  }();
  double here = f(p);
  if (here == 0) return 0;
  auto other_sign_within = [&](double r) {
    for (const P3& d : dirs)
      if ((f({p[0] + r * d[0], p[1] + r * d[1], p[2] + r * d[2]}) > 0) != (here > 0)) return true;
    return false;
  };
  if (!other_sign_within(most)) return most;
  double lo = 0, hi = most;
  for (int i = 0; i < 10; ++i) (other_sign_within((lo + hi) / 2) ? hi : lo) = (lo + hi) / 2;
  return hi;
}

mesh::Mesh run(const mesh::Field& field, mesh::Mesher kind, int cells = kCells,
               double tolerance = mesh::MesherOptions::kDefaultTolerance) {
  return test::meshed(test::job(field, cells), kind, tolerance);
}

}  // namespace

TEST_CASE("dual contouring keeps the sharp edges of CSG shapes turned off the grid") {
  Turn turn;
  for (const CsgShape& s : {six_half_spaces(), cube_minus_sphere(), boxes_at_an_angle(), cut_cylinder()}) {
    Fn f = turned(s.f, turn);
    FnField field([&](double x, double y, double z) { return f({x, y, z}); });
    mesh::Mesh dc = run(field, mesh::Mesher::DualContouring), mt = run(field, mesh::Mesher::MarchingTetrahedra);
    auto t = mesh::topology(dc);
    double worst_vertex = 0;
    for (const auto& v : dc.positions)
      worst_vertex = std::max(worst_vertex, distance_to_surface(f, {v[0], v[1], v[2]}, kH));
    mesh::Mesh edge_points, mt_points;
    for (const P3& e : s.edges) {
      P3 w;
      turn.apply(e.data(), w.data(), false);
      edge_points.positions.push_back({float(w[0]), float(w[1]), float(w[2])});
    }
    double worst_edge = mesh::mesh_distances(edge_points, dc).max_ab,
           mt_edge = mesh::mesh_distances(edge_points, mt).max_ab;
    INFO(s.name << ": " << dc.triangles.size() << " triangles (marching tetrahedra " << mt.triangles.size()
                << "), vertices within " << worst_vertex / kH << " of a cell, " << s.edges.size()
                << " edge points within " << worst_edge / kH << " (marching tetrahedra " << mt_edge / kH << ")");
    CHECK(t.watertight);
    CHECK(t.oriented);
    CHECK(t.manifold);
    CHECK(t.euler == s.euler);
    CHECK(worst_vertex < s.vertex_bound * kH);
    CHECK(worst_edge < s.edge_bound * kH);
    CHECK(mt_edge > s.edge_gain * worst_edge);
    CHECK(4 * dc.triangles.size() <= mt.triangles.size());
  }
}

TEST_CASE("dual contouring of smooth shapes: no farther from a dense reference than marching tetrahedra") {
  FnField sphere([](double x, double y, double z) { return 0.7 - std::sqrt(x * x + y * y + z * z); });
  FnField torus([](double x, double y, double z) { return 0.2 - std::hypot(std::hypot(x, y) - 0.55, z); });
  FnField gyroid_ball([](double x, double y, double z) {
    double k = 2 * M_PI * 1.5;
    double g =
        std::sin(k * x) * std::cos(k * y) + std::sin(k * y) * std::cos(k * z) + std::sin(k * z) * std::cos(k * x);
    return std::min(g, 0.75 - std::sqrt(x * x + y * y + z * z));
  });
  struct Case {
    const char* name;
    const FnField* f;
  };
  // The reference: dual contouring without merging at four times the resolution (its sharp edges,
  // where the ball cuts the gyroid, are where marching tetrahedra would be the looser reference).
  for (const Case& c : {Case{"sphere", &sphere}, Case{"torus", &torus}, Case{"gyroid in a ball", &gyroid_ball}})
    for (int cells : {32, 40}) {
      if (cells != 32 && c.f != &gyroid_ball)
        continue;  // one resolution is enough where nothing is thinner than a cell
      double h = 2.0 / cells;
      mesh::Mesh reference = run(*c.f, mesh::Mesher::DualContouring, 4 * cells, 0);
      mesh::Mesh uniform = run(*c.f, mesh::Mesher::DualContouring, cells, 0),
                 dc = run(*c.f, mesh::Mesher::DualContouring, cells);
      mesh::Mesh mt = run(*c.f, mesh::Mesher::MarchingTetrahedra, cells);
      auto d_uniform = mesh::mesh_distances(uniform, reference), d_dc = mesh::mesh_distances(dc, reference);
      auto d_mt = mesh::mesh_distances(mt, reference);
      auto t_dc = mesh::topology(dc), t_mt = mesh::topology(mt);
      INFO(c.name << " at " << cells << " cells: Hausdorff " << d_dc.hausdorff / h << " cells (without merging "
                  << d_uniform.hausdorff / h << ", marching tetrahedra " << d_mt.hausdorff / h
                  << "); from the mesh to the "
                  << "reference " << d_dc.max_ab / h << " (" << d_mt.max_ab / h << "); " << dc.triangles.size()
                  << " triangles (" << uniform.triangles.size() << ", " << mt.triangles.size() << ")");
      CHECK(t_dc.watertight);
      CHECK(t_dc.manifold);
      if (c.f != &gyroid_ball) {
        CHECK(t_dc.euler == t_mt.euler);
        CHECK(d_uniform.hausdorff <= d_mt.hausdorff);
        // Merged cells trade a hundredth of a cell for their fewer triangles (docs/scenes.md).
        CHECK(d_dc.hausdorff <= d_mt.hausdorff + 0.01 * h);
      } else {
        // Where the ball cuts the gyroid at a grazing angle it leaves wedges thinner than a cell, which
        // neither mesher sees (about a cell of Hausdorff distance, both ways): the mesh's own points
        // are what must be no farther from the surface.
        CHECK(d_dc.max_ab <= d_mt.max_ab);
        // The same slivers change the Euler characteristic from one resolution to the next (-36 at
        // 32 cells, -48 at 40): dual contouring's is marching tetrahedra's on the same samples, its
        // bridges and tunnels decided alike (dc_cells.h), with the same components.
        INFO("Euler characteristic " << t_dc.euler << ", marching tetrahedra " << t_mt.euler);
        CHECK(t_dc.euler == t_mt.euler);
        CHECK(t_dc.components == t_mt.components);
        CHECK(t_dc.inverted_components == 0);
      }
    }
}
