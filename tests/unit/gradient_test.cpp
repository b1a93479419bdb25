// Forward-mode gradients (ir/passes/gradient.h): against derivatives worked out by hand, against
// central differences for every op with a rule, equal on every backend, and refused where no rule is.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>

#include "backends/backend.h"
#include "ir/passes/gradient.h"
#include "ir/verifier.h"
#include "engine/scene/shape_field.h"
#include "engine/scene/shape_mesh.h"
#include "tests/unit/helpers.h"
#include "tests/unit/scene_helpers.h"

using namespace fscript;

namespace {

struct Grad {
  float f, g[3];
};

std::unique_ptr<backends::Kernel> gradient_kernel(const std::string& src, const std::string& be = "vm") {
  auto b = test::build(src);
  INFO(src << "\n" << test::messages(b->diag));
  REQUIRE(b->ok);
  auto m = ir::gradient_module(*b->module);
  REQUIRE(m);
  CHECK(ir::verify(*m).empty());
  std::unique_ptr<backends::Kernel> k;
  REQUIRE(driver::compile_kernel(*m, be, {}, k).ok());
  return k;
}

Grad at(const backends::Kernel& k, float x, float y, float z, float t = 0) {
  std::vector<float> in = {x, y, z, t};
  in.resize(k.num_inputs(), 0.0f);
  float out[4];
  backends::RuntimeError err;
  REQUIRE(k.num_outputs() == 4);
  REQUIRE(k.eval(in.data(), out, err));
  return {out[0], {out[1], out[2], out[3]}};
}

bool close(double a, double b, double tol) { return std::fabs(a - b) <= tol * (1 + std::fabs(b)); }

}  // namespace

TEST_CASE("gradient: the gyroid and the sphere against their derivatives by hand") {
  const double k = 4 * M_PI;
  auto gyroid = gradient_kernel(
      "function FRep(x,y,z,t){ var k = 6.283185307179586 * 2.0; var X = x*k + t, Y = y*k, Z = z*k;"
      " return sin(X)*cos(Y) + sin(Y)*cos(Z) + sin(Z)*cos(X); }");
  auto sphere = gradient_kernel("function FRep(x,y,z,t){ return 0.81 - x*x - y*y - z*z; }");
  auto ball = gradient_kernel("function FRep(x,y,z,t){ return 1 - sqrt(x*x + y*y + z*z); }");
  const float pts[][3] = {{0.1f, 0.2f, 0.3f}, {-0.7f, 0.05f, 0.4f}, {0.33f, -0.9f, -0.12f}, {1.5f, 2.5f, -3.25f}};
  for (const auto& p : pts) {
    double X = p[0] * k, Y = p[1] * k, Z = p[2] * k, r = std::sqrt(double(p[0]) * p[0] + p[1] * p[1] + p[2] * p[2]);
    double want[3] = {k * (std::cos(X) * std::cos(Y) - std::sin(Z) * std::sin(X)),
                      k * (-std::sin(X) * std::sin(Y) + std::cos(Y) * std::cos(Z)),
                      k * (-std::sin(Y) * std::sin(Z) + std::cos(Z) * std::cos(X))};
    Grad g = at(*gyroid, p[0], p[1], p[2]), s = at(*sphere, p[0], p[1], p[2]), b = at(*ball, p[0], p[1], p[2]);
    INFO(p[0] << "," << p[1] << "," << p[2]);
    for (int a = 0; a < 3; ++a) {
      CHECK(close(g.g[a], want[a], 1e-4));
      CHECK(close(s.g[a], -2.0 * p[a], 1e-6));
      CHECK(close(b.g[a], -p[a] / r, 1e-5));
    }
  }
}

