// The scene layer end to end: a .wrl text to the model to meshes (kinds, time, FTransform
// operations, 3D texture displacement, Transforms), checked by mesh invariants.
#include <catch2/catch.hpp>
#include <cmath>

#include "frontend/vrml/vrml_parser.h"
#include "engine/mesh/mesh.h"
#include "engine/scene/scene_model.h"
#include "engine/scene/shape_mesh.h"
#include "runtime/support/cancel.h"
#include "tests/unit/helpers.h"
#include "tests/unit/scene_helpers.h"

using namespace fscript;

namespace {
using Loaded = test::LoadedScene;

std::unique_ptr<Loaded> load(const std::string& body, scene::ModelOptions opts = {}) {
  return test::load_scene("s.wrl", "#VRML V2.0 utf8\n" + body, opts);
}

double mean_radius(const mesh::Mesh& m, double cx = 0) {
  double sum = 0;
  for (const auto& p : m.positions) sum += std::sqrt((p[0] - cx) * (p[0] - cx) + p[1] * p[1] + p[2] * p[2]);
  return sum / m.positions.size();
}
}  // namespace

TEST_CASE("scene: a hollow ball by subtraction, and a union of two balls") {
  auto l = load(R"W(FTransform { operation "subtraction" children [
      FShape { geometry FGeometry { definition "0.8^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } }
      FShape { geometry FGeometry { definition "0.4^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } } ] }
    FTransform { children [
      FShape { geometry FGeometry { definition "0.3^2-(x-0.5)^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } }
      FShape { geometry FGeometry { definition "0.3^2-(x+0.5)^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } } ] })W");
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  REQUIRE(l->model.groups.size() == 2);
  for (int g = 0; g < 2; ++g) {
    mesh::Mesh m;
    backends::RuntimeError err;
    REQUIRE(scene::mesh_group(l->model, g, m, err));
    auto topo = mesh::topology(m);
    CHECK(topo.watertight);
    CHECK(topo.oriented);
    CHECK(topo.euler == 4);  // two spheres each
  }
}

TEST_CASE("scene: an analytical operation morphs between its children with t") {
  auto at = [](double f) {
    scene::ModelOptions o;
    o.fraction = f;
    auto l = load(R"W(FTransform { type "analytical" operation "f*(1-t)+g*t" children [
        FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } }
        FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } } ] })W",
                  o);
    REQUIRE(l->ok);
    mesh::Mesh m;
    backends::RuntimeError err;
    REQUIRE(scene::mesh_group(l->model, 0, m, err));
    return mean_radius(m);
  };
  CHECK(at(0) == Approx(0.3).epsilon(0.01));
  CHECK(at(1) == Approx(0.7).epsilon(0.01));
}

TEST_CASE("scene: a displacement texture adds to the function; a Transform moves the mesh") {
  auto l = load(R"W(Transform { translation 2 0 0 children [ FShape {
      appearance FAppearance { texture3D FTexture3D { definition "0.2*t" type "displacement" timeSpan 0 1 } }
      geometry FGeometry { definition "0.5-sqrt(x*x+y*y+z*z)" bboxSize 2 2 2 resolution [32] } } ] })W",
                [] {
                  scene::ModelOptions o;
                  o.fraction = 1;
                  return o;
                }());
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], m, err));
  CHECK(mean_radius(m, 2.0) == Approx(0.7).epsilon(0.01));  // 0.5 + 0.2, centred at x = 2
}

