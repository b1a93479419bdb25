// The implicit polygonizer by its invariants: watertight, consistently oriented outward, 2-manifold,
// Euler characteristic, vertices on the true surface, caps on the box faces.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "engine/mesh/marching_tetrahedra.h"
#include "engine/mesh/parametric.h"
#include "runtime/support/cancel.h"
#include "tests/unit/helpers.h"

using namespace fscript;

static mesh::Mesh polygonize(const std::string& src, std::array<double, 6> box, int n, float t = 0,
                             mesh::Mesher kind = mesh::Mesher::MarchingTetrahedra) {
  auto b = test::build(src);
  REQUIRE(b->ok);
  mesh::KernelField field(*b->kernel, t);
  mesh::ImplicitJob job;
  job.field = &field;
  job.box = box;
  job.cells = {n, n, n};
  job.mesher.kind = kind;
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(mesh::polygonize(job, m, err));
  return m;
}

TEST_CASE("mesh: a sphere is a watertight oriented 2-manifold with Euler characteristic 2, on the surface") {
  auto m = polygonize("function FRep(x,y,z,t){ return 0.7*0.7 - x*x - y*y - z*z; }", {-1, 1, -1, 1, -1, 1}, 40);
  auto topo = mesh::topology(m);
  CHECK(topo.watertight);
  CHECK(topo.oriented);
  CHECK(topo.manifold);
  CHECK(topo.euler == 2);
  double cell = 2.0 / 40, worst = 0;
  int inward = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const auto& p = m.positions[v];
    double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    worst = std::max(worst, std::fabs(r - 0.7));
    inward += (p[0] * m.normals[v][0] + p[1] * m.normals[v][1] + p[2] * m.normals[v][2]) < 0;
  }
  CHECK(worst < 0.01 * cell);
  CHECK(inward == 0);
  // Outward orientation: the signed volume of the triangles is positive and near 4/3 pi r^3.
  double vol = 0;
  for (const auto& t : m.triangles) {
    const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    vol +=
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6;
  }
  CHECK(vol == Approx(4.0 / 3 * M_PI * 0.343).epsilon(0.02));
}

TEST_CASE("mesh: a torus has Euler characteristic 0") {
  auto m = polygonize("function FRep(x,y,z,t){ var q = sqrt(x*x+y*y) - 0.6; return 0.25*0.25 - q*q - z*z; }",
                      {-1, 1, -1, 1, -0.5, 0.5}, 48);
  auto topo = mesh::topology(m);
  CHECK(topo.watertight);
  CHECK(topo.oriented);
  CHECK(topo.euler == 0);
}

TEST_CASE("mesh: a solid cut by the box is closed by caps on the box faces") {
  auto m = polygonize("function FRep(x,y,z,t){ return 1 - x*x - y*y; }", {-0.5, 0.5, -0.5, 0.5, -0.5, 0.5}, 16);
  auto topo = mesh::topology(m);
  CHECK(topo.watertight);
  CHECK(topo.oriented);
  CHECK(topo.euler == 2);
  int off_box = 0;
  for (const auto& p : m.positions) {
    double d = std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
    off_box += std::fabs(d - 0.5) > 1e-6;
  }
  CHECK(off_box == 0);  // the whole surface is the box
}

TEST_CASE("mesh: two separate spheres, a thin plate, and time") {
  auto two = polygonize("function FRep(x,y,z,t){ return max(0.09-(x-0.5)^2-y*y-z*z, 0.09-(x+0.5)^2-y*y-z*z); }",
                        {-1, 1, -1, 1, -1, 1}, 40);
  CHECK(mesh::topology(two).euler == 4);
  auto thin = polygonize("function FRep(x,y,z,t){ return min(0.03 - abs(z), 0.5 - max(abs(x), abs(y))); }",
                         {-1, 1, -1, 1, -1, 1}, 64);
  CHECK(mesh::topology(thin).watertight);
  auto grow = polygonize("function FRep(x,y,z,t){ return t*t - x*x - y*y - z*z; }", {-1, 1, -1, 1, -1, 1}, 20, 0.5f);
  double r = std::sqrt(grow.positions[0][0] * grow.positions[0][0] + grow.positions[0][1] * grow.positions[0][1] +
                       grow.positions[0][2] * grow.positions[0][2]);
  CHECK(r == Approx(0.5).epsilon(0.001));
}

