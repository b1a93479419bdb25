// Octree pruning of implicit meshing: the bounds of scene fields hold at every point, and every
// implicit shape and FTransform of the corpus, the paper's examples and the benchmarks gives the
// same mesh, bit for bit, pruned or dense, on one thread or two.
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <random>

#include "frontend/fscript/embedded.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"
#include "ir/interval_eval.h"
#include "engine/driver/driver.h"
#include "engine/mesh/marching_tetrahedra.h"
#include "engine/scene/scene_model.h"
#include "engine/scene/shape_field.h"
#include "engine/scene/shape_mesh.h"
#include "runtime/support/files.h"
#include "tests/support/skip.h"
#include "tests/unit/scene_helpers.h"

using namespace fscript;
namespace fsys = std::filesystem;

namespace {

using Loaded = test::LoadedScene;

std::unique_ptr<Loaded> load_text(const std::string& path, const std::string& text, double scale = 1) {
  scene::ModelOptions o;
  o.resolution_scale = scale;
  o.fraction = 0.37;  // time-dependent shapes at a t that is not a round number
  return test::load_scene(path, text, o);
}

bool same_bits(const mesh::Mesh& a, const mesh::Mesh& b) {
  auto eq = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return eq(a.positions, b.positions) && eq(a.normals, b.normals) && eq(a.triangles, b.triangles) &&
      eq(a.colours, b.colours);
}

struct Tally {
  size_t meshes = 0, pruned = 0, decided = 0;  // decided: some region was found empty or full
};

// Every implicit shape outside an FTransform and every top-level implicit FTransform of the model:
// pruned (1 and 2 threads) and dense meshes are the same bits.
void compare_all(const Loaded& l, const std::string& where, Tally& tally) {
  auto one = [&](auto mesh_fn, const std::string& what) {
    mesh::Mesh dense, pruned, pruned2;
    backends::RuntimeError e1, e2, e3;
    bool ok_dense = mesh_fn(dense, e1, 1, false);
    mesh::PruneStats before = mesh::prune_totals();
    bool ok_pruned = mesh_fn(pruned, e2, 1, true);
    mesh::PruneStats after = mesh::prune_totals();
    bool ok_pruned2 = mesh_fn(pruned2, e3, 2, true);
    INFO(where << ": " << what << ": " << e1.message << " / " << e2.message);
    REQUIRE(ok_dense == ok_pruned);
    REQUIRE(ok_pruned == ok_pruned2);
    if (!ok_dense) {
      CHECK(e1.message == e2.message);
      return;
    }
    CHECK(same_bits(dense, pruned));
    CHECK(same_bits(pruned, pruned2));
    CHECK(after.fallbacks == before.fallbacks);
    ++tally.meshes;
    if (after.pruned && after.points > before.points &&
        after.evaluated - before.evaluated < after.points - before.points)
      ++tally.decided;
    size_t levels_before = 0, levels_after = 0;
    for (const auto& lv : before.levels) levels_before += lv.empty + lv.full + lv.ambiguous;
    for (const auto& lv : after.levels) levels_after += lv.empty + lv.full + lv.ambiguous;
    if (levels_after > levels_before) ++tally.pruned;
  };
  for (size_t i = 0; i < l.model.shapes.size(); ++i) {
    const scene::Shape& s = l.model.shapes[i];
    if (s.group >= 0 || s.kind != scene::ShapeKind::Implicit) continue;
    one([&](mesh::Mesh& m, backends::RuntimeError& e, int threads,
            bool prune) { return scene::mesh_shape(s, m, e, true, threads, prune); },
        "shape " + std::to_string(i));
  }
  for (size_t g = 0; g < l.model.groups.size(); ++g) {
    if (l.model.groups[g].parent >= 0 || scene::parametric_group(l.model, static_cast<int>(g))) continue;
    one([&](mesh::Mesh& m, backends::RuntimeError& e, int threads,
            bool prune) { return scene::mesh_group(l.model, static_cast<int>(g), m, e, true, threads, prune); },
        "FTransform " + std::to_string(g));
  }
}

void compare_folder(const std::string& dir, double scale, Tally& tally) {
  for (const auto& e : fsys::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".wrl") continue;
    std::string text, err;
    REQUIRE(support::read_file(e.path().string(), text, err));
    if (text.rfind("BSCRYPT", 0) == 0) continue;  // the encrypted course file
    auto l = load_text(e.path().string(), text, scale);
    if (!l->ok) continue;  // a scene with errors has no meshes (the corpus test covers that)
    compare_all(*l, e.path().string(), tally);
  }
}

}  // namespace