TEST_CASE("scene: parametric kinds and domains from resolution and parameters") {
  auto l = load(R"W(FShape { geometry FGeometry { definition "x=u; y=u*u; z=0;" resolution [20] parameters [0 2] } }
    FShape { geometry FGeometry { definition "x=u; y=v; z=u*v;" resolution [8 8] parameters [0 1 0 1] } })W");
  REQUIRE(l->ok);
  CHECK(l->model.shapes[0].kind == scene::ShapeKind::Curve);
  CHECK(l->model.shapes[1].kind == scene::ShapeKind::Surface);
  mesh::Mesh curve, surface;
  backends::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], curve, err));
  REQUIRE(scene::mesh_shape(l->model.shapes[1], surface, err));
  CHECK(curve.polylines[0].size() == 21);
  CHECK(curve.positions.back()[1] == 4.0f);
  CHECK(surface.triangles.size() == 128);
}

namespace {
mesh::Mesh group_mesh(const std::string& body, double fraction = 0, mesh::Mesher mesher = mesh::MesherOptions{}.kind) {
  scene::ModelOptions o;
  o.fraction = fraction;
  auto l = load(body, o);
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  mesh::Mesh m;
  backends::RuntimeError err;
  INFO(err.message);
  mesh::MesherOptions how;
  how.kind = mesher;
  REQUIRE(scene::mesh_group(l->model, 0, m, err, true, 1, true, how));
  return m;
}

// The middle of the bounding box: a symmetric shape's centre whatever the mesher's vertex density
// (dual contouring's vertices crowd where cells did not merge).
std::array<double, 3> centroid(const mesh::Mesh& m) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const auto& p : m.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], double(p[a])), hi[a] = std::max(hi[a], double(p[a]));
  return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
}
}  // namespace

TEST_CASE("scene: an analytical operation over parametric children works on each coordinate") {
  // Two spheres of radius 0.3 and 0.7 on the same (u, v): the morph's points lie on a sphere of
  // radius 0.3 (1 - t) + 0.7 t.
  const char* body = R"W(FTransform { type "analytical" operation "f*(1-t)+g*t" parameters [0 1 0 1] children [
      FShape { geometry FGeometry { resolution [24 24]
        definition "x=0.3*cos(2*pi*u)*sin(pi*v); y=0.3*sin(2*pi*u)*sin(pi*v); z=0.3*cos(pi*v);" } }
      FShape { geometry FGeometry { resolution [24 24]
        definition "x=0.7*cos(2*pi*u)*sin(pi*v); y=0.7*sin(2*pi*u)*sin(pi*v); z=0.7*cos(pi*v);" } } ] })W";
  for (double f : {0.0, 0.25, 1.0}) {
    mesh::Mesh m = group_mesh(body, f);
    INFO("fraction " << f);
    double want = 0.3 * (1 - f) + 0.7 * f, worst = 0;
    for (const auto& p : m.positions)
      worst = std::max(worst, std::fabs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - want));
    CHECK(worst < 1e-5);
    auto topo = mesh::topology(m);
    CHECK(topo.watertight);  // seams and poles welded as for one shape
    CHECK(topo.euler == 2);
  }
}

TEST_CASE("scene: a union of parametric children is both surfaces; other set operations say why not") {
  mesh::Mesh m = group_mesh(R"W(FTransform { translation "0, 0, 1" children [
      FShape { geometry FGeometry { definition "x=u; y=v; z=0;" resolution [4 4] parameters [0 1 0 1] } }
      FShape { geometry FGeometry { definition "x=u; y=v; z=1;" resolution [4 4] parameters [0 1 0 1] } } ] })W");
  CHECK(m.triangles.size() == 64);
  CHECK(centroid(m)[2] == Approx(1.5));  // both squares moved up by the FTransform's translation
  auto l = load(R"W(FTransform { operation "intersection" children [
      FShape { geometry FGeometry { definition "x=u; y=v; z=0;" resolution [4 4] parameters [0 1 0 1] } }
      FShape { geometry FGeometry { definition "x=u; y=v; z=1;" resolution [4 4] parameters [0 1 0 1] } } ] }
    FTransform { children [
      FShape { geometry FGeometry { definition "x=u; y=v; z=0;" resolution [4 4] parameters [0 1 0 1] } }
      FShape { geometry FGeometry { definition "0.5-x*x-y*y-z*z" } } ] })W");
  REQUIRE(l->ok);
  mesh::Mesh bad;
  backends::RuntimeError err;
  CHECK(!scene::mesh_group(l->model, 0, bad, err));
  CHECK(err.message.find("'intersection' over parametric children") != std::string::npos);
  CHECK(!scene::mesh_group(l->model, 1, bad, err));
  CHECK(err.message.find("cannot mix implicit and parametric") != std::string::npos);
}

