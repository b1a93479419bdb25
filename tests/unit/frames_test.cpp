// The frame cache: compact frames round-trip within their quantisation step, the cache fills
// progressively as the paper describes, and filling in parallel gives the same frames.
#include <catch2/catch.hpp>
#include <cmath>
#include <mutex>

#include "runtime/mesh/frame_cache.h"
#include "runtime/mesh/implicit.h"
#include "tests/unit/helpers.h"

using namespace fscript;

namespace {

// A sphere whose radius grows with t: frame i is at t = i / frames.
struct GrowingSphere {
  std::unique_ptr<test::Built> b = test::build("function FRep(x,y,z,t){ return (0.3+0.4*t)^2 - x*x - y*y - z*z; }");
  size_t frames;
  std::vector<int> made;  // which frames the maker was asked for, in order
  std::mutex mutex;

  explicit GrowingSphere(size_t n) : frames(n) {}

  mesh::FrameCache::Maker maker() {
    return [this](size_t i, mesh::Mesh& out, backends::RuntimeError& err) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        made.push_back(static_cast<int>(i));
      }
      mesh::KernelField field(*b->kernel, static_cast<float>(i) / frames);
      mesh::ImplicitJob job;
      job.field = &field;
      job.box = {-1, 1, -1, 1, -1, 1};
      job.cells = {24, 24, 24};
      if (!mesh::polygonize_implicit(job, out, err)) return false;
      out.colours.assign(out.positions.size(), mesh::Vec3{0.25f, 0.5f, 1.0f});
      return true;
    };
  }
};

double radius(const mesh::Vec3& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]); }

}  // namespace

TEST_CASE("frames: a compact mesh expands to the same mesh within the quantisation step") {
  GrowingSphere s(1);
  REQUIRE(s.b->ok);
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(s.maker()(0, m, err));
  m.polylines = {{0, 1, 2}, {5, 3}};
  m.material = mesh::Material{};
  m.material->shininess = 0.7f;
  mesh::CompactMesh c = mesh::compress(m);
  mesh::Mesh back = mesh::expand(c);
  REQUIRE(back.positions.size() == m.positions.size());
  CHECK(back.triangles == m.triangles);
  CHECK(back.polylines == m.polylines);
  REQUIRE(back.material);
  CHECK(back.material->shininess == 0.7f);
  double worst_p = 0, worst_n = 0, worst_c = 0;
  for (size_t v = 0; v < m.positions.size(); ++v)
    for (int a = 0; a < 3; ++a) {
      worst_p = std::max(worst_p, double(std::fabs(back.positions[v][a] - m.positions[v][a])));
      worst_n = std::max(worst_n, double(std::fabs(back.normals[v][a] - m.normals[v][a])));
      worst_c = std::max(worst_c, double(std::fabs(back.colours[v][a] - m.colours[v][a])));
    }
  CHECK(worst_p <= 0.6 / 65535 + 1e-6);  // the sphere of radius 0.3 spans 0.6 per axis
  CHECK(worst_n < 1e-4);
  CHECK(worst_c <= 0.5 / 255 + 1e-6);
  auto topo = mesh::topology(back);
  CHECK(topo.watertight);
  CHECK(topo.euler == 2);
  // Compact: well under the 30 bytes per triangle of positions, normals and indices as floats and
  // 32-bit integers.
  double per_triangle = double(c.bytes()) / m.triangles.size();
  INFO("bytes per triangle " << per_triangle);
  CHECK(per_triangle < 14);
}

TEST_CASE("frames: the cache fills progressively, the paper's way") {
  GrowingSphere s(4);
  REQUIRE(s.b->ok);
  mesh::FrameCache cache(4, s.maker());
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(cache.get(2, m, err));  // a miss: made and cached, nothing else
  CHECK(s.made == std::vector<int>{2});
  CHECK(cache.cached() == 1);
  double r2 = radius(m.positions[0]);
  CHECK(r2 == Approx(0.5).margin(0.01));
  REQUIRE(cache.get(2, m, err));  // a hit: returned from the cache, and the next missing frame made
  CHECK(s.made == std::vector<int>{2, 3});
  CHECK(radius(m.positions[0]) == Approx(r2).margin(1e-4));
  REQUIRE(cache.get(3, m, err));  // a hit again: the next missing one wraps around to 0
  CHECK(s.made == std::vector<int>{2, 3, 0});
  REQUIRE(cache.get(0, m, err));
  REQUIRE(cache.get(1, m, err));  // 1 was made as the last missing frame
  CHECK(s.made == std::vector<int>{2, 3, 0, 1});
  CHECK(cache.cached() == 4);
  REQUIRE(cache.get(1, m, err));  // all cached: nothing more is made
  CHECK(s.made.size() == 4);
  CHECK(cache.bytes() > 0);
  CHECK(!cache.get(4, m, err));
  CHECK(err.message.find("outside") != std::string::npos);
}

TEST_CASE("frames: filling with threads gives the same frames as one at a time") {
  GrowingSphere a(5), b(5);
  REQUIRE(a.b->ok);
  mesh::FrameCache one(5, a.maker()), two(5, b.maker());
  backends::RuntimeError err;
  REQUIRE(one.fill(1, err));
  REQUIRE(two.fill(2, err));
  CHECK(one.cached() == 5);
  CHECK(two.cached() == 5);
  CHECK(one.bytes() == two.bytes());
  for (size_t i = 0; i < 5; ++i) {
    mesh::Mesh x, y;
    REQUIRE(one.get(i, x, err));
    REQUIRE(two.get(i, y, err));
    CHECK(x.positions == y.positions);
    CHECK(x.triangles == y.triangles);
  }
}

TEST_CASE("frames: a failing frame reports its error and caches nothing") {
  mesh::FrameCache cache(3, [](size_t i, mesh::Mesh&, backends::RuntimeError& err) {
    if (i == 1) {
      err.message = "loop budget exceeded";
      return false;
    }
    return true;
  });
  backends::RuntimeError err;
  CHECK(!cache.fill(2, err));
  CHECK(err.message == "loop budget exceeded");
  CHECK(!cache.has(1));
}