TEST_CASE("prune: the corpus, the paper's examples and the benchmark scenes mesh the same pruned or dense") {
  if (!fsys::exists(FS_CORPUS_DIR)) {
    test::skip(test::SkipKind::Missing, "the shared corpus folder is absent: " FS_CORPUS_DIR);
    return;
  }
  Tally corpus, paper, bench;
  compare_folder(FS_CORPUS_DIR, 1, corpus);
  compare_folder(FS_SOURCE_DIR "/examples", 1, paper);
  compare_folder(FS_SOURCE_DIR "/bench/scenes", 0.25, bench);
  WARN("implicit meshes (pruned by intervals / with regions decided): corpus "
       << corpus.meshes << " (" << corpus.pruned << " / " << corpus.decided << "), examples " << paper.meshes << " ("
       << paper.pruned << " / " << paper.decided << "), bench " << bench.meshes << " (" << bench.pruned << " / "
       << bench.decided << ")");
  CHECK(corpus.meshes >= 7);  // the course's files are mostly parametric
  CHECK(corpus.decided == corpus.meshes);
  CHECK(paper.meshes >= 1);   // Figure 6: blends bound too loosely to decide anything (it runs dense)
  CHECK(bench.decided == bench.meshes);
}

TEST_CASE("prune: every set operation, blend, analytical operation, texture and affine move keeps the same mesh") {
  const char* scenes[] = {
      R"W(FTransform { operation "intersection" children [
        FShape { geometry FGeometry { definition "sin(8*x)*cos(8*y)+sin(8*y)*cos(8*z)+sin(8*z)*cos(8*x)" bboxSize 2 2 2 resolution [40] } }
        FShape { geometry FGeometry { definition "0.9^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [40] } } ] })W",
      R"W(FTransform { operation "subtraction" children [
        FShape { geometry FGeometry { definition "0.8^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [37] } }
        FShape { geometry FGeometry { definition "0.45^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [37] } } ] })W",
      R"W(FTransform { operation "blend_union" parameters [0.1 0.3 0.7] children [
        FShape { geometry FGeometry { definition "0.3^2-(x-0.35)^2-y^2-z^2" bboxSize 2 2 2 resolution [41] } }
        FShape { geometry FGeometry { definition "0.3^2-(x+0.35)^2-y^2-z^2" bboxSize 2 2 2 resolution [41] } } ] })W",
      R"W(FTransform { operation "blend_intersection" parameters [0.05 0.5 0.5] children [
        FShape { geometry FGeometry { definition "0.6-abs(x)-abs(y)" bboxSize 2 2 2 resolution [33] } }
        FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [33] } } ] })W",
      R"W(FTransform { type "analytical" operation "f*(1-t)+g*t" children [
        FShape { geometry FGeometry { definition "0.3^2-x^2-y^2-z^2" bboxSize 2 2 2 resolution [36] } }
        FShape { geometry FGeometry { definition "0.6-max(abs(x),max(abs(y),abs(z)))" bboxSize 2 2 2 resolution [36] } } ] })W",
      R"W(FTransform { translation "0.3, -0.1, 0.05" rotation "0.3, 0.5, 0.8, 0.7" scale "1.3, 0.7, 1.1" children [
        FTransform { operation "union" children [
          FShape { geometry FGeometry { definition "0.3^2-(x-0.3)^2-y^2-z^2" bboxSize 2 2 2 resolution [35] } }
          FShape { geometry FGeometry { definition "0.25-abs(y)-abs(x+0.3)-abs(z)" bboxSize 2 2 2 resolution [35] } } ] } ] })W",
      R"W(FTransform { translation "0.2*t, 0, 0" rotation "0, 0, 1, t" children [
          FShape { geometry FGeometry { definition "0.4^2-x^2-(2*y)^2-z^2" bboxSize 2 2 2 resolution [34] } } ] })W",
      R"W(FShape { appearance FAppearance { texture3D FTexture3D { definition "0.05*sin(20*u)*cos(20*v)" type "displacement" } }
        geometry FGeometry { definition "0.6-sqrt(x*x+y*y+z*z)" bboxSize 2 2 2 resolution [45] } })W",
      R"W(FShape { geometry FGeometry { definition "function FRep(x,y,z,t){ var r=0; for (var i=0;i<3;i++) r+=x*x; return 0.5-r-y*y-z*z; }" bboxSize 2 2 2 resolution [30] } })W",
      R"W(FShape { geometry FGeometry { definition "0.5^2-(x-0.5*t)^2-y^2-z^2" bboxSize 2 2 2 resolution [43 31 27] timeSpan 0 1 } })W",
  };
  Tally tally;
  for (const char* body : scenes) {
    auto l = load_text("s.wrl", std::string("#VRML V2.0 utf8\n") + body);
    INFO(body << "\n" << frontend::render_all(l->diag));
    REQUIRE(l->ok);
    compare_all(*l, body, tally);
  }
  CHECK(tally.meshes == sizeof(scenes) / sizeof(scenes[0]));
  CHECK(tally.decided >= tally.meshes - 1);  // the loop cannot be bounded (it runs dense)
}