TEST_CASE("scene: an FTransform's affine fields move, turn and scale its result, and may follow t") {
  // A ball of radius 0.3 moved by translation "t, 0, 0": at fraction 1 its centre is x = 1 and the
  // box the polygonizer samples moved with it (the ball is whole).
  mesh::Mesh moved = group_mesh(R"W(FTransform { translation "t, 0, 0" children [
      FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 1 1 1 resolution [24] } } ] })W",
                                1.0);
  CHECK(centroid(moved)[0] == Approx(1.0).margin(1e-3));
  CHECK(mean_radius(moved, 1.0) == Approx(0.3).epsilon(0.01));
  CHECK(mesh::topology(moved).watertight);
  CHECK(mesh::topology(moved).euler == 2);
  // scale "2 1 1" makes an ellipsoid with semi-axes 0.6, 0.3, 0.3; numbers work as well as strings.
  // (Marching tetrahedra, whose vertices have normals.)
  mesh::Mesh scaled = group_mesh(R"W(FTransform { scale "2 1 1" children [
      FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 1 1 1 resolution [32] } } ] })W",
                                 0, mesh::Mesher::MarchingTetrahedra);
  REQUIRE(scaled.normals.size() == scaled.positions.size());
  double worst = 0;
  for (const auto& p : scaled.positions) {
    double e = std::sqrt((p[0] / 0.6) * (p[0] / 0.6) + (p[1] / 0.3) * (p[1] / 0.3) + (p[2] / 0.3) * (p[2] / 0.3));
    worst = std::max(worst, std::fabs(e - 1));
  }
  CHECK(worst < 0.01);
  // Normals of the stretched shape still point out of it.
  int outward = 0;
  for (size_t i = 0; i < scaled.positions.size(); ++i) {
    const auto &p = scaled.positions[i], &n = scaled.normals[i];
    outward += p[0] / 0.36 * n[0] + p[1] / 0.09 * n[1] + p[2] / 0.09 * n[2] > 0;
  }
  CHECK(outward == static_cast<int>(scaled.positions.size()));
  // A quarter turn about z carries a ball at x = 0.5 to y = 0.5.
  mesh::Mesh turned = group_mesh(R"W(FTransform { rotation "0 0 1 1.5707963" children [
      FShape { geometry FGeometry { definition "0.2^2-(x-0.5)^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } } ] })W");
  CHECK(centroid(turned)[0] == Approx(0.0).margin(1e-3));
  CHECK(centroid(turned)[1] == Approx(0.5).margin(1e-3));
  // A zero scale has no volume: a clear error.
  auto l = load(R"W(FTransform { scale "0 1 1" children [
      FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" } } ] })W");
  REQUIRE(l->ok);
  mesh::Mesh flat;
  backends::RuntimeError err;
  CHECK(!scene::mesh_group(l->model, 0, flat, err));
  CHECK(err.message.find("scale is zero") != std::string::npos);
}

TEST_CASE("scene: a displacement texture on a parametric surface moves points along the normal") {
  auto l = load(R"W(FShape {
      appearance FAppearance { texture3D FTexture3D { definition "0.1" type "displacement" } }
      geometry FGeometry { resolution [24 24] parameters [0 1 0 1]
        definition "x=0.5*cos(2*pi*u)*sin(pi*v); y=0.5*sin(2*pi*u)*sin(pi*v); z=0.5*cos(pi*v);" } })W");
  REQUIRE(l->ok);
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], m, err));
  // dP/du x dP/dv points inward on this map, so +0.1 along the normal shrinks the sphere.
  CHECK(mean_radius(m) == Approx(0.4).epsilon(0.01));
}

