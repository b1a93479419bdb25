// The direct renderer (engine/render/direct.h): pruned and dense hits bit for bit on random CSG
// programs, on every backend and thread count; depths and normals of shapes with a known answer.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "engine/mesh/local_field.h"
#include "engine/render/direct.h"
#include "engine/render/shading.h"
#include "ir/interval_eval.h"
#include "tests/unit/helpers.h"
#include "tests/unit/random_csg.h"

using namespace fscript;

namespace {

// A script's field as fscript render3d makes it: bounded, with its regions' tapes.
struct Script {
  std::unique_ptr<test::Built> b;
  std::unique_ptr<ir::IntervalTape> tape;
  std::unique_ptr<mesh::Field> field;
};

Script script(const std::string& src, const std::string& backend = "vm") {
  Script s;
  s.b = test::build(src, "", true, {}, backend);
  REQUIRE(s.b->ok);
  const ir::Function& fn = s.b->module->kernel_function();
  REQUIRE(ir::interval_evaluable(fn));
  s.tape = std::make_unique<ir::IntervalTape>(fn);
  s.field = std::make_unique<mesh::LocalKernelField>(*s.b->kernel, 0.0f, *s.tape, nullptr, mesh::GradientTape{});
  return s;
}

render::Hits trace(const mesh::Field& f, const render::RayGrid& g, bool prune, unsigned threads = 1,
                   render::DirectStats* stats = nullptr) {
  render::Hits h;
  render::DirectStats st;
  render::DirectOptions o;
  o.prune = prune, o.threads = threads;
  backends::RuntimeError err;
  REQUIRE(render::trace(f, g, o, h, st, err));
  CHECK(st.pruned == prune);
  if (stats) *stats = st;
  return h;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same(const render::Hits& a, const render::Hits& b) {
  return same_bits(a.depth, b.depth) && same_bits(a.point, b.point) && same_bits(a.normal, b.normal) &&
      a.step == b.step;
}

size_t hits(const render::Hits& h) {
  size_t n = 0;
  for (float d : h.depth) n += std::isfinite(d);
  return n;
}

}  // namespace

TEST_CASE("direct pictures: pruned and dense hits are the same bits, on every backend and thread count") {
  std::mt19937 rng(5);
  size_t drawn = 0, pruned_points = 0, dense_points = 0;
  for (int program = 0; program < 10; ++program) {
    const std::string src = "function FRep(x,y,z,t){ return " + test::random_csg(rng, 4) + "; }";
    Script vm = script(src);
    double az = program * 37.0, el = program % 3 == 0 ? 0.0 : 25.0 - 10.0 * program;
    render::RayGrid g = render::orthographic({-1, 1, -1.05, 1, -1, 0.97}, 61 + program, 47, 70 + program, az, el);
    render::DirectStats dense_stats, pruned_stats;
    render::Hits dense = trace(*vm.field, g, false, 1, &dense_stats);
    render::Hits pruned = trace(*vm.field, g, true, 1, &pruned_stats);
    CHECK(same(dense, pruned));
    CHECK(same(dense, trace(*vm.field, g, true, 2)));
    for (const std::string& be : backends::available_backends()) {
      if (be == "vm") continue;
      Script other = script(src, be);
      CHECK(same(dense, trace(*other.field, g, true)));
      CHECK(same(dense, trace(*other.field, g, false)));
    }
    drawn += hits(dense) > 0 && hits(dense) < dense.depth.size();
    pruned_points += pruned_stats.points, dense_points += dense_stats.points;
  }
  CHECK(drawn >= 4);                           // the pictures show shapes, not empty or full frames
  CHECK(pruned_points * 4 < dense_points);     // and the intervals did skip most steps
}

TEST_CASE("direct pictures: a shape extruded along the view is probed once a ray where its tape is constant") {
  // 2D programs in (u, v) extruded along w, seen down w: the regions whose tape drops w are
  // probed once a ray (and once a tape, region after region), with the dense picture's bits.
  std::mt19937 rng(11);
  struct Axis {
    const char *u, *v, *w;
    double az, el;
  };
  const Axis axes[] = {{"x", "y", "z", 0, 0}, {"z", "y", "x", 90, 0}, {"x", "z", "y", 0, 90}};
  for (const Axis& a : axes) {
    size_t constant = 0;
    for (int program = 0; program < 3; ++program) {
      std::string flat = program == 0 ? "0.2 - abs(sqrt(x*x + y*y) - 0.5)" : test::random_csg(rng, 3);
      for (size_t at; (at = flat.find('z')) != std::string::npos;) flat.replace(at, 1, "0.0");
      const std::string src = std::string("function F2(x, y) { return ") + flat + "; }\n" +
          "function FRep(x, y, z, t) { return min(F2(" + a.u + ", " + a.v + "), 0.55 - abs(" + a.w + ")); }";
      Script s = script(src);
      INFO(src);
      render::RayGrid g = render::orthographic({-1, 1, -1, 1, -1, 1}, 57, 50, 160, a.az, a.el);
      render::DirectStats st;
      render::Hits dense = trace(*s.field, g, false);
      CHECK(same(dense, trace(*s.field, g, true, 1, &st)));
      CHECK(same(dense, trace(*s.field, g, true, 2)));
      constant += st.constant;
      render::RayGrid tilted = render::orthographic({-1, 1, -1, 1, -1, 1}, 40, 40, 90, a.az + 20, a.el - 15);
      CHECK(same(trace(*s.field, tilted, false), trace(*s.field, tilted, true, 1, &st)));
      CHECK(st.constant == 0);  // tilted rays move along every axis
    }
    INFO("extruded along " << a.w);
    CHECK(constant > 0);
  }
}

TEST_CASE("direct pictures: a ball's depth and normals are the true ones, seen from any side") {
  Script s = script("function FRep(x,y,z,t){ return 0.36 - (x-0.1)*(x-0.1) - y*y - (z+0.05)*(z+0.05); }");
  const double c[3] = {0.1, 0, -0.05}, r = 0.6;
  for (auto [az, el] : {std::pair{0.0, 0.0}, {30.0, 20.0}, {-120.0, -45.0}, {0.0, 90.0}}) {
    render::RayGrid g = render::orthographic({-1, 1, -1, 1, -1, 1}, 96, 80, 128, az, el);
    render::Hits h = trace(*s.field, g, true);
    size_t n = 0;
    double worst_depth = 0, worst_angle = 0;
    for (uint32_t row = 0; row < g.h; ++row)
      for (uint32_t col = 0; col < g.w; ++col) {
        // The ray against the ball, in double.
        double o[3], v[3];
        g.ray(col, row, o, v);
        double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
        double a = v[0] * v[0] + v[1] * v[1] + v[2] * v[2], b = oc[0] * v[0] + oc[1] * v[1] + oc[2] * v[2];
        double disc = b * b - a * (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r);
        size_t i = size_t(row) * g.w + col;
        // Rays that graze the ball within a step of its outline may go either way.
        if (disc < 0.02 * a) {
          if (disc < 0) CHECK(!std::isfinite(h.depth[i]));
          continue;
        }
        REQUIRE(std::isfinite(h.depth[i]));
        double d = (-b - std::sqrt(disc)) / a;
        worst_depth = std::max(worst_depth, std::fabs(h.depth[i] - d));
        double p[3], nrm[3], dotp = 0;
        render::RayGrid::at(o, v, d, p);
        for (int k = 0; k < 3; ++k) nrm[k] = (p[k] - c[k]) / r, dotp += nrm[k] * h.normal[i][static_cast<size_t>(k)];
        worst_angle = std::max(worst_angle, std::acos(std::min(1.0, dotp)) * 180 / M_PI);
        ++n;
      }
    INFO("view " << az << ", " << el);
    CHECK(n > 300);
    CHECK(worst_depth < 1e-5);  // refined far below the step (2 / 127 deep)
    CHECK(worst_angle < 0.05);
  }
}

TEST_CASE("direct pictures: a box, a torus, and a solid cut by its box closed by the box's faces") {
  render::RayGrid g = render::orthographic({-1, 1, -1, 1, -1, 1}, 64, 64, 64, 0, 0);
  SECTION("a cube's front face: depth 1 - 0.5 and the normal +z, its outline exact") {
    Script s = script("function FRep(x,y,z,t){ return 0.5 - max(max(abs(x), abs(y)), abs(z)); }");
    render::Hits h = trace(*s.field, g, true);
    for (uint32_t row = 0; row < g.h; ++row)
      for (uint32_t col = 0; col < g.w; ++col) {
        double o[3], v[3];
        g.ray(col, row, o, v);
        size_t i = size_t(row) * g.w + col;
        bool in = std::fabs(o[0]) <= 0.5 && std::fabs(o[1]) <= 0.5;
        REQUIRE(std::isfinite(h.depth[i]) == in);
        if (!in) continue;
        CHECK(std::fabs(h.depth[i] - 0.5) < 1e-6);
        CHECK(h.normal[i][2] > 0.9999f);
      }
  }
  SECTION("a torus: every hit on the surface, the normal its gradient's") {
    Script s = script("function FRep(x,y,z,t){ var q = sqrt(x*x + z*z) - 0.6; return 0.04 - q*q - y*y; }");
    render::RayGrid tilted = render::orthographic({-1, 1, -1, 1, -1, 1}, 90, 90, 90, 20, 35);
    render::Hits h = trace(*s.field, tilted, true);
    size_t n = 0;
    for (size_t i = 0; i < h.depth.size(); ++i) {
      if (!std::isfinite(h.depth[i])) continue;
      auto [x, y, z] = h.point[i];
      double rho = std::sqrt(double(x) * x + double(z) * z), q = rho - 0.6;
      CHECK(std::fabs(0.04 - q * q - double(y) * y) < 1e-5);
      double gx = q * x / rho, gy = y, gz = q * z / rho, l = std::sqrt(gx * gx + gy * gy + gz * gz);
      double dotp = (gx * h.normal[i][0] + gy * h.normal[i][1] + gz * h.normal[i][2]) / l;
      CHECK(dotp > 0.9999);  // outward: minus the gradient of f, plus the gradient of the distance
      ++n;
    }
    CHECK(n > 1000);
  }
  SECTION("a solid larger than its box: the box's front face, its normal the face's") {
    Script s = script("function FRep(x,y,z,t){ return 3.5 - x*x - y*y - z*z; }");
    render::Hits h = trace(*s.field, g, true);
    for (size_t i = 0; i < h.depth.size(); ++i) {
      REQUIRE(std::isfinite(h.depth[i]));
      CHECK(h.depth[i] == 0.0f);
      CHECK(h.normal[i] == std::array<float, 3>{0, 0, 1});
    }
    render::RayGrid side = render::orthographic({-1, 1, -1, 1, -1, 1}, 32, 32, 64, 90, 0);  // from +x
    h = trace(*s.field, side, true);
    for (size_t i = 0; i < h.depth.size(); ++i) CHECK(h.normal[i] == std::array<float, 3>{1, 0, 0});
  }
}

TEST_CASE("shading seen along one direction gives Shading::shade's values, bit for bit") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  render::Shading plain, shiny, lit;
  shiny.material = mesh::Material{};
  shiny.material->shininess = 0.3f, shiny.material->specular = {0.5f, 0.4f, 0.3f};
  lit.lights.push_back({{0.3f, -1, -0.2f}, {1, 0.9f, 0.8f}, 0.8f, 0.1f});
  for (render::Shading* s : {&plain, &shiny, &lit}) {
    s->right = {0.8, 0, -0.6}, s->up = {0, 1, 0}, s->back = {0.6, 0, 0.8};
    const render::FixedViewShading fixed(*s, s->back);
    for (int i = 0; i < 500; ++i) {
      render::V3 n{u(rng), u(rng), u(rng)};
      std::array<float, 3> base{0.8f, 0.5f, 0.2f};
      auto want = s->shade(base, n, s->back), got = fixed.shade(base, n);
      CHECK(std::memcmp(want.data(), got.data(), sizeof want) == 0);
    }
  }
}