TEST_CASE("prune: scene fields' bounds hold every point of random boxes") {
  auto l = load_text("s.wrl", R"W(#VRML V2.0 utf8
    FTransform { translation "0.3, -0.1, 0.05" rotation "0.3, 0.5, 0.8, 0.7" scale "1.3, 0.7, 1.1" operation "blend_union" parameters [0.1 0.3 0.7] children [
      FShape { appearance FAppearance { texture3D FTexture3D { definition "0.05*sin(20*u)*cos(20*v)" type "displacement" } }
        geometry FGeometry { definition "0.3^2-(x-0.35)^2-y^2-z^2" bboxSize 2 2 2 } }
      FTransform { operation "subtraction" children [
        FShape { geometry FGeometry { definition "0.6-abs(x)-abs(y)-abs(z)" bboxSize 2 2 2 } }
        FShape { geometry FGeometry { definition "0.2^2-x^2-y^2-z^2" bboxSize 2 2 2 } } ] } ] }
    FTransform { operation "blend_intersection" parameters [0.05 0.5 0.5] children [
      FShape { geometry FGeometry { definition "0.6-abs(x)-abs(y)" bboxSize 2 2 2 } }
      FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" bboxSize 2 2 2 } } ] })W");
  INFO(frontend::render_all(l->diag));
  REQUIRE(l->ok);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-1.5f, 1.5f), size(0.0f, 0.6f), frac(0.0f, 1.0f);
  size_t checked = 0;
  for (int g : {0, 2}) {
    scene::GroupField field(l->model, g);
    REQUIRE(field.can_bound());
    for (int box = 0; box < 300; ++box) {
      mesh::Box3 b;
      for (int a = 0; a < 3; ++a) b.lo[a] = pos(rng), b.hi[a] = b.lo[a] + size(rng);
      math::Interval v = field.bound(b);
      std::vector<float> x(64), y(64), z(64), out(64);
      for (size_t i = 0; i < 64; ++i) {  // corners and random points
        float* p[3] = {&x[i], &y[i], &z[i]};
        for (int a = 0; a < 3; ++a)
          *p[a] = i < 8 ? ((i >> a) & 1 ? b.hi[a] : b.lo[a]) : b.lo[a] + frac(rng) * (b.hi[a] - b.lo[a]);
      }
      backends::RuntimeError err;
      REQUIRE(field.eval(x.data(), y.data(), z.data(), 64, out.data(), err));
      for (size_t i = 0; i < 64; ++i) {
        INFO("group " << g << " at " << x[i] << " " << y[i] << " " << z[i] << ": " << out[i] << " not in [" << v.lo
                      << ", " << v.hi << "] nan " << v.nan);
        CHECK(v.contains(out[i]));
        ++checked;
      }
    }
  }
  CHECK(checked == 2 * 300 * 64);
}

namespace {
// A sphere whose bound wrongly says "inside" for boxes away from the origin: the polygonizer must
// notice the contradiction and mesh densely.
class LyingField : public mesh::Field {
 public:
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError&) const override {
    for (size_t i = 0; i < n; ++i) out[i] = 0.5f - (x[i] * x[i] + y[i] * y[i] + z[i] * z[i]);
    return true;
  }
  math::Interval bound(const mesh::Box3& b) const override {
    return b.lo[0] > 0.3f ? math::Interval{1, 2, false} : math::Interval::everything();
  }
  bool can_bound() const override { return true; }
};
}  // namespace