#include "engine/mesh/parametric.h"

static mesh::Mesh sample(const std::string& src, mesh::ParametricKind kind, std::array<double, 6> dom, int n) {
  auto b = test::build(src);
  REQUIRE(b->ok);
  mesh::KernelParametric map(*b->kernel, 0);
  mesh::ParametricJob job;
  job.field = &map;
  job.kind = kind;
  job.domain = dom;
  job.intervals = {n, n, n};
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(mesh::polygonize_parametric(job, m, err));
  return m;
}

TEST_CASE("mesh: a parametric sphere welds its seam and poles into a closed surface on the formula") {
  auto m = sample("x=0.5*cos(2*pi*u)*sin(pi*v); y=0.5*sin(2*pi*u)*sin(pi*v); z=0.5*cos(pi*v);",
                  mesh::ParametricKind::Surface, {0, 1, 0, 1, 0, 0}, 32);
  auto topo = mesh::topology(m);
  CHECK(topo.watertight);
  CHECK(topo.euler == 2);
  double worst = 0;
  for (const auto& p : m.positions)
    worst = std::max(worst, std::fabs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 0.5));
  CHECK(worst < 1e-5);
  // Normals from the derivatives: dP/du x dP/dv points inward for this map; exact away from the
  // poles, the face average at them.
  double worst_side = 1, worst_exact = 1;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const auto &p = m.positions[i], &n = m.normals[i];
    double d = -(p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / 0.5;
    worst_side = std::min(worst_side, d);
    if (std::fabs(p[2]) < 0.49) worst_exact = std::min(worst_exact, d);
  }
  CHECK(worst_side > 0.99);
  CHECK(worst_exact > 0.99999);
}

TEST_CASE("mesh: a parametric curve is a polyline of N+1 samples; a solid is its six faces") {
  auto c = sample("x=u; y=u*u; z=0;", mesh::ParametricKind::Curve, {0, 1, 0, 0, 0, 0}, 10);
  REQUIRE(c.polylines.size() == 1);
  CHECK(c.polylines[0].size() == 11);
  CHECK(c.positions[10][1] == 1.0f);
  auto s = sample("x=u; y=v; z=w;", mesh::ParametricKind::Solid, {0, 1, 0, 2, 0, 3}, 4);
  auto topo = mesh::topology(s);
  CHECK(topo.watertight);
  CHECK(topo.oriented);
  CHECK(topo.euler == 2);
  double vol = 0;  // outward faces give the positive volume 1 * 2 * 3
  for (const auto& t : s.triangles) {
    const auto &a = s.positions[t[0]], &b = s.positions[t[1]], &c = s.positions[t[2]];
    vol +=
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6;
  }
  CHECK(vol == Approx(6.0));
}

#include "engine/mesh/distance.h"
#include "engine/mesh/mesh_io.h"
#include "engine/mesh/mesh_read.h"
#include "runtime/support/files.h"

