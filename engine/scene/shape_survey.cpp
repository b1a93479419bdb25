// The survey of shape_survey.h: regions halve from a power-of-two cube of bricks down to bricks of
// 8^3 samples; each region's children are bounded together on the parent's simplified tape.
#include "engine/scene/shape_survey.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace fscript::scene {
namespace {

constexpr int kBrick = 8;

class Surveyor {
 public:
  Surveyor(const SurveyGrid& g, const SurveyOptions& o, Survey& s) : g_(g), o_(o), s_(s) {}

  bool run(const mesh::Field& f, backends::RuntimeError& err) {
    int side = kBrick;
    while (side < std::max({g_.n[0], g_.n[1], g_.n[2]})) side *= 2;
    const int lo[3] = {0, 0, 0};
    math::Interval v = f.can_bound() ? f.bound(box_of(lo, side)) : math::Interval::everything();
    return region(lo, side, v, f, err);
  }

 private:
  // The box of the samples of region [lo, lo + side) clipped to the grid (what a bound must hold).
  mesh::Box3 box_of(const int lo[3], int side) const {
    mesh::Box3 b;
    for (int a = 0; a < 3; ++a) {
      int hi = std::min(lo[a] + side, g_.n[a]) - 1;
      b.lo[a] = std::min(g_.at(a, lo[a]), g_.at(a, hi)), b.hi[a] = std::max(g_.at(a, lo[a]), g_.at(a, hi));
    }
    return b;
  }

  bool done() const {
    return (o_.stop_at_inside && s_.inside > 0) || (o_.stop_when_mixed && s_.inside > 0 && s_.inside < s_.points) ||
        !s_.complete;
  }

  bool region(const int lo[3], int side, const math::Interval& v, const mesh::Field& f, backends::RuntimeError& err) {
    int hi[3];
    for (int a = 0; a < 3; ++a) hi[a] = std::min(lo[a] + side, g_.n[a]);
    if (hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2] || done()) return true;
    if (!v.nan && v.lo > 0) return whole(lo, hi, true), true;
    if (!v.nan && v.hi <= 0) return whole(lo, hi, false), true;
    if (v.empty()) return whole_nan(lo, hi), true;
    if (side <= kBrick) return sample(lo, hi, f, err);
    const int half = side / 2;
    mesh::Box3 boxes[8];
    int corner[8][3];
    size_t n = 0;
    for (int q = 0; q < 8; ++q) {
      int c[3] = {lo[0] + (q & 1) * half, lo[1] + (q >> 1 & 1) * half, lo[2] + (q >> 2 & 1) * half};
      if (c[0] >= g_.n[0] || c[1] >= g_.n[1] || c[2] >= g_.n[2]) continue;
      std::copy(c, c + 3, corner[n]);
      boxes[n++] = box_of(c, half);
    }
    math::Interval bounds[8];
    std::shared_ptr<const mesh::Field> locals[8];
    if (f.can_bound()) {
      f.bounds_and_locals(
          boxes, n, bounds, [](size_t, const math::Interval& b) { return b.nan || (b.lo <= 0 && b.hi > 0); }, locals);
    } else {
      std::fill(bounds, bounds + n, math::Interval::everything());
    }
    for (size_t q = 0; q < n; ++q)
      if (!region(corner[q], half, bounds[q], locals[q] ? *locals[q] : f, err)) return false;
    return true;
  }

  // A region the bound decides: every sample inside, or every one outside (f <= 0).
  void whole(const int lo[3], const int hi[3], bool inside) {
    uint64_t d[3] = {uint64_t(hi[0] - lo[0]), uint64_t(hi[1] - lo[1]), uint64_t(hi[2] - lo[2])};
    uint64_t count = d[0] * d[1] * d[2];
    s_.points += count;
    for (int a = 0; a < 3; ++a) {
      uint64_t layer = count / d[a];
      if (lo[a] == 0) s_.face_points[2 * a] += layer, s_.face_inside[2 * a] += inside ? layer : 0;
      if (hi[a] == g_.n[a]) s_.face_points[2 * a + 1] += layer, s_.face_inside[2 * a + 1] += inside ? layer : 0;
    }
    if (!inside) return;
    s_.inside += count;
    for (int a = 0; a < 3; ++a) grow(a, lo[a], hi[a] - 1);
  }

  // A region where the function is NaN at every point (its bound holds only NaN).
  void whole_nan(const int lo[3], const int hi[3]) {
    whole(lo, hi, false);
    s_.nan += uint64_t(hi[0] - lo[0]) * uint64_t(hi[1] - lo[1]) * uint64_t(hi[2] - lo[2]);
    if (s_.has_nan_point) return;
    s_.has_nan_point = true;
    for (int a = 0; a < 3; ++a) s_.nan_point[a] = g_.at(a, (lo[a] + hi[a] - 1) / 2);
  }

  void grow(int a, int i0, int i1) {
    double h = g_.step(a);
    s_.extent[2 * a] = std::min(s_.extent[2 * a], g_.at(a, i0) - h / 2);
    s_.extent[2 * a + 1] = std::max(s_.extent[2 * a + 1], g_.at(a, i1) + h / 2);
  }

  bool sample(const int lo[3], const int hi[3], const mesh::Field& f, backends::RuntimeError& err) {
    xs_.clear(), ys_.clear(), zs_.clear();
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i)
          xs_.push_back(g_.at(0, i)), ys_.push_back(g_.at(1, j)), zs_.push_back(g_.at(2, k));
    if (sampled_ + xs_.size() > o_.budget) return s_.complete = false, true;
    sampled_ += xs_.size();
    s_.open.push_back({lo[0], lo[1], lo[2]});
    vals_.resize(xs_.size());
    if (!f.eval(xs_.data(), ys_.data(), zs_.data(), xs_.size(), vals_.data(), err)) return false;
    size_t p = 0;
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i, ++p) point(i, j, k, vals_[p]);
    return true;
  }

  void point(int i, int j, int k, float v) {
    const int at[3] = {i, j, k};
    const bool inside = v > 0, nan = std::isnan(v);
    ++s_.points;
    for (int a = 0; a < 3; ++a) {
      if (at[a] == 0) ++s_.face_points[2 * a], s_.face_inside[2 * a] += inside;
      if (at[a] == g_.n[a] - 1) ++s_.face_points[2 * a + 1], s_.face_inside[2 * a + 1] += inside;
    }
    if (nan && !s_.has_nan_point) {
      s_.has_nan_point = true;
      for (int a = 0; a < 3; ++a) s_.nan_point[a] = g_.at(a, at[a]);
    }
    s_.nan += nan;
    if (!inside) return;
    ++s_.inside;
    for (int a = 0; a < 3; ++a) grow(a, at[a], at[a]);
  }

  const SurveyGrid& g_;
  const SurveyOptions& o_;
  Survey& s_;
  uint64_t sampled_ = 0;
  std::vector<float> xs_, ys_, zs_, vals_;
};

}  // namespace

bool survey(const mesh::Field& f, const SurveyGrid& g, const SurveyOptions& o, Survey& out,
            backends::RuntimeError& err) {
  out = Survey{};
  if (g.n[0] <= 0 || g.n[1] <= 0 || g.n[2] <= 0) return true;
  return Surveyor(g, o, out).run(f, err);
}

}  // namespace fscript::scene
