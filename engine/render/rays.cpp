// Ray grids of pictures (their points, the box they cross, the orthographic and parallel grids)
// and where in its box a shape is: what the direct renderer and its callers set it up with.
#include "engine/render/direct.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace fscript::render {

bool RayGrid::entry(uint32_t col, uint32_t row, double& d, int& face) const {
  double o[3], v[3];
  ray(col, row, o, v);
  double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
  face = 0;
  for (int a = 0; a < 3; ++a) {
    if (v[a] == 0) {
      if (o[a] < box.lo[a] || o[a] > box.hi[a]) return false;
      continue;
    }
    double t0 = (box.lo[a] - o[a]) / v[a], t1 = (box.hi[a] - o[a]) / v[a];
    bool high = t1 < t0;  // going down the axis: in through the high face
    if (high) std::swap(t0, t1);
    if (t0 > enter) enter = t0, face = a * 2 + (high ? 1 : 0);
    leave = std::min(leave, t1);
  }
  d = enter;
  return enter <= leave;
}

namespace {

using V3 = std::array<double, 3>;
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 unit(V3 a) {
  double l = std::sqrt(dot(a, a));
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : a;
}

}  // namespace

namespace {

// The picture of `box` seen down -back, right along its columns and up its rows, the box filling it.
RayGrid along(const std::array<double, 6>& box, uint32_t w, uint32_t h, uint32_t steps, V3 back, V3 right, V3 up) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};  // along right, up, back
  for (int k = 0; k < 8; ++k) {
    V3 q = {box[k & 1], box[2 + ((k >> 1) & 1)], box[4 + ((k >> 2) & 1)]};
    double c[3] = {dot(q, right), dot(q, up), dot(q, back)};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  double s = std::max((hi[0] - lo[0]) / w, (hi[1] - lo[1]) / h);  // one sample's side
  if (!(s > 0)) s = 1.0 / std::max(w, h);
  double mid_r = (lo[0] + hi[0]) / 2, mid_u = (lo[1] + hi[1]) / 2;
  RayGrid g;
  g.w = w, g.h = h, g.steps = std::max(2u, steps);
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = right[a] * (mid_r + (0.5 - w / 2.0) * s) + up[a] * (mid_u - (0.5 - h / 2.0) * s) + back[a] * hi[2];
    g.origin_col[a] = right[a] * s, g.origin_row[a] = -up[a] * s;
    g.dir[a] = -back[a];
  }
  g.near = 0, g.far = hi[2] - lo[2];
  for (int a = 0; a < 3; ++a)
    g.box.lo[a] = static_cast<float>(box[2 * a]), g.box.hi[a] = static_cast<float>(box[2 * a + 1]);
  return g;
}

}  // namespace

RayGrid orthographic(const std::array<double, 6>& box, uint32_t w, uint32_t h, uint32_t steps, double az, double el) {
  el = std::clamp(el, -90.0, 90.0);
  // Whole quarter turns exactly (cos 90 degrees is 6e-17 in double): a view down an axis keeps its
  // rays off the other two, which is what lets a shape extruded along it be probed once a ray.
  auto cos_deg = [](double a) {
    double q = std::remainder(a, 360.0);
    return q == 0             ? 1.0
        : std::fabs(q) == 180 ? -1.0
        : std::fabs(q) == 90  ? 0.0
                              : std::cos(q * 3.14159265358979323846 / 180);
  };
  auto sin_deg = [&](double a) { return cos_deg(a - 90); };
  V3 back = {cos_deg(el) * sin_deg(az), sin_deg(el), cos_deg(el) * cos_deg(az)};
  // Straight up or down, "up" in the picture is -z (as if the camera had tipped over from the front).
  V3 right = std::fabs(cos_deg(el)) < 1e-12 ? V3{cos_deg(az), 0, -sin_deg(az)} : unit(cross({0, 1, 0}, back));
  V3 up = cross(back, right);
  return along(box, w, h, steps, back, right, up);
}

RayGrid parallel(const std::array<double, 6>& box, const std::array<double, 3>& dir, uint32_t n) {
  V3 back = unit({-dir[0], -dir[1], -dir[2]});
  V3 other = std::fabs(back[1]) < 0.9 ? V3{0, 1, 0} : V3{1, 0, 0};
  V3 right = unit(cross(other, back));
  return along(box, n, n, n, back, right, cross(back, right));
}

