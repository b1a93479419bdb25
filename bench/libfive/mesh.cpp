// libfive's Mesh::render of ../shared/data/spheres400.fs (the tree min(d^2 - r^2) over its balls,
// which bench/libfive/mesh.sh writes to balls.h) over [-1, 1]^3 with cells of 2/256 (min_feature
// 0.01: the octree stops at 256 cells across), its dual contouring with default cell merging:
// the peer of `fvrml-run` meshing the same model at resolution 256. Best of 3, one or N threads,
// evaluators built inside each render as a caller's would be.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "libfive/render/brep/mesh.hpp"
#include "libfive/render/brep/region.hpp"
#include "libfive/render/brep/settings.hpp"
#include "spheres400.h"

int main(int argc, char** argv) {
  unsigned threads = argc > 1 ? static_cast<unsigned>(std::atoi(argv[1])) : 1;
  libfive::Tree t = spheres400_tree();
  libfive::Region<3> r({-1, -1, -1}, {1, 1, 1});
  libfive::BRepSettings s;
  s.min_feature = 0.01;
  s.workers = threads;
  s.alg = libfive::DUAL_CONTOURING;
  double best = 1e9;
  for (int k = 0; k < 3; ++k) {
    auto t0 = std::chrono::steady_clock::now();
    auto m = libfive::Mesh::render(t, r, s);
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, ms);
    if (k == 0) std::printf("%zu triangles\n", m->branes.size());
  }
  std::printf("%.0f ms\n", best);
}