TEST_CASE("gradient: every op with a rule against central differences") {
  // Each body is smooth near the test points; h is large enough for float's rounding.
  const char* bodies[] = {"x*y - z/(y+3) + 2",
                          "(x % 0.7) * y",
                          "-x + abs(y - 0.05) * z",
                          "min(x, y) + max(y*z, x)",
                          "sqrt(x*x + 2) * exp(y)",
                          "pow(x + 2, 1.5) + pow(2, y) + pow(y + 3, z)",
                          "log(x + 3) + log10(y + 4) * z",
                          "sin(x) * cos(y) + tan(z)",
                          "asin(x * 0.5) + acos(y * 0.5) + atan(z)",
                          "atan2(y + 0.1, x + 2) + hypot(x, z + 1)",
                          "sinh(x) + cosh(y) * tanh(z)",
                          "clamp(x * 3, -0.5, 0.5) + clamp(y, z - 9, z + 9)",
                          "(x > y ? x * z : y * y) + floor(z) + round(x) + sign(y) + ceil(y)",
                          "x < 0.5 && y > -1 ? exp(z) : 0",
                          "Math.pow(x + 2, y) * t",
                          "noise(1, 2, 3) * x",
                          "fabs(x) * mod(y + 2, 0.7)"};
  // Every built-in of the language's table is in some body (a new one cannot be left out).
  for (const char* name : {
#define FS_BUILTIN(N, A, OP, SIG, DOC) N,
#include "frontend/fscript/builtins.def"
       }) {
    bool used = false;
    for (const char* body : bodies) used |= std::string(body).find(std::string(name) + "(") != std::string::npos;
    INFO("no body of this test calls " << name);
    CHECK(used);
  }
  const float pts[][3] = {{0.13f, 0.27f, 0.31f}, {-0.41f, 0.12f, -0.23f}, {0.37f, -0.29f, 0.44f}};
  const double h = 1e-3;
  for (const char* body : bodies) {
    std::string src = std::string("function FRep(x,y,z,t){ return ") + body + "; }";
    auto gk = gradient_kernel(src);
    auto fk = test::build(src);
    REQUIRE(fk->ok);
    for (const auto& p : pts) {
      Grad g = at(*gk, p[0], p[1], p[2], 1.5f);
      CHECK(g.f == test::eval1(*fk, {p[0], p[1], p[2], 1.5f}));
      for (int a = 0; a < 3; ++a) {
        float q[3] = {p[0], p[1], p[2]}, r[3] = {p[0], p[1], p[2]};
        q[a] = static_cast<float>(p[a] + h), r[a] = static_cast<float>(p[a] - h);
        double fd = (double(test::eval1(*fk, {q[0], q[1], q[2], 1.5f})) - test::eval1(*fk, {r[0], r[1], r[2], 1.5f})) /
            (double(q[a]) - r[a]);
        INFO(body << " at " << p[0] << "," << p[1] << "," << p[2] << " d/d" << "xyz"[a] << " " << g.g[a] << " vs "
                  << fd);
        CHECK(close(g.g[a], fd, 2e-3));
      }
    }
  }
}

TEST_CASE("gradient: min, max and select take the side they return") {
  auto k = gradient_kernel("function FRep(x,y,z,t){ return max(min(x, 2*y), -z); }");
  Grad a = at(*k, 0.5f, 1, 3), b = at(*k, 0.5f, 0.1f, 3), c = at(*k, 0.5f, 1, -3);
  CHECK((a.g[0] == 1 && a.g[1] == 0 && a.g[2] == 0));
  CHECK((b.g[0] == 0 && b.g[1] == 2 && b.g[2] == 0));
  CHECK((c.g[0] == 0 && c.g[1] == 0 && c.g[2] == -1));
}

TEST_CASE("gradient: what depends only on t costs no instruction, and noise in x has no rule") {
  auto b = test::build("function FRep(x,y,z,t){ return sin(t) * cos(t * 3) + x; }");
  REQUIRE(b->ok);
  auto m = ir::gradient_module(*b->module);
  REQUIRE(m);
  auto k = gradient_kernel("function FRep(x,y,z,t){ return sin(t) * cos(t * 3) + x; }");
  Grad g = at(*k, 0.2f, 0.3f, 0.4f, 0.7f);
  CHECK((g.g[0] == 1 && g.g[1] == 0 && g.g[2] == 0));
  // The copy of f plus one constant for d/dx: nothing is multiplied by a zero derivative.
  CHECK(m->instruction_count() <= b->module->instruction_count() + 2);
  auto n = test::build("function FRep(x,y,z,t){ return noise(x, y, z); }");
  REQUIRE(n->ok);
  CHECK(!ir::gradient_module(*n->module));
  auto loop = test::build("function FRep(x,y,z,t){ var s = 0; for (var i = 0; i < x; i++) s += y; return s; }");
  REQUIRE(loop->ok);
  CHECK(!ir::gradient_module(*loop->module));
}

TEST_CASE("gradient: every backend computes the same bits") {
  const char* src =
      "function FRep(x,y,z,t){ var k = 12.566; return min(sin(x*k)*cos(y*k) + sin(y*k)*cos(z*k) + sin(z*k)*cos(x*k),"
      " 0.81 - x*x - y*y - z*z) + atan2(y, x) * 0.01 + pow(abs(z) + 1, 1.5) * 0.01; }";
  auto vm = gradient_kernel(src, "vm");
  for (const std::string& be : backends::available_backends()) {
    if (be == "vm") continue;
    auto k = gradient_kernel(src, be);
    for (float x = -0.9f; x < 0.9f; x += 0.173f)
      for (float y = -0.9f; y < 0.9f; y += 0.211f) {
        Grad a = at(*vm, x, y, 0.3f), b = at(*k, x, y, 0.3f);
        INFO(be << " at " << x << "," << y);
        CHECK(a.f == b.f);
        for (int c = 0; c < 3; ++c) CHECK(a.g[c] == b.g[c]);
      }
  }
}