TEST_CASE("mesh: distances with known answers, and every writer read back") {
  auto small =
      polygonize("function FRep(x,y,z,t){ return 1 - x*x - y*y - z*z; }", {-1.5, 1.5, -1.5, 1.5, -1.5, 1.5}, 40);
  auto big =
      polygonize("function FRep(x,y,z,t){ return 1.21 - x*x - y*y - z*z; }", {-1.5, 1.5, -1.5, 1.5, -1.5, 1.5}, 40);
  auto d = mesh::mesh_distances(small, big);
  CHECK(d.hausdorff == Approx(0.1).epsilon(0.05));
  CHECK(d.chamfer == Approx(0.1).epsilon(0.02));
  auto self = mesh::mesh_distances(small, small);
  CHECK(self.hausdorff < 1e-4);
  mesh::Mesh shifted = small;
  for (auto& p : shifted.positions) p[0] += 0.25f;
  CHECK(mesh::mesh_distances(small, shifted).hausdorff == Approx(0.25).epsilon(0.05));
  for (auto [fmt, name] : {std::pair{mesh::MeshFormat::Ply, "a.ply"},
                           {mesh::MeshFormat::Obj, "a.obj"},
                           {mesh::MeshFormat::Stl, "a.stl"}}) {
    mesh::Mesh back;
    std::string err;
    INFO(name << ": " << err);
    REQUIRE(mesh::parse_mesh(mesh::encode_mesh(small, fmt), name, back, err));
    CHECK(back.triangles.size() == small.triangles.size());
    CHECK(mesh::topology(back).watertight);
    CHECK(mesh::mesh_distances(small, back).hausdorff < 1e-5);
  }
  mesh::Mesh bad;
  std::string err;
  CHECK(!mesh::parse_mesh("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\n", "x.ply", bad,
                          err));
  CHECK(!mesh::parse_mesh("v 0 0 0\nf 1 2 3\n", "x.obj", bad, err));
  CHECK(err.find("refers to vertex") != std::string::npos);
  CHECK(!mesh::parse_mesh("garbage", "x.stl", bad, err));
}

// The file write_mesh makes at path, read back.
std::string written(const mesh::Mesh& m, mesh::MeshFormat fmt, const std::string& path) {
  std::string err, bytes;
  REQUIRE(mesh::write_mesh(m, fmt, path, err));
  REQUIRE(support::read_file(path, bytes, err));
  return bytes;
}

