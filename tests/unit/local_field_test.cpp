// Local tapes (engine/mesh/local_field.h): a region's simplified tapes give the whole kernel's bits
// inside the region, values and gradients, nested regions too; dual contouring through them writes
// the mesh the whole function gives, on random CSG programs.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>

#include "engine/driver/driver.h"
#include "engine/mesh/local_field.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "ir/interval_eval.h"
#include "tests/unit/helpers.h"
#include "tests/unit/random_csg.h"

using namespace fscript;

namespace {

// An FRep compiled with what a scene shape has: its interval tape, its gradient kernel and tape.
struct Compiled {
  std::unique_ptr<test::Built> b;
  std::unique_ptr<backends::Kernel> gradient;
  std::unique_ptr<ir::IntervalTape> tape, gradient_tape;
};

Compiled compile(const std::string& src, const std::string& backend = "vm") {
  Compiled c;
  c.b = test::build(src, "", true, {}, backend);
  REQUIRE(c.b->ok);
  REQUIRE(ir::interval_evaluable(c.b->module->kernel_function()));
  c.tape = std::make_unique<ir::IntervalTape>(c.b->module->kernel_function());
  std::unique_ptr<ir::Module> g = driver::gradient_ir(*c.b->module);
  REQUIRE(g);
  c.gradient = driver::compile_gradient(*g, backend, {});
  REQUIRE(c.gradient);
  c.gradient_tape = std::make_unique<ir::IntervalTape>(g->kernel_function());
  return c;
}

// The kernel's field offering local tapes as a scene shape's does (or not: the whole function).
struct LocalKernelField : mesh::KernelField {
  LocalKernelField(const Compiled& c, float t, bool local)
      : KernelField(*c.b->kernel, t, c.tape.get(), c.gradient.get()),
        tapes(*c.tape, t, [&c] { return c.gradient_tape.get(); }), offers(local) {}
  std::shared_ptr<const mesh::Field> local(const mesh::Box3& b) const override {
    return offers ? tapes.at(b) : nullptr;
  }
  mesh::LocalTapes tapes;
  bool offers;
};

bool same_bits(const float* a, const float* b, size_t n) { return n == 0 || std::memcmp(a, b, n * sizeof(float)) == 0; }
// A mesh's vectors as floats (an empty mesh's data() is null: not dereferenced).
const float* floats(const std::vector<mesh::Vec3>& v) { return reinterpret_cast<const float*>(v.data()); }

}  // namespace

TEST_CASE("local tapes: values and gradients inside a region are the whole kernel's bits, nested regions too") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0, 1);
  size_t simplified = 0;
  for (int program = 0; program < 40; ++program) {
    Compiled c = compile("function FRep(x,y,z,t){ return " + test::random_csg(rng, 4) + " + 0.01*t; }");
    LocalKernelField whole(c, 0.5f, false);
    mesh::LocalTapes tapes(*c.tape, 0.5f, [&c] { return c.gradient_tape.get(); });
    for (int region = 0; region < 12; ++region) {
      mesh::Box3 box;
      for (int a = 0; a < 3; ++a) {
        float lo = -1 + 1.8f * u(rng), side = 0.05f + 0.4f * u(rng);
        box.lo[a] = lo, box.hi[a] = lo + side;
      }
      std::shared_ptr<const mesh::Field> f = tapes.at(box);
      if (!f) continue;
      ++simplified;
      // A box inside the box, for a region within a region.
      mesh::Box3 inner = box;
      for (int a = 0; a < 3; ++a) inner.hi[a] = inner.lo[a] + (box.hi[a] - box.lo[a]) / 3;
      std::shared_ptr<const mesh::Field> g = f->local(inner);
      const size_t n = 300;
      std::vector<float> x(n), y(n), z(n);
      for (size_t i = 0; i < n; ++i) {
        const mesh::Box3& in = i % 2 && g ? inner : box;
        x[i] = in.lo[0] + (in.hi[0] - in.lo[0]) * u(rng), y[i] = in.lo[1] + (in.hi[1] - in.lo[1]) * u(rng),
        z[i] = in.lo[2] + (in.hi[2] - in.lo[2]) * u(rng);
        if (i == 0) x[i] = in.lo[0], y[i] = in.hi[1], z[i] = in.lo[2];  // the box's corners belong to it
      }
      std::vector<float> want(n), got(n), want_g(4 * n), got_g(4 * n);
      backends::RuntimeError err;
      REQUIRE(whole.eval(x.data(), y.data(), z.data(), n, want.data(), err));
      REQUIRE(f->eval(x.data(), y.data(), z.data(), n, got.data(), err));
      CHECK(same_bits(want.data(), got.data(), n));
      float* const wg[4] = {want_g.data(), want_g.data() + n, want_g.data() + 2 * n, want_g.data() + 3 * n};
      float* const gg[4] = {got_g.data(), got_g.data() + n, got_g.data() + 2 * n, got_g.data() + 3 * n};
      REQUIRE(whole.eval_gradient(x.data(), y.data(), z.data(), n, wg, err));
      REQUIRE(f->eval_gradient(x.data(), y.data(), z.data(), n, gg, err));
      CHECK(same_bits(want_g.data(), got_g.data(), 4 * n));
      if (!g) continue;
      std::vector<float> xi, yi, zi;  // the inner box's points
      for (size_t i = 1; i < n; i += 2) xi.push_back(x[i]), yi.push_back(y[i]), zi.push_back(z[i]);
      std::vector<float> w2(xi.size()), g2(xi.size());
      REQUIRE(whole.eval(xi.data(), yi.data(), zi.data(), xi.size(), w2.data(), err));
      REQUIRE(g->eval(xi.data(), yi.data(), zi.data(), xi.size(), g2.data(), err));
      CHECK(same_bits(w2.data(), g2.data(), xi.size()));
    }
  }
  CHECK(simplified > 100);  // the programs' regions do decide choices: the check is not empty
}

TEST_CASE("local tapes: dual contouring through them writes the whole function's mesh, bit for bit") {
  std::mt19937 rng(11);
  int narrowed = 0;
  for (int program = 0; program < 60; ++program) {
    const std::string be = program % 3 == 0 ? "sse" : "vm";
    Compiled c = compile("function FRep(x,y,z,t){ return " + test::random_csg(rng, 5) + "; }", be);
    LocalKernelField whole(c, 0, false), local(c, 0, true);
    mesh::ImplicitJob j;
    j.box = {-1, 1, -1.05, 1, -1, 0.97};
    j.cells = {40 + program % 7, 43, 37 + program % 5};
    j.mesher.kind = mesh::Mesher::DualContouring;
    j.threads = 1 + program % 2;
    mesh::Mesh a, b;
    backends::RuntimeError err;
    j.field = &whole;
    REQUIRE(mesh::polygonize(j, a, err));
    const uint64_t before = mesh::local_tape_totals().simplified.load();
    j.field = &local;
    REQUIRE(mesh::polygonize(j, b, err));
    INFO("program " << program);
    narrowed += mesh::local_tape_totals().simplified.load() > before;
    REQUIRE(a.positions.size() == b.positions.size());
    REQUIRE(a.triangles == b.triangles);
    CHECK(same_bits(floats(a.positions), floats(b.positions), 3 * a.positions.size()));
    REQUIRE(a.normals.size() == b.normals.size());
    CHECK(same_bits(floats(a.normals), floats(b.normals), 3 * a.normals.size()));
  }
  CHECK(narrowed > 40);  // most programs mesh through simplified tapes: the comparison means something
}
