// One dual contouring job split into slabs of block layers (fvrml-run --shard K/M without
// --frames): the shards' slabs joined give the very mesh of the whole job, for any shard count
// (more shards than layers too), pruned or dense, merged across the seams or not; a missing or
// damaged slab is an error.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "engine/mesh/dc_slabs.h"
#include "engine/mesh/dual_contour.h"
#include "tests/unit/field_helpers.h"

using namespace fscript;
using test::FnField;
using test::job;

namespace {

// A sphere of radius r that bounds itself (exactly, widened for float rounding), so the blocks
// far from its surface are pruned: all inside or all outside.
struct BoundedSphere : FnField {
  double r;
  explicit BoundedSphere(double radius)
      : FnField([radius](double x, double y, double z) { return radius - std::sqrt(x * x + y * y + z * z); }),
        r(radius) {}
  math::Interval bound(const mesh::Box3& b) const override {
    double near = 0, far = 0;
    for (int a = 0; a < 3; ++a) {
      double lo = b.lo[a], hi = b.hi[a];
      double n = lo > 0 ? lo : hi < 0 ? -hi : 0, f = std::max(std::abs(lo), std::abs(hi));
      near += n * n, far += f * f;
    }
    return math::Interval{static_cast<float>(r - std::sqrt(far) - 1e-4),
                          static_cast<float>(r - std::sqrt(near) + 1e-4)};
  }
  bool can_bound() const override { return true; }
};

mesh::Mesh whole(const mesh::ImplicitJob& j) {
  mesh::Mesh m;
  mesh::DualContourStats st;
  backends::RuntimeError err;
  REQUIRE(mesh::dual_contour(j, m, st, err));
  return m;
}

// Every shard's slab made, then joined.
std::vector<mesh::Slab> slabs(mesh::ImplicitJob j, int shards) {
  std::vector<mesh::Slab> all;
  for (int k = 0; k < shards; ++k) {
    auto split = mesh::SlabSplit::make(k, shards);
    j.mesher.slabs = split.get();
    mesh::Mesh m;
    mesh::DualContourStats st;
    backends::RuntimeError err;
    REQUIRE(mesh::dual_contour(j, m, st, err));
    CHECK(m.positions.empty());  // a shard's mesh is the merge's to make
    REQUIRE(split->slabs().size() == 1);
    all.push_back(split->slabs()[0]);
  }
  return all;
}

bool joined(mesh::ImplicitJob j, std::vector<mesh::Slab> parts, mesh::Mesh& m, std::string& error) {
  auto split = mesh::SlabSplit::join(std::move(parts));
  j.mesher.slabs = split.get();
  mesh::DualContourStats st;
  backends::RuntimeError err;
  bool ok = mesh::dual_contour(j, m, st, err);
  error = err.message;
  return ok;
}

void set_bytes(mesh::Slab& s, std::string bytes) {
  auto data = std::make_shared<const std::string>(std::move(bytes));
  s.data = data, s.bytes = *data;
}

void same_mesh(const mesh::Mesh& a, const mesh::Mesh& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.triangles.size() == b.triangles.size());
  CHECK(std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof a.positions[0]) == 0);
  CHECK(a.triangles == b.triangles);
}

}  // namespace

TEST_CASE("dc slabs: the joined slabs are the whole job's mesh, for any number of shards") {
  BoundedSphere sphere(0.83);
  FnField gyroid([](double x, double y, double z) {
    double s = 0.7 - std::sqrt(x * x + y * y + z * z);
    double g =
        std::sin(9 * x) * std::cos(9 * y) + std::sin(9 * y) * std::cos(9 * z) + std::sin(9 * z) * std::cos(9 * x);
    return std::min(s, 0.4 - std::abs(g));
  });
  FnField slab_z([](double, double, double z) { return 0.31 - std::abs(z); });  // flat: blocks merge across layers
  // Finer than the grid: tube faces, cut sheets and joined middles on every layer (dc_tubes.h).
  FnField fine([](double x, double y, double z) {
    return std::sin(43 * x) * std::cos(41 * y) + std::sin(41 * y) * std::cos(47 * z) +
        std::sin(47 * z) * std::cos(43 * x);
  });
  struct Case {
    const char* name;
    const mesh::Field* f;
    int cells;
    double tolerance;
    int threads;
  } cases[] = {{"pruned sphere", &sphere, 70, mesh::MesherOptions::kDefaultTolerance, 1},
               {"sphere, every cell kept", &sphere, 47, 0, 2},
               {"gyroid in a sphere", &gyroid, 64, mesh::MesherOptions::kDefaultTolerance, 2},
               {"flat slab, merged across blocks", &slab_z, 90, 0.5, 1},
               {"gyroid finer than the grid", &fine, 50, mesh::MesherOptions::kDefaultTolerance, 2}};
  for (const Case& c : cases) {
    SECTION(c.name) {
      mesh::ImplicitJob j = job(*c.f, c.cells);
      j.mesher.tolerance = c.tolerance;
      j.threads = c.threads;
      mesh::Mesh one = whole(j);
      REQUIRE(!one.triangles.empty());
      INFO(one.positions.size() << " vertices");
      // Its two planes are 2 x 91^2 cells: merged within blocks and into groups of blocks across the layers.
      if (c.f == &slab_z) CHECK(one.positions.size() < 8000);
      for (int shards : {1, 2, 3, 5, 9}) {  // 70 cells: 5 layers of blocks, so 9 shards leave some empty
        INFO(shards << " shards");
        mesh::Mesh m;
        std::string error;
        REQUIRE(joined(j, slabs(j, shards), m, error));
        same_mesh(one, m);
        auto t = mesh::topology(m);
        CHECK(t.watertight);
        CHECK(t.manifold);
      }
    }
  }
}

TEST_CASE("dc slabs: a missing, foreign or damaged slab is an error") {
  BoundedSphere sphere(0.83);
  mesh::ImplicitJob j = job(sphere, 70);
  std::vector<mesh::Slab> parts = slabs(j, 3);
  mesh::Mesh m;
  std::string error;
  SECTION("missing") {
    parts.erase(parts.begin() + 1);
    CHECK_FALSE(joined(j, parts, m, error));
    CHECK(error.find("the parts hold block layers 0 to ") != std::string::npos);
    CHECK(error.find(" of this shape's 5 ") != std::string::npos);
  }
  SECTION("another grid") {
    mesh::ImplicitJob other = job(sphere, 70, 1.01);
    CHECK_FALSE(joined(other, parts, m, error));
    CHECK(error.find("another grid") != std::string::npos);
  }
  SECTION("truncated or with a wild index") {
    std::string good(parts[1].bytes);
    for (size_t cut : {good.size() - 1, good.size() / 2, size_t{40}}) {
      set_bytes(parts[1], good.substr(0, cut));
      CHECK_FALSE(joined(j, parts, m, error));
      CHECK(error.find("damaged") != std::string::npos);
    }
    for (size_t at = 100; at < good.size(); at += good.size() / 97) {  // any flipped byte: an error or a mesh, no crash
      std::string bad = good;
      bad[at] = static_cast<char>(bad[at] ^ 0x5a);
      set_bytes(parts[1], bad);
      joined(j, parts, m, error);
    }
  }
}