namespace {

constexpr int kDeepest = 6;  // occupied()'s cells: 1/64 of the box a side

// occupied() below a box whose bound is open: its eight children on the box's own tape. The open
// cells of the last level are kept where one of their corners or their centre is inside, or their
// signs differ (the surface crosses); `open` counts them all.
bool occupy(const mesh::Field& f, const mesh::Box3& b, int level, std::vector<mesh::Box3>& kept, size_t& open,
            backends::RuntimeError& err) {
  mesh::Box3 kids[8];
  for (int k = 0; k < 8; ++k)
    for (int a = 0; a < 3; ++a) {
      float mid = 0.5f * (b.lo[a] + b.hi[a]);
      bool high = (k >> a) & 1;
      kids[k].lo[a] = high ? mid : b.lo[a], kids[k].hi[a] = high ? b.hi[a] : mid;
    }
  math::Interval iv[8];
  std::shared_ptr<const mesh::Field> locals[8];
  auto decided = [&](const math::Interval& v) { return v.empty() || v.hi < 0 || (!v.nan && v.lo >= 0); };
  const bool last = level + 1 == kDeepest;
  f.bounds_and_locals(kids, 8, iv, [&](size_t, const math::Interval& v) { return !last && !decided(v); }, locals);
  float x[72], y[72], z[72], v[72];
  size_t n = 0;
  int cells[8], count = 0;
  for (int k = 0; k < 8; ++k) {
    if (iv[k].empty() || iv[k].hi < 0) continue;  // nothing inside (NaN is outside)
    if (decided(iv[k])) {
      kept.push_back(kids[k]);
    } else if (!last) {
      if (!occupy(locals[k] ? *locals[k] : f, kids[k], level + 1, kept, open, err)) return false;
    } else {
      ++open;
      cells[count++] = k;
      for (int c = 0; c < 9; ++c, ++n) {
        const mesh::Box3& q = kids[k];
        x[n] = c == 8 ? 0.5f * (q.lo[0] + q.hi[0]) : (c & 1 ? q.hi[0] : q.lo[0]);
        y[n] = c == 8 ? 0.5f * (q.lo[1] + q.hi[1]) : (c & 2 ? q.hi[1] : q.lo[1]);
        z[n] = c == 8 ? 0.5f * (q.lo[2] + q.hi[2]) : (c & 4 ? q.hi[2] : q.lo[2]);
      }
    }
  }
  if (n == 0) return true;
  if (!f.eval(x, y, z, n, v, err)) return false;
  for (int j = 0; j < count; ++j) {
    int in = 0;
    for (int c = 0; c < 9; ++c) in += v[9 * j + c] >= 0;
    if (in > 0) kept.push_back(kids[cells[j]]);
  }
  return true;
}

}  // namespace

bool occupied(const mesh::Field& f, const std::array<double, 6>& box, Occupancy& out, backends::RuntimeError& err) {
  out = {};
  if (!f.can_bound()) {
    out.extent = box, out.open = 1;
    return true;  // no outline: whoever draws it meshes it
  }
  mesh::Box3 whole;
  for (int a = 0; a < 3; ++a)
    whole.lo[a] = static_cast<float>(box[2 * a]), whole.hi[a] = static_cast<float>(box[2 * a + 1]);
  math::Interval v;
  f.bounds(&whole, 1, &v);
  if (v.empty() || v.hi < 0) return true;
  if (!v.nan && v.lo >= 0) {
    out.extent = box;
    for (int k = 0; k < 8; ++k)
      out.outline.push_back(
          {k & 1 ? whole.hi[0] : whole.lo[0], k & 2 ? whole.hi[1] : whole.lo[1], k & 4 ? whole.hi[2] : whole.lo[2]});
    return true;
  }
  std::vector<mesh::Box3> kept;
  size_t open = 0;
  if (!occupy(f, whole, 0, kept, open, err)) return false;
  out.open = static_cast<double>(open) / std::pow(8.0, kDeepest);
  if (kept.empty()) return true;
  std::array<double, 6> e{HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
  for (const auto& b : kept) {
    for (int a = 0; a < 3; ++a)
      e[2 * a] = std::min<double>(e[2 * a], b.lo[a]), e[2 * a + 1] = std::max<double>(e[2 * a + 1], b.hi[a]);
    for (int k = 0; k < 8; ++k)
      out.outline.push_back({k & 1 ? b.hi[0] : b.lo[0], k & 2 ? b.hi[1] : b.lo[1], k & 4 ? b.hi[2] : b.lo[2]});
  }
  out.extent = e;
  return true;
}

}  // namespace fscript::render
