#pragma once
// Quadric error functions for dual contouring: the planes through a cell's surface crossings
// (Hermite data: point and normal), accumulated, summed when cells merge, and minimised robustly
// inside the cell. Eigen stays in qef.cpp.
#include <cmath>
#include <cstddef>

namespace fscript::mesh {

// The sums a QEF keeps: A^T A (xx xy xz yy yz zz), A^T b, b^T b and the sum of the points, and a
// pad so the sums add in pairs.
enum QefTerm { kXX, kXY, kXZ, kYY, kYZ, kZZ, kBX, kBY, kBZ, kBB, kMX, kMY, kMZ, kQefTerms = 14 };

// A tangent plane ready to add (unit normal u, offset d = u.p, the point p on it), as its terms:
// made once per crossing and added to up to four cells, so the products are not made four times.
struct Plane {
  double w[kQefTerms] = {};
  bool valid = false;  // false when the normal was zero or not finite (the plane adds nothing)
};

class Qef {
 public:
  Qef() = default;
  // The QEF of one plane: a cell's first crossing (zeroing 120 bytes, then adding, cost more).
  explicit Qef(const Plane& q) {
    if (!q.valid) return;
    for (int k = 0; k < kQefTerms; ++k) s_[k] = q.w[k];
    count_ = 1;
  }
  // The plane through p with normal n (any length but zero: normalised here).
  // Inline, like add and merge: they run per crossing and per cell, and as calls they were more
  // of the meshing than their arithmetic.
  static Plane plane(const double p[3], const double n[3]) {
    Plane q;
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0) || !std::isfinite(len)) return q;
    double u[3];
    for (int a = 0; a < 3; ++a) u[a] = n[a] / len;
    double d = u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
    double* w = q.w;
    w[kXX] = u[0] * u[0], w[kXY] = u[0] * u[1], w[kXZ] = u[0] * u[2];
    w[kYY] = u[1] * u[1], w[kYZ] = u[1] * u[2], w[kZZ] = u[2] * u[2];
    for (int a = 0; a < 3; ++a) w[kBX + a] = u[a] * d, w[kMX + a] = p[a];
    w[kBB] = d * d;
    q.valid = true;
    return q;
  }
  void add(const Plane& q) {
    if (!q.valid) return;
    for (int k = 0; k < kQefTerms; ++k) s_[k] += q.w[k];
    ++count_;
  }
  void add(const double p[3], const double n[3]) { add(plane(p, n)); }
  // The planes of both (a merged cell's QEF is the sum of its children's).
  void merge(const Qef& o) {
    for (int k = 0; k < kQefTerms; ++k) s_[k] += o.s_[k];
    count_ += o.count_;
  }
  size_t count() const { return count_; }
  // The sum of squared distances from x to the planes.
  double error(const double x[3]) const;

  struct Solution {
    double x[3] = {0, 0, 0};
    double error = 0;
    int rank = 0;  // eigen-directions used: 3 a corner, 2 an edge, 1 a face, 0 the mass point
  };
  // The point of least error inside the box [lo, hi]: the minimiser around the mass point (the
  // average crossing) with eigenvalues under kCutoff times the largest dropped, so near-parallel
  // planes do not throw the vertex away; when that leaves the box, the best of fewer directions
  // that stays in it (down to the mass point itself, clamped into the box).
  Solution solve(const double lo[3], const double hi[3]) const;

  static constexpr double kCutoff = 0.1;

 private:
  double s_[kQefTerms] = {};  // QefTerm
  size_t count_ = 0;
};

}  // namespace fscript::mesh