TEST_CASE("gradient: scene fields by the chain rule through set operations, blends and the FTransform's matrix") {
  auto l = test::load_scene("s.wrl", R"W(#VRML V2.0 utf8
    FTransform { translation "0.3, -0.1, 0.05" rotation "0.3, 0.5, 0.8, 0.7" scale "1.3, 0.7, 1.1" operation "blend_union" parameters [0.1 0.3 0.7] children [
      FShape { geometry FGeometry { definition "0.3^2-(x-0.35)^2-y^2-z^2" bboxSize 2 2 2 } }
      FTransform { operation "subtraction" children [
        FShape { geometry FGeometry { definition "0.6-abs(x)-abs(y)-abs(z)" bboxSize 2 2 2 } }
        FShape { geometry FGeometry { definition "0.2^2-x^2-y^2-z^2" bboxSize 2 2 2 } } ] } ] }
    FTransform { operation "intersection" children [
      FShape { geometry FGeometry { definition "sin(6*x)*cos(6*y)+sin(6*y)*cos(6*z)+sin(6*z)*cos(6*x)" bboxSize 2 2 2 } }
      FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" bboxSize 2 2 2 } } ] }
    FShape { appearance FAppearance { texture3D FTexture3D { definition "0.05*sin(20*u)" type "displacement" } }
      geometry FGeometry { definition "0.5-x*x-y*y-z*z" bboxSize 2 2 2 } })W");
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> pos(-0.9f, 0.9f);
  const double h = 1e-3;
  size_t checked = 0;
  for (int g : {0, 2}) {
    scene::GroupField field(l->model, g);
    REQUIRE(field.has_gradient());
    for (int i = 0; i < 400; ++i) {
      float p[3] = {pos(rng), pos(rng), pos(rng)}, f, grad[4];
      float* out[4] = {&grad[0], &grad[1], &grad[2], &grad[3]};
      backends::RuntimeError err;
      REQUIRE(field.eval(&p[0], &p[1], &p[2], 1, &f, err));
      REQUIRE(field.eval_gradient(&p[0], &p[1], &p[2], 1, out, err));
      CHECK(grad[0] == f);
      for (int a = 0; a < 3; ++a) {
        float q[3] = {p[0], p[1], p[2]}, r[3] = {p[0], p[1], p[2]}, fq, fr;
        q[a] = static_cast<float>(p[a] + h), r[a] = static_cast<float>(p[a] - h);
        REQUIRE(field.eval(&q[0], &q[1], &q[2], 1, &fq, err));
        REQUIRE(field.eval(&r[0], &r[1], &r[2], 1, &fr, err));
        // Skip points where a min, max or abs changes sides between the probes (a kink).
        double fd = (double(fq) - fr) / (double(q[a]) - r[a]), fwd = (double(fq) - f) / (double(q[a]) - p[a]),
               bwd = (double(f) - fr) / (double(p[a]) - r[a]);
        if (std::fabs(bwd - fwd) > 0.01 * (1 + std::fabs(fd))) continue;
        INFO("group " << g << " at " << p[0] << "," << p[1] << "," << p[2] << " d/d" << "xyz"[a] << " " << grad[1 + a]
                      << " vs " << fd);
        CHECK(close(grad[1 + a], fd, 5e-3));
        ++checked;
      }
    }
  }
  CHECK(checked > 1500);
  // A displacement texture has no gradient here (the polygonizer takes differences).
  scene::ShapeField textured(l->model.shapes.back());
  CHECK(!textured.has_gradient());
}

TEST_CASE("gradient: marching tetrahedra's normals are the function's own gradient") {
  // A sphere of radius 0.6 by its distance (not a polynomial, so differences are not exact): the
  // unit normal at p is p / |p|.
  auto l = test::load_scene("s.wrl", R"W(#VRML V2.0 utf8
    FShape { geometry FGeometry { definition "exp(0.6-sqrt(x*x+y*y+z*z))-1" bboxSize 2 2 2 resolution [24] } })W");
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  mesh::MesherOptions mt;
  mt.kind = mesh::Mesher::MarchingTetrahedra;
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(scene::mesh_shape(l->model.shapes[0], m, err, true, 1, true, mt));
  REQUIRE(m.normals.size() == m.positions.size());
  REQUIRE(m.positions.size() > 500);
  double worst = 0;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const auto& p = m.positions[v];
    double r = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    for (int a = 0; a < 3; ++a) worst = std::max(worst, std::fabs(m.normals[v][a] - p[a] / r));
  }
  CHECK(worst < 1e-5);  // the differences: 4.3e-5; the gradient: 1e-7
}

TEST_CASE("gradient: a big kernel's gradient is not compiled by LLVM, which would take seconds") {
  std::string body = "var s = 0;";
  for (int i = 0; i < 400; ++i) body += " s = s + sin(x * " + std::to_string(i + 1) + ".5) * y;";
  auto b = test::build("function FRep(x,y,z,t){ " + body + " return s; }");
  REQUIRE(b->ok);
  auto g = ir::gradient_module(*b->module);
  REQUIRE(g);
  REQUIRE(g->instruction_count() > driver::kMaxLlvmGradientOps);
  CHECK(driver::gradient_kernel(*b->module, "vm", {}) != nullptr);
  CHECK(driver::gradient_kernel(*b->module, "llvm", {}) == nullptr);
  auto small = test::build("function FRep(x,y,z,t){ return sin(x) * y; }");
  REQUIRE(small->ok);
  for (const std::string& be : backends::available_backends())
    CHECK(driver::gradient_kernel(*small->module, be, {}) != nullptr);
}
