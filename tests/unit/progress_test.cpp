// The run's progress counters (runtime/support/progress.h): jobs and their shares add up, the text
// the terminal line shows, many threads advancing one job, and both meshers reporting all their work.
#include <catch2/catch.hpp>
#include <thread>
#include <vector>

#include "engine/mesh/marching_tetrahedra.h"
#include "runtime/support/progress.h"
#include "tests/unit/helpers.h"

using namespace fscript;

TEST_CASE("progress: finished jobs and the shares of running ones make the fraction") {
  support::progress_reset();
  support::progress_expect(4, "frames");
  {
    support::ProgressJob a;
    a.set_units(10);
    a.advance(5);
    CHECK(support::progress_state().fraction == Approx(0.5 / 4));
    { support::ProgressJob b; }  // one job, done without units
    support::ProgressState s = support::progress_state();
    CHECK(s.jobs == 4);
    CHECK(s.done == 1);
    CHECK(s.fraction == Approx(1.5 / 4));
    CHECK(support::progress_text(s, 3.0) == "1/4 frames, 37%, about 5 s left");
    a.advance(100);  // past its units: the job counts whole, not more
    CHECK(support::progress_state().fraction == Approx(2.0 / 4));
  }
  support::ProgressState s = support::progress_state();
  CHECK(s.done == 2);
  CHECK(s.fraction == Approx(2.0 / 4));
  CHECK(support::progress_text(s, 100.0) == "2/4 frames, 50%, about 2 min left");
  CHECK(support::progress_text({4, 0, 0.01, "shapes"}, 1.0) == "0/4 shapes, 1%");  // too early to guess
  CHECK(support::progress_text({4, 3, 0.9, "shapes"}, 1.0) == "3/4 shapes, 90%, under a second left");
  // More jobs than announced: the total follows what started.
  support::progress_reset();
  support::progress_expect(1, "meshes");
  support::ProgressJob x, y;
  CHECK(support::progress_state().jobs == 2);
}

TEST_CASE("progress: threads advancing one job add up to the whole job") {
  support::progress_reset();
  support::progress_expect(1, "meshes");
  {
    support::ProgressJob job;
    job.set_units(8000);
    std::vector<std::thread> pool;
    for (int t = 0; t < 8; ++t)
      pool.emplace_back([&] {
        for (int i = 0; i < 1000; ++i) job.advance(1);
      });
    for (auto& t : pool) t.join();
    CHECK(support::progress_state().fraction == Approx(1.0));
    CHECK(support::progress_state().done == 0);
  }
  CHECK(support::progress_state().done == 1);
  CHECK(support::progress_state().fraction == Approx(1.0));
}

TEST_CASE("progress: both meshers report every part of the grid done") {
  auto b = test::build("function FRep(x,y,z,t){ return 0.6*0.6 - x*x - y*y - z*z; }");
  REQUIRE(b->ok);
  mesh::KernelField field(*b->kernel, 0);
  for (mesh::Mesher kind : {mesh::Mesher::DualContouring, mesh::Mesher::MarchingTetrahedra})
    for (int threads : {1, 3}) {
      support::progress_reset();
      support::progress_expect(1, "meshes");
      support::ProgressJob job;
      mesh::ImplicitJob j;
      j.field = &field;
      j.box = {-1, 1, -1, 1, -1, 1};
      j.cells = {40, 40, 40};
      j.threads = threads;
      j.mesher.kind = kind;
      j.progress = &job;
      mesh::Mesh m;
      backends::RuntimeError err;
      REQUIRE(mesh::polygonize(j, m, err));
      INFO("mesher " << int(kind) << ", threads " << threads);
      CHECK(support::progress_state().fraction == Approx(1.0));
    }
}