TEST_CASE("mesh: files are streamed in chunks with the same bytes as encode_mesh; a failed write leaves nothing") {
  // 160^3 cells: about 300,000 triangles, several of the writer's 256 KiB chunks in every format.
  auto m = polygonize("function FRep(x,y,z,t){ return 1 - x*x - y*y - z*z; }", {-1.5, 1.5, -1.5, 1.5, -1.5, 1.5}, 160);
  REQUIRE(m.triangles.size() > 100000);
  m.colours.assign(m.positions.size(), {0.25f, 0.5f, 2.0f});  // PLY's colour bytes, one clamped
  std::string dir = (std::filesystem::temp_directory_path() / ("mesh-stream-" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(dir);
  for (auto [fmt, name] : {std::pair{mesh::MeshFormat::Ply, "a.ply"},
                           {mesh::MeshFormat::Obj, "a.obj"},
                           {mesh::MeshFormat::Stl, "a.stl"},
                           {mesh::MeshFormat::Glb, "a.glb"}}) {
    INFO(name);
    std::string bytes = written(m, fmt, dir + "/" + name), want = mesh::encode_mesh(m, fmt);
    CHECK(want.size() > (size_t{1} << 19));
    CHECK(bytes == want);
  }
  std::string err;
  CHECK(!mesh::write_mesh(m, mesh::MeshFormat::Ply, dir + "/no/such/dir/a.ply", err));
  CHECK(err.find("cannot write") != std::string::npos);
  std::string left;
  CHECK(!support::read_file(dir + "/no/such/dir/a.ply.tmp", left, err));
  std::filesystem::remove_all(dir);
}

// Corpus scenes without a polygonized shape (Cube.wrl, FVRML.wrl in the cli test) write an empty
// mesh: its arrays have no data, and the writers once copied zero bytes from a null pointer
// (UBSan in the SANITIZE=1 suite).
TEST_CASE("mesh: an empty mesh is a valid file in every format") {
  mesh::Mesh empty;
  std::string dir = (std::filesystem::temp_directory_path() / ("mesh-empty-" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(dir);
  for (auto [fmt, name] : {std::pair{mesh::MeshFormat::Ply, "a.ply"},
                           {mesh::MeshFormat::Obj, "a.obj"},
                           {mesh::MeshFormat::Stl, "a.stl"},
                           {mesh::MeshFormat::Glb, "a.glb"}}) {
    INFO(name);
    std::string bytes = written(empty, fmt, dir + "/" + name), err;
    CHECK(bytes == mesh::encode_mesh(empty, fmt));
    if (fmt == mesh::MeshFormat::Glb) continue;  // (no glTF reader here; the CLI tests validate glTF)
    mesh::Mesh back;
    REQUIRE(mesh::parse_mesh(bytes, name, back, err));
    CHECK(back.triangles.empty());
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("mesh: the same mesh, vertex for vertex, for 1, 2 and 5 threads") {
  auto b = test::build(
      "function FRep(x,y,z,t){ var k = 6.283185307179586*2.0; "
      "return min(sin(x*k)*cos(y*k)+sin(y*k)*cos(z*k)+sin(z*k)*cos(x*k), 0.9^2-x*x-y*y-z*z); }");
  REQUIRE(b->ok);
  mesh::KernelField field(*b->kernel, 0);
  mesh::Mesh ref;
  for (int threads : {1, 2, 5}) {
    mesh::ImplicitJob job;
    job.field = &field;
    job.box = {-1, 1, -1, 1, -1, 1};
    job.cells = {48, 48, 48};
    job.threads = threads;
    mesh::Mesh m;
    backends::RuntimeError err;
    REQUIRE(mesh::polygonize_implicit(job, m, err));
    auto topo = mesh::topology(m);
    CHECK(topo.watertight);
    CHECK(topo.oriented);
    if (threads == 1) {
      ref = m;
      continue;
    }
    INFO(threads << " threads");
    CHECK(m.positions == ref.positions);
    CHECK(m.triangles == ref.triangles);
    CHECK(m.normals == ref.normals);
  }
}

// ---- The topology checks themselves, on meshes made by hand ----
namespace {
mesh::Mesh tetrahedron(float dx = 0) {
  mesh::Mesh m;
  m.positions = {{dx, 0, 0}, {dx + 1, 0, 0}, {dx, 1, 0}, {dx, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};  // outward
  return m;
}
}  // namespace

TEST_CASE("topology: a closed tetrahedron, and what breaks each property") {
  auto t = mesh::topology(tetrahedron());
  CHECK(t.watertight);
  CHECK(t.oriented);
  CHECK(t.manifold);
  CHECK(t.euler == 2);
  CHECK(t.boundary_edges == 0);

  auto flipped = tetrahedron();  // one face turned over: closed, not oriented
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  auto f = mesh::topology(flipped);
  CHECK(f.watertight);
  CHECK_FALSE(f.oriented);

  auto open = tetrahedron();  // a face missing: three boundary edges, Euler characteristic 1
  open.triangles.pop_back();
  auto o = mesh::topology(open);
  CHECK_FALSE(o.watertight);
  CHECK_FALSE(o.oriented);  // a boundary edge is used in one direction only
  CHECK(o.boundary_edges == 3);
  CHECK(o.euler == 1);

  auto fin = tetrahedron();  // a third triangle on an edge
  fin.positions.push_back({0.5f, -1, 0});
  fin.triangles.push_back({0, 1, 4});
  CHECK_FALSE(mesh::topology(fin).watertight);

  auto degenerate = tetrahedron();
  degenerate.triangles.push_back({1, 1, 2});
  CHECK(mesh::topology(degenerate).degenerate_triangles == 1);
  CHECK(mesh::topology(degenerate).euler == 2);
}

TEST_CASE("topology: two closed bodies touching at one vertex are not a 2-manifold") {
  mesh::Mesh a = tetrahedron(), b;
  // The second body shares vertex 0: mirrored through it, so the two meet only there.
  b.positions = {{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  b.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  auto apart = a;
  apart.append(b);  // two separate bodies: still manifold, Euler characteristic 4
  auto s = mesh::topology(apart);
  CHECK(s.watertight);
  CHECK(s.oriented);
  CHECK(s.manifold);
  CHECK(s.euler == 4);
  CHECK(apart.triangles.size() == 8);
  CHECK(apart.triangles[4][0] == 4);  // the second body's indices moved past the first's vertices
  auto bowtie = apart;  // now make them share vertex 0 (drop b's copy of it)
  for (auto& tri : bowtie.triangles)
    for (auto& v : tri)
      if (v == 4) v = 0;
  auto w = mesh::topology(bowtie);
  CHECK(w.watertight);
  CHECK_FALSE(w.manifold);
  CHECK(w.euler == 3);  // 7 used vertices - 12 edges + 8 faces
}

TEST_CASE("mesh: a crossing starts at the linear estimate along its edge, exact for a plane") {
  // With no refinement step the vertices of f = 0.3 - x lie on the plane x = 0.3 exactly where
  // the linear estimate puts them; the others close the box on its faces.
  auto b = test::build("0.3 - x");
  REQUIRE(b->ok);
  mesh::KernelField field(*b->kernel, 0);
  mesh::ImplicitJob job;
  job.field = &field;
  job.box = {-1, 1, -1, 1, -1, 1};
  job.cells = {10, 10, 10};
  job.refine_steps = 0;
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(mesh::polygonize_implicit(job, m, err));
  size_t on_plane = 0;
  for (const auto& p : m.positions) {
    bool plane = std::fabs(p[0] - 0.3f) < 1e-5f;
    bool face = std::fabs(std::fabs(p[0]) - 1) < 1e-5f || std::fabs(std::fabs(p[1]) - 1) < 1e-5f ||
        std::fabs(std::fabs(p[2]) - 1) < 1e-5f;
    INFO(p[0] << " " << p[1] << " " << p[2]);
    REQUIRE((plane || face));
    on_plane += plane;
  }
  CHECK(on_plane > 100);
  CHECK(mesh::topology(m).watertight);
}

TEST_CASE("crease normals: a cube's corners keep their faces' normals; a sphere's are radial") {
  mesh::Mesh cube;
  for (int c = 0; c < 8; ++c) cube.positions.push_back({float(c & 1), float(c >> 1 & 1), float(c >> 2 & 1)});
  // Two outward triangles per face.
  cube.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  REQUIRE(mesh::topology(cube).watertight);
  auto n = mesh::crease_normals(cube, mesh::kCreaseAngle);
  REQUIRE(n.size() == 36);
  for (size_t t = 0; t < 12; ++t) {
    const auto &a = cube.positions[cube.triangles[t][0]], &b = cube.positions[cube.triangles[t][1]],
               &c = cube.positions[cube.triangles[t][2]];
    float f[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                  (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                  (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    for (int k = 0; k < 3; ++k)
      for (int a2 = 0; a2 < 3; ++a2) CHECK(n[3 * t + k][a2] == Approx(f[a2]).margin(1e-6));  // unit already
  }
  // Past the crease angle every corner is smooth: a right angle counts as smooth at 100 degrees.
  auto soft = mesh::crease_normals(cube, 100 * 3.14159265 / 180);
  CHECK(std::fabs(soft[0][0]) > 0.1);
  CHECK(std::fabs(soft[0][1]) > 0.1);
  // A sphere meshed by dual contouring: every corner's normal within a few degrees of radial.
  mesh::Mesh ball = polygonize("function FRep(x,y,z,t){ return 0.7*0.7 - x*x - y*y - z*z; }", {-1, 1, -1, 1, -1, 1}, 32,
                               0, mesh::Mesher::DualContouring);
  REQUIRE(ball.normals.size() == ball.positions.size());  // its own, from the gradient (dc_normals.h)
  ball.normals.clear();
  auto r = mesh::crease_normals(ball, mesh::kCreaseAngle);
  double worst = 1;
  for (size_t t = 0; t < ball.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& p = ball.positions[ball.triangles[t][static_cast<size_t>(k)]];
      double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      const auto& q = r[3 * t + static_cast<size_t>(k)];
      worst = std::min(worst, (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / len);
    }
  CHECK(worst > std::cos(10 * 3.14159265 / 180));
}

// A cancelled run (fvrml-run --serve after a save, --max-seconds, Ctrl-C) stops a frame within a
// batch: each mesher gives up with the cancel's message instead of finishing the shape. The flag is
// set from another thread after a few batches; each mesh would take a minute or more otherwise.
TEST_CASE("mesh: a cancel from another thread stops every mesher within a batch") {
  auto b = test::build(
      "function FRep(x,y,z,t){ var s = 0; for (var i = 0; i < 20000; i++) s += sin(x * i); "
      "return 0.5 - x*x - y*y - z*z + 1e-9 * s; }");
  auto p = test::build(
      "function FRep(u,v,w,t){ var s = 0; for (var i = 0; i < 20000; i++) s += sin(u * i); "
      "x = u; y = v; z = 1e-9 * s; }");
  REQUIRE(b->ok);
  REQUIRE(p->ok);
  mesh::KernelField field(*b->kernel, 0);
  mesh::KernelParametric map(*p->kernel, 0);
  for (int which = 0; which < 3; ++which) {
    test::CancelAfter cancel(200);
    mesh::Mesh m;
    backends::RuntimeError err;
    bool ok;
    if (which < 2) {
      mesh::ImplicitJob job;
      job.field = &field;
      job.box = {-1, 1, -1, 1, -1, 1};
      job.cells = {64, 64, 64};
      job.threads = 2;
      job.mesher.kind = which == 0 ? mesh::Mesher::MarchingTetrahedra : mesh::Mesher::DualContouring;
      ok = mesh::polygonize(job, m, err);
    } else {
      mesh::ParametricJob job;
      job.field = &map;
      job.kind = mesh::ParametricKind::Surface;
      job.domain = {0, 1, 0, 1, 0, 0};
      job.intervals = {512, 512, 1};
      ok = mesh::polygonize_parametric(job, m, err);
    }
    INFO("mesher " << which);
    CHECK_FALSE(ok);
    CHECK(err.message == support::kCancelledMessage);
  }
  CHECK_FALSE(support::run_cancelled());  // outside every scope
}

TEST_CASE("topology: components, inside-out ones, and vertices split for their normals") {
  mesh::Mesh a = tetrahedron(), b = tetrahedron();
  for (auto& p : b.positions) p[0] += 5;  // a second body beside the first
  auto two = a;
  two.append(b);
  auto t = mesh::topology(two);
  CHECK(t.components == 2);
  CHECK(t.inverted_components == 0);
  // Turn the second body inside out: still closed and consistently oriented, but a negative volume.
  for (size_t i = 4; i < two.triangles.size(); ++i) std::swap(two.triangles[i][1], two.triangles[i][2]);
  t = mesh::topology(two);
  CHECK(t.watertight);
  CHECK(t.oriented);
  CHECK(t.components == 2);
  CHECK(t.inverted_components == 1);
  // Each triangle of a tetrahedron with vertices of its own, each with the face's normal (as a
  // writer splits a sharp vertex): the same closed surface once the split vertices are welded.
  mesh::Mesh split;
  auto tet = tetrahedron();
  std::vector<int32_t> first(tet.positions.size(), -1);
  for (const auto& tri : tet.triangles) {
    std::array<uint32_t, 3> out;
    for (int k = 0; k < 3; ++k) {
      out[k] = static_cast<uint32_t>(split.positions.size());
      if (first[tri[k]] < 0) first[tri[k]] = static_cast<int32_t>(out[k]);
      split.split_from.push_back(static_cast<uint32_t>(first[tri[k]]));
      split.positions.push_back(tet.positions[tri[k]]);
      split.normals.push_back({float(split.triangles.size()), 0, 1});  // a different normal per face
    }
    split.triangles.push_back(out);
  }
  auto s = mesh::topology(split);
  CHECK(s.watertight);
  CHECK(s.oriented);
  CHECK(s.manifold);
  CHECK(s.euler == 2);
  CHECK(s.components == 1);
  // Without saying where they were split from, the same vertices are twelve separate points: an
  // open soup of four triangles.
  split.split_from.clear();
  auto soup = mesh::topology(split);
  CHECK_FALSE(soup.watertight);
  CHECK(soup.components == 4);
}
