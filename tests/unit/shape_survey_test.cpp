// The survey behind shape diagnostics (engine/scene/shape_survey.h): what it counts over a grid
// from bounds and open bricks is what evaluating every sample counts (inside, NaN, the faces'
// layers, the extent), on random CSG programs and on functions with NaN; budgets and early stops.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "engine/mesh/local_field.h"
#include "engine/scene/shape_survey.h"
#include "ir/interval_eval.h"
#include "tests/unit/helpers.h"
#include "tests/unit/random_csg.h"

using namespace fscript;

namespace {

struct Shape {
  std::unique_ptr<test::Built> b;
  std::unique_ptr<ir::IntervalTape> tape;
  std::unique_ptr<mesh::Field> field;
};

Shape shape(const std::string& src, bool local) {
  Shape s;
  s.b = test::build(src, "", true, {}, "vm");
  REQUIRE(s.b->ok);
  REQUIRE(ir::interval_evaluable(s.b->module->kernel_function()));
  s.tape = std::make_unique<ir::IntervalTape>(s.b->module->kernel_function());
  if (local)
    s.field = std::make_unique<mesh::LocalKernelField>(*s.b->kernel, 0.0f, *s.tape, nullptr, mesh::GradientTape{});
  else s.field = std::make_unique<mesh::KernelField>(*s.b->kernel, 0.0f, s.tape.get());
  return s;
}

// Every sample evaluated, counted as the survey counts.
scene::Survey dense(const mesh::Field& f, const scene::SurveyGrid& g) {
  scene::Survey s;
  std::vector<float> x, y, z, v;
  std::vector<std::array<int, 3>> at;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        x.push_back(g.at(0, i)), y.push_back(g.at(1, j)), z.push_back(g.at(2, k)), at.push_back({i, j, k});
  v.resize(x.size());
  backends::RuntimeError err;
  REQUIRE(f.eval(x.data(), y.data(), z.data(), x.size(), v.data(), err));
  for (size_t p = 0; p < v.size(); ++p) {
    bool in = v[p] > 0;
    ++s.points, s.inside += in, s.nan += std::isnan(v[p]);
    for (int a = 0; a < 3; ++a) {
      if (at[p][a] == 0) ++s.face_points[2 * a], s.face_inside[2 * a] += in;
      if (at[p][a] == g.n[a] - 1) ++s.face_points[2 * a + 1], s.face_inside[2 * a + 1] += in;
      if (in) {
        s.extent[2 * a] = std::min(s.extent[2 * a], g.at(a, at[p][a]) - g.step(a) / 2);
        s.extent[2 * a + 1] = std::max(s.extent[2 * a + 1], g.at(a, at[p][a]) + g.step(a) / 2);
      }
    }
  }
  return s;
}

void same_counts(const scene::Survey& a, const scene::Survey& b) {
  CHECK(a.points == b.points);
  CHECK(a.inside == b.inside);
  CHECK(a.nan == b.nan);
  for (int q = 0; q < 6; ++q) {
    CHECK(a.face_points[q] == b.face_points[q]);
    CHECK(a.face_inside[q] == b.face_inside[q]);
    if (a.inside) CHECK(a.extent[q] == Approx(b.extent[q]).margin(1e-6));
  }
}

}  // namespace

TEST_CASE("shape survey: bounds and open bricks count what every sample counts, on random CSG") {
  std::mt19937 rng(11);
  for (int p = 0; p < 30; ++p) {
    std::string src = test::random_csg(rng, 3);
    INFO(src);
    for (bool local : {false, true}) {
      Shape s = shape(src, local);
      scene::SurveyGrid g{{-1, 1, -0.9, 1.1, -1, 1}, {37, 24 + p, 40}};
      scene::Survey got;
      backends::RuntimeError err;
      REQUIRE(scene::survey(*s.field, g, {}, got, err));
      CHECK(got.complete);
      same_counts(got, dense(*s.field, g));
      CHECK(got.open.size() * 512 < g.points());  // bounds decided some of the box
    }
  }
}

TEST_CASE("shape survey: NaN counted where the bounds allow it, regions that are all NaN whole") {
  for (const char* src :
       {"0.5 - sqrt(x) - y*y - z*z", "0.5 - log(x + y) - z*z", "sqrt(-1 - x*x) + y", "0.5 - asin(2 * x) * y - z*z"}) {
    INFO(src);
    Shape s = shape(src, true);
    scene::SurveyGrid g{{-1, 1, -1, 1, -1, 1}, {33, 33, 33}};
    scene::Survey got;
    backends::RuntimeError err;
    REQUIRE(scene::survey(*s.field, g, {}, got, err));
    scene::Survey want = dense(*s.field, g);
    same_counts(got, want);
    CHECK(got.nan > 0);
    REQUIRE(got.has_nan_point);
    float v;
    const float* p = got.nan_point;
    REQUIRE(s.field->eval(&p[0], &p[1], &p[2], 1, &v, err));
    CHECK(std::isnan(v));
  }
}

TEST_CASE("shape survey: the budget leaves it incomplete; a stop at the first inside sample") {
  Shape s = shape("sin(9*x) * cos(7*y) + sin(8*z)", false);
  scene::SurveyGrid g{{-1, 1, -1, 1, -1, 1}, {64, 64, 64}};
  scene::Survey got;
  backends::RuntimeError err;
  scene::SurveyOptions small;
  small.budget = 10000;
  REQUIRE(scene::survey(*s.field, g, small, got, err));
  CHECK_FALSE(got.complete);
  scene::SurveyOptions first;
  first.stop_at_inside = true;
  REQUIRE(scene::survey(*s.field, g, first, got, err));
  CHECK(got.inside > 0);
  CHECK(got.points < g.points() / 8);
}