TEST_CASE("prune: a bound that a point contradicts makes the job run dense, with the dense mesh") {
  LyingField f;
  mesh::ImplicitJob job;
  job.field = &f;
  job.box = {-1, 1, -1, 1, -1, 1};
  job.cells = {40, 40, 40};
  mesh::Mesh pruned, dense;
  mesh::PruneStats st;
  backends::RuntimeError err;
  job.stats = &st;
  REQUIRE(mesh::polygonize_implicit(job, pruned, err));
  CHECK(st.fallbacks == 1);
  CHECK(st.evaluated == st.points);
  job.prune = false;
  REQUIRE(mesh::polygonize_implicit(job, dense, err));
  CHECK(same_bits(pruned, dense));
}

namespace {
struct Boundable {
  size_t total = 0, bounded = 0;
  std::vector<std::string> not_bounded;
};

// Whether the optimised kernel of a script is straight-line (the intervals bound it: full pruning).
void count_script(std::unique_ptr<frontend::SourceFile> file, const std::string& where, Boundable& b) {
  frontend::DiagnosticSink diag;
  frontend::Script script;
  if (!frontend::load_script(std::move(file), diag, script)) return;
  frontend::KernelSpec spec;
  std::string err;
  if (!frontend::default_spec(script.sema, spec, err)) return;
  auto m = driver::build_module(script, spec, diag, {}, err);
  if (!m) return;
  ++b.total;
  if (ir::interval_evaluable(m->kernel_function())) ++b.bounded;
  else b.not_bounded.push_back(where);
}

Boundable count_fs(const std::vector<std::string>& dirs) {
  Boundable b;
  for (const auto& dir : dirs) {
    if (!fsys::exists(dir)) continue;
    for (const auto& e : fsys::directory_iterator(dir)) {
      if (e.path().extension() != ".fs") continue;
      std::string text, err;
      REQUIRE(support::read_file(e.path().string(), text, err));
      count_script(std::make_unique<frontend::SourceFile>(e.path().string(), text), e.path().string(), b);
    }
  }
  return b;
}
}  // namespace

// docs/architecture.md quotes these counts: which functions pruning can bound in full.
TEST_CASE("prune: the functions of the benchmarks, examples and corpus that intervals bound") {
  if (!fsys::exists(FS_CORPUS_DIR)) {
    test::skip(test::SkipKind::Missing, "the shared corpus folder is absent: " FS_CORPUS_DIR);
    return;
  }
  Boundable bench = count_fs({FS_CORPUS_DIR "/../bench", FS_CORPUS_DIR "/../data", FS_SOURCE_DIR "/bench"});
  Boundable examples = count_fs({FS_SOURCE_DIR "/examples"});
  Boundable corpus;
  for (const std::string& dir : {std::string(FS_CORPUS_DIR), std::string(FS_SOURCE_DIR "/examples/paper")})
    for (const auto& e : fsys::recursive_directory_iterator(dir)) {
      if (e.path().extension() != ".wrl") continue;
      std::string text, err;
      REQUIRE(support::read_file(e.path().string(), text, err));
      frontend::DiagnosticSink vdiag;
      vrml::Scene scene;
      if (!vrml::parse_scene(std::make_unique<frontend::SourceFile>(e.path().string(), text), vdiag, scene)) continue;
      for (const auto& ss : vrml::scene_scripts(scene)) {
        if (ss.script.field == "operation") continue;
        count_script(
            std::make_unique<frontend::SourceFile>(e.path().string(), ss.script.text, ss.script.line, ss.script.col),
            e.path().filename().string() + ":" + std::to_string(ss.script.line) + " " + ss.script.field, corpus);
      }
    }
  auto list = [](const Boundable& b) {
    std::string s;
    for (const auto& w : b.not_bounded) s += "\n  " + w;
    return s;
  };
  WARN("bounded by intervals: bench " << bench.bounded << " of " << bench.total << list(bench) << "\nexamples "
                                      << examples.bounded << " of " << examples.total << list(examples)
                                      << "\ncorpus and paper scripts " << corpus.bounded << " of " << corpus.total
                                      << list(corpus));
  CHECK(bench.total >= 6);
  CHECK(bench.bounded * 2 >= bench.total);
  CHECK(corpus.bounded * 10 >= corpus.total * 9);
}
