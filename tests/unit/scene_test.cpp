// The scene layer end to end: a .wrl text to the model to meshes (kinds, time, FTransform
// operations, 3D texture displacement, Transforms), checked by mesh invariants.
#include <catch2/catch.hpp>
#include <cmath>

#include "frontend/vrml/vrml_parser.h"
#include "runtime/mesh/mesh.h"
#include "runtime/scene/scene_model.h"
#include "runtime/scene/shape_mesh.h"

using namespace fscript;

namespace {
struct Loaded {
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  scene::SceneModel model;
  bool ok = false;
};

std::unique_ptr<Loaded> load(const std::string& body, scene::ModelOptions opts = {}) {
  auto l = std::make_unique<Loaded>();
  std::string text = "#VRML V2.0 utf8\n" + body;
  l->ok = vrml::parse_scene(std::make_unique<frontend::SourceFile>("s.wrl", text), l->diag, l->scene) &&
          scene::build_scene_model(l->scene, opts, l->diag, l->model);
  return l;
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
    backend::RuntimeError err;
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
        FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [32] } } ] })W", o);
    REQUIRE(l->ok);
    mesh::Mesh m;
    backend::RuntimeError err;
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
  backend::RuntimeError err;
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
  backend::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], curve, err));
  REQUIRE(scene::mesh_shape(l->model.shapes[1], surface, err));
  CHECK(curve.polylines[0].size() == 21);
  CHECK(curve.positions.back()[1] == 4.0f);
  CHECK(surface.triangles.size() == 128);
}