TEST_CASE("scene: FMaterial strings set the material; none leaves the viewer's default") {
  auto l = load(R"W(FShape { appearance FAppearance { material FMaterial {
        shininess "0.25+0.5*t" transparency "0.5" emissiveColor "r=1; g=0; b=0;" specularColor "0.3" } }
      geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 1 1 1 resolution [8] } }
    FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 1 1 1 resolution [8] } })W",
                [] {
                  scene::ModelOptions o;
                  o.fraction = 1;
                  return o;
                }());
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  mesh::Mesh a, b;
  backends::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], a, err));
  REQUIRE(scene::mesh_shape(l->model.shapes[1], b, err));
  REQUIRE(a.material);
  CHECK(a.material->shininess == Approx(0.75));
  CHECK(a.material->transparency == Approx(0.5));
  CHECK(a.material->emissive == mesh::Vec3{1, 0, 0});
  CHECK(a.material->specular == mesh::Vec3{0.3f, 0.3f, 0.3f});
  CHECK(a.material->diffuse == mesh::Vec3{0.8f, 0.8f, 0.8f});
  CHECK(!b.material);
}

#include "engine/scene/standard_geometry.h"

TEST_CASE("scene: standard VRML97 geometry becomes meshes for pictures, with materials and Transforms") {
  auto l = load(R"W(Background { skyColor 0 0 1 }
    Transform { translation 2 0 0 children Shape {
      appearance Appearance { material Material { diffuseColor 1 0 0 shininess 0.9 } }
      geometry Box { size 2 4 6 } } }
    Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }
      coordIndex [0 1 2 3 -1] color Color { color [1 0 0, 0 1 0] } colorPerVertex FALSE colorIndex [1] } }
    Shape { geometry IndexedLineSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0] } coordIndex [0 1 2] } }
    Switch { whichChoice 1 choice [ Shape { geometry Sphere { } } Shape { geometry Cone { } } ] }
    Shape { geometry Cylinder { radius 0.5 } }
    FShape { geometry FGeometry { definition "1-x*x-y*y-z*z" } })W");
  REQUIRE(l->ok);
  auto parts = scene::standard_meshes(l->scene);
  REQUIRE(parts.size() == 5);  // the FShape is not standard; the Switch draws its chosen child only
  const auto& box = parts[0];
  CHECK(box.triangles.size() == 12);
  mesh::Vec3 lo = box.positions[0], hi = lo;
  for (const auto& p : box.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  CHECK(lo == mesh::Vec3{1, -2, -3});
  CHECK(hi == mesh::Vec3{3, 2, 3});
  REQUIRE(box.material);
  CHECK(box.material->diffuse == mesh::Vec3{1, 0, 0});
  CHECK(box.positions.size() == 24);  // flat faces: four vertices of its own each
  CHECK(parts[1].triangles.size() == 2);
  REQUIRE(parts[1].colours.size() == 4);
  CHECK(parts[1].colours[0] == mesh::Vec3{0, 1, 0});  // colour 1 for the whole face
  CHECK(parts[2].polylines.size() == 1);
  CHECK(parts[2].polylines[0].size() == 3);
  double cone_top = -1e9;
  for (const auto& p : parts[3].positions) cone_top = std::max(cone_top, double(p[1]));
  CHECK(cone_top == Approx(1.0));  // the Cone, height 2 about the origin
  auto sky = scene::background_colour(l->scene);
  REQUIRE(sky);
  CHECK((*sky)[2] == 1.0f);
  // Merging keeps each part's colour: the red box and the grey default stay apart.
  mesh::Mesh all = parts[0];
  all.append(parts[4]);
  REQUIRE(all.colours.size() == all.positions.size());
  CHECK(all.colours.front() == mesh::Vec3{1, 0, 0});
  CHECK(all.colours.back() == mesh::Vec3{0.8f, 0.8f, 0.8f});
}

