#pragma once
// Pictures of implicit shapes without meshing: for each sample of the picture, the first point
// along its ray where f >= 0 inside the shape's box, found by interval descent over screen tiles x
// depth ranges in front-to-back order on tapes simplified per region (the quadtree's machinery in
// 3D); then refined along the ray to float precision and given the gradient's normal (central
// differences on the region's tape).
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/field.h"
#include "runtime/support/progress.h"

namespace fscript::render {

// The rays of a picture in the field's own coordinates. Sample (col, row) looks along
// origin(col, row) + d * dir(col, row), both affine in (col, row) (an orthographic or a perspective
// camera, moved into the shape's frame by an affine map), and is probed at `steps` depths d evenly
// spaced from near to far. Every point is computed by point(), in double and then rounded, so a
// point has the same bits whichever path asks for it.
struct RayGrid {
  uint32_t w = 1, h = 1, steps = 2;
  std::array<double, 3> origin{}, origin_col{}, origin_row{};  // the ray of sample (0, 0), and per column, row
  std::array<double, 3> dir{}, dir_col{}, dir_row{};
  double near = 0, far = 1;
  mesh::Box3 box{};  // the shape's box: points outside it are outside (a solid it cuts is closed by it)

  double depth(uint32_t k) const {
    return steps > 1 ? near + (far - near) * static_cast<double>(k) / static_cast<double>(steps - 1) : near;
  }
  // Origin and direction of (col, row).
  void ray(uint32_t col, uint32_t row, double o[3], double v[3]) const {
    const double c = col, r = row;
    for (int a = 0; a < 3; ++a) {
      o[a] = origin[a] + c * origin_col[a] + r * origin_row[a];
      v[a] = dir[a] + c * dir_col[a] + r * dir_row[a];
    }
  }
  static void at(const double o[3], const double v[3], double d, double p[3]) {
    for (int a = 0; a < 3; ++a) p[a] = o[a] + d * v[a];
  }
  void point(uint32_t col, uint32_t row, double d, double p[3]) const {
    double o[3], v[3];
    ray(col, row, o, v);
    at(o, v, d, p);
  }
  void point(uint32_t col, uint32_t row, double d, float p[3]) const {  // rounded to float
    double q[3];
    point(col, row, d, q);
    for (int a = 0; a < 3; ++a) p[a] = static_cast<float>(q[a]);
  }
  bool in_box(const float p[3]) const {
    for (int a = 0; a < 3; ++a)
      if (!(p[a] >= box.lo[a] && p[a] <= box.hi[a])) return false;
    return true;
  }
  void clamp_to_box(float p[3]) const {
    for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], box.lo[a], box.hi[a]);
  }
  // Where the ray of (col, row) enters the box, and through which face (axis * 2 + 1 for the high
  // side); false when it misses.
  bool entry(uint32_t col, uint32_t row, double& d, int& face) const;
};

// An orthographic picture of `box` (x0, x1, y0, y1, z0, z1) seen from azimuth `az` (degrees about
// +y, from +z toward +x) and elevation `el` (degrees above the horizon): at 0, 0 columns run along
// +x over [x0, x1], rows down from y1 to y0, and the rays go down z, the box filling the picture.
RayGrid orthographic(const std::array<double, 6>& box, uint32_t w, uint32_t h, uint32_t steps, double az, double el);

// n x n rays along `dir` across `box` (both in the field's coordinates), probed in n steps: how a
// picture's automatic camera finds a shape's outline before it knows where it stands.
RayGrid parallel(const std::array<double, 6>& box, const std::array<double, 3>& dir, uint32_t n);

// What a picture's rays met, per sample (row-major from the top row).
struct Hits {
  std::vector<float> depth;                    // the ray's d at its first surface point; +inf: none
  std::vector<std::array<float, 3>> point;     // that point, in the field's coordinates (empty unless asked for)
  std::vector<std::array<float, 3>> normal;    // outward and unit, in the field's coordinates
  std::vector<int32_t> step;                   // the first step found inside; -1: none
};

struct DirectLevel {
  uint32_t tile = 0, steps = 0;  // a region's side in samples and its depth in steps
  size_t empty = 0, full = 0, ambiguous = 0;
};

struct DirectStats {
  bool pruned = false;  // false: every step of every ray on the whole function
  std::vector<DirectLevel> levels;
  size_t points = 0;     // step points evaluated
  size_t refines = 0;    // points evaluated refining hits along their rays
  size_t gradients = 0;  // normals from the function's slope (the rest from the box's faces, or facing the ray)
  size_t hits = 0;
  size_t constant = 0;  // regions whose tape the rays cross without changing it: probed once a ray
};

struct DirectOptions {
  unsigned threads = 1;
  bool prune = true;
  support::ProgressJob* progress = nullptr;  // told as top-level tiles are done
  const std::vector<char>* wanted = nullptr;  // when given, only the samples marked here are traced
  bool points = true;  // fill Hits::point (12 bytes a sample: a picture that only shades goes without)
};

// Where in `box` a shape is, by interval subdivision down to cells of 1/64 of the box a side: the
// cells the intervals prove inside, and the open ones with a corner or the centre inside (the
// framing of a picture, so a thin part may fall outside by up to a cell). `open`: the share of the
// box's cells the intervals leave open, which says how well they bound the function (a blend's
// bounds are loose everywhere, and a direct picture would probe every step of most rays).
struct Occupancy {
  std::optional<std::array<double, 6>> extent;  // none: nothing shows
  std::vector<std::array<float, 3>> outline;    // the kept cells' corners: what a camera frames
  double open = 0;
};
bool occupied(const mesh::Field& f, const std::array<double, 6>& box, Occupancy& out, backends::RuntimeError& err);

// The same hits, bit for bit, pruned or dense, for any thread count: the intervals only skip steps
// no point of which is inside, and a region's tape gives the whole function's bits inside it.
bool trace(const mesh::Field& f, const RayGrid& g, const DirectOptions& o, Hits& out, DirectStats& stats,
           backends::RuntimeError& err);

}  // namespace fscript::render
