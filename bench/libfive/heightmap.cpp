// libfive's Heightmap::render of ../shared/data/spheres400.fs (the tree min(d^2 - r^2) over its
// balls, which bench/libfive/heightmap.sh writes to balls.h) at 1024^3 over [-1, 1]^3, evaluators
// prebuilt: the peer of `fscript render3d spheres400.fs --size 1024`. Best of 7, one or N threads.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "libfive/eval/evaluator.hpp"
#include "libfive/render/discrete/heightmap.hpp"
#include "libfive/render/discrete/voxels.hpp"
#include "spheres400.h"

int main(int argc, char** argv) {
  unsigned threads = argc > 1 ? static_cast<unsigned>(std::atoi(argv[1])) : 1;
  libfive::Tree t = spheres400_tree();
  libfive::Voxels r({-1, -1, -1}, {1, 1, 1}, 512);  // 512 voxels a unit: 1024 across the box
  std::vector<libfive::Evaluator*> es;
  for (unsigned i = 0; i < threads; ++i) es.push_back(new libfive::Evaluator(t));
  std::atomic_bool abort(false);
  double best = 1e9;
  for (int k = 0; k < 7; ++k) {
    auto t0 = std::chrono::steady_clock::now();
    auto h = libfive::Heightmap::render(es, r, abort);
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, ms);
    if (k > 0) continue;
    size_t hit = 0;
    for (int i = 0; i < h->depth.rows(); ++i)
      for (int j = 0; j < h->depth.cols(); ++j) hit += h->depth(i, j) != -std::numeric_limits<float>::infinity();
    std::printf("%zu pixels on the shape\n", hit);
  }
  std::printf("%.1f ms\n", best);
}