TEST_CASE("scene: a looping shape at several clock values follows its TimeSensor fields") {
  auto radius_at = [](double now) {
    scene::ModelOptions o;
    o.now = now;
    auto l = load(R"W(FShape { loop TRUE cycleInterval 2
      geometry FGeometry { definition "(0.3+0.4*t)^2-x*x-y*y-z*z" bboxSize 2 2 2 resolution [32] } })W",
                  o);
    REQUIRE(l->ok);
    mesh::Mesh m;
    backends::RuntimeError err;
    REQUIRE(scene::mesh_shape(l->model.shapes[0], m, err));
    return mean_radius(m);
  };
  CHECK(radius_at(0.5) == Approx(0.4).epsilon(0.01));   // fraction 0.25
  CHECK(radius_at(1.5) == Approx(0.6).epsilon(0.01));   // fraction 0.75
  CHECK(radius_at(2.5) == Approx(0.4).epsilon(0.01));   // the second cycle
}

TEST_CASE("scene: a field knows whether it reads t, through helper functions too") {
  auto l = load(R"(FShape { geometry FGeometry { definition "1 - x*x - y*y - z*z" } }
FShape { geometry FGeometry { definition "t - x*x - y*y - z*z" } }
FShape { geometry FGeometry { definition "
function grow(a) { return a * t; }
function FRep(x, y, z, t) { return grow(1) - x*x - y*y - z*z; }" } }
FShape { geometry FGeometry { definition "1 - x*x - y*y - z*z + 0 * t" }
         appearance FAppearance { material FMaterial { diffuseColor "x + t" } } })");
  REQUIRE(l->ok);
  REQUIRE(l->model.shapes.size() == 4);
  CHECK(!l->model.shapes[0].geometry.reads_t);
  CHECK(l->model.shapes[1].geometry.reads_t);
  CHECK(l->model.shapes[2].geometry.reads_t);
  REQUIRE(l->model.shapes[3].colour);
  CHECK(l->model.shapes[3].colour->reads_t);
}

// A cancelled run (fvrml-run --serve) stops within a batch in the per-vertex passes too: the
// colour and the displacement of each of the 66,049 vertices of a parametric sphere. The geometry
// is quick and the per-vertex script slow (seconds for all vertices, a fraction of a second per
// batch); the cancel comes after the geometry, so the shape fails with the cancel's message
// instead of finishing.
TEST_CASE("scene: a cancel stops per-vertex colours and displacements within a batch") {
  const std::string slow =
      "function FRep(x, y, z, t) { var s = 0; for (var i = 0; i < 10000; i++) s += sin(x * i); "
      "return 0.5 + 1e-9 * s; }";
  const std::string sphere =
      "geometry FGeometry { resolution [256 256] parameters [0 1 0 1] definition "
      "\"x=0.5*cos(2*pi*u)*sin(pi*v); y=0.5*sin(2*pi*u)*sin(pi*v); z=0.5*cos(pi*v);\" } }\n";
  auto l = load("FShape { appearance FAppearance { material FMaterial { diffuseColor \"" + slow + "\" } }\n" + sphere +
                "FShape { appearance FAppearance { texture3D FTexture3D { definition \"" + slow +
                "\" type \"displacement\" } }\n" + sphere);
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  REQUIRE(l->model.shapes.size() == 2);
  for (size_t which = 0; which < 2; ++which) {
    test::CancelAfter cancel(300);
    mesh::Mesh m;
    backends::RuntimeError err;
    bool ok = scene::mesh_shape(l->model.shapes[which], m, err);
    INFO("shape " << which);
    CHECK_FALSE(ok);
    CHECK(err.message == support::kCancelledMessage);
  }
}
