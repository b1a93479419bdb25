#pragma once
// A survey of a field over a grid of cell-centred samples (the meshers' grid): an octree of
// interval bounds decides regions whole, and only bricks the bounds leave open (or that may hold
// NaN) are sampled. What shape diagnostics read: signs, NaN, the faces' layers, the extent.
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/field.h"

namespace fscript::scene {

// Samples at box[2a] + (i + 0.5) * (box[2a + 1] - box[2a]) / n[a], as the meshers take them.
struct SurveyGrid {
  std::array<double, 6> box{};
  std::array<int, 3> n{};
  double step(int a) const { return (box[2 * a + 1] - box[2 * a]) / n[a]; }
  float at(int a, int i) const { return static_cast<float>(box[2 * a] + (i + 0.5) * step(a)); }
  uint64_t points() const { return uint64_t(n[0]) * uint64_t(n[1]) * uint64_t(n[2]); }
};

struct Survey {
  uint64_t points = 0, inside = 0, nan = 0;  // inside: f > 0, as the meshers draw
  uint64_t face_points[6] = {}, face_inside[6] = {};  // the outer layer of samples: -x +x -y +y -z +z
  // The cells around the inside samples and regions: x0 x1 y0 y1 z0 z1 (lo > hi: none).
  double extent[6] = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  bool has_nan_point = false;
  float nan_point[3] = {0, 0, 0};  // a sample where f is NaN
  std::vector<std::array<int, 3>> open;  // the first grid point of each brick that was sampled
  bool complete = true;                  // false: the sample budget ran out
};

struct SurveyOptions {
  uint64_t budget = 4'000'000;  // the most points sampled; past it the survey stops, incomplete
  bool stop_at_inside = false;  // stop at the first inside sample (all an emptiness check needs)
  // Stop once some samples are inside and some not: neither empty nor full (all an animation's
  // frames are checked for).
  bool stop_when_mixed = false;
};

// Surveys `f` over `g`; false on a runtime error of the function.
bool survey(const mesh::Field& f, const SurveyGrid& g, const SurveyOptions& o, Survey& out,
            backends::RuntimeError& err);

}  // namespace fscript::scene
