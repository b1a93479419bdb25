// The frame cache: compact frames round-trip within their quantisation step, the cache fills
// progressively as the paper describes (coarse to fine in time), filling in parallel gives the same
// frames, and a glTF animation of some of the frames shows each until the next.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>

#include "engine/mesh/frame_cache.h"
#include "engine/mesh/gltf.h"
#include "engine/mesh/marching_tetrahedra.h"
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

TEST_CASE("frames: the progressive order is coarse to fine and takes each frame once") {
  using mesh::FrameCache;
  CHECK(FrameCache::progressive_order(1) == std::vector<size_t>{0});
  CHECK(FrameCache::progressive_order(4) == std::vector<size_t>{0, 2, 1, 3});
  for (size_t n : {2, 3, 5, 7, 24, 100}) {
    std::vector<size_t> order = FrameCache::progressive_order(n), sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<size_t> all(n);
    std::iota(all.begin(), all.end(), size_t{0});
    CHECK(sorted == all);
    CHECK(order[0] == 0);
    if (n >= 4) {  // the first two frames after 0 split the cycle in half, then in quarters
      CHECK(order[1] == n / 2);
      CHECK(std::max(order[2], order[3]) >= n / 2);
      CHECK(std::min(order[2], order[3]) < n / 2);
    }
  }
}

TEST_CASE("frames: fill makes frames coarse to fine and reports each one; put and compact") {
  GrowingSphere s(8);
  REQUIRE(s.b->ok);
  mesh::FrameCache cache(8, s.maker());
  backends::RuntimeError err;
  std::vector<size_t> counts;
  REQUIRE(cache.fill(1, err, [&](size_t cached) { counts.push_back(cached); }));
  CHECK(counts == std::vector<size_t>{1, 2, 3, 4, 5, 6, 7, 8});
  CHECK(s.made == std::vector<int>{0, 4, 2, 6, 1, 5, 3, 7});
  GrowingSphere t(8);
  mesh::FrameCache copy(8, t.maker());
  for (size_t i = 0; i < 8; i += 2) copy.put(i, *cache.compact(i));  // from elsewhere: not made again
  REQUIRE(copy.fill(2, err));
  std::sort(t.made.begin(), t.made.end());
  CHECK(t.made == std::vector<int>{1, 3, 5, 7});
  for (size_t i = 0; i < 8; ++i) CHECK(*copy.compact(i) == *cache.compact(i));
  CHECK(!cache.compact(8));
}

// The key times of a glb's first animation sampler (its input accessor, in the binary chunk).
static std::vector<float> key_times(const std::string& glb) {
  uint32_t json_len = 0;
  std::memcpy(&json_len, glb.data() + 12, 4);
  auto j = nlohmann::json::parse(glb.substr(20, json_len));
  const auto& acc = j["accessors"][j["animations"][0]["samplers"][0]["input"].get<size_t>()];
  const auto& view = j["bufferViews"][acc["bufferView"].get<size_t>()];
  size_t at = 20 + json_len + 8 + view.value("byteOffset", size_t{0}) + acc.value("byteOffset", size_t{0});
  std::vector<float> out(acc["count"].get<size_t>());
  std::memcpy(out.data(), glb.data() + at, out.size() * 4);
  return out;
}

TEST_CASE("frames: a glTF animation of some frames shows each from its start to the next") {
  mesh::Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  mesh::GltfAnimation a;
  a.cycle_interval = 2;
  a.frames = {tri, tri, tri};
  CHECK(key_times(mesh::encode_glb(tri, {a})) == std::vector<float>{0, 2.0f / 3, 4.0f / 3, 2});
  a.starts = {0, 0.5, 1.5};  // frames 0, 1 and 3 of 4 made so far
  CHECK(key_times(mesh::encode_glb(tri, {a})) == std::vector<float>{0, 0.5, 1.5, 2});
}
