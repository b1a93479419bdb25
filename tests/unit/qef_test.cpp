// Quadric error functions (dual contouring's vertex placement): corners, edges and faces found
// exactly, off the grid axes too; near-parallel planes and corners outside the cell kept in it.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "engine/mesh/qef.h"

using fscript::mesh::Qef;

namespace {

const double kLo[3] = {0, 0, 0}, kHi[3] = {1, 1, 1};

// Points on the plane through `at` with normal n, spread inside the unit cell.
void add_plane(Qef& q, const double at[3], const double n[3], std::mt19937& rng, int points = 4) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (int k = 0; k < points; ++k) {
    double p[3] = {at[0] + u(rng), at[1] + u(rng), at[2] + u(rng)};
    double d = ((p[0] - at[0]) * n[0] + (p[1] - at[1]) * n[1] + (p[2] - at[2]) * n[2]) /
        (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; ++a) p[a] -= d * n[a];  // onto the plane
    q.add(p, n);
  }
}

double distance(const double a[3], const double b[3]) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Rotates v by the rotation about (1, 2, 3) through 0.7 radians (Rodrigues).
void rotate(const double v[3], double out[3]) {
  double k[3] = {1, 2, 3}, len = std::sqrt(14.0), c = std::cos(0.7), s = std::sin(0.7);
  for (double& x : k) x /= len;
  double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  double cross[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
  for (int a = 0; a < 3; ++a) out[a] = v[a] * c + cross[a] * s + k[a] * kv * (1 - c);
}

}  // namespace

TEST_CASE("qef: a corner, an edge and a face of axis planes") {
  std::mt19937 rng(1);
  const double corner[3] = {0.3, 0.4, 0.5};
  const double nx[3] = {1, 0, 0}, ny[3] = {0, 1, 0}, nz[3] = {0, 0, 1};
  Qef q3, q2, q1;
  add_plane(q3, corner, nx, rng), add_plane(q3, corner, ny, rng), add_plane(q3, corner, nz, rng);
  add_plane(q2, corner, nx, rng), add_plane(q2, corner, ny, rng);
  add_plane(q1, corner, nz, rng);
  Qef::Solution s3 = q3.solve(kLo, kHi), s2 = q2.solve(kLo, kHi), s1 = q1.solve(kLo, kHi);
  CHECK(s3.rank == 3);
  CHECK(distance(s3.x, corner) < 1e-9);
  CHECK(s3.error < 1e-12);
  CHECK(s2.rank == 2);  // on the edge x = 0.3, y = 0.4, at the crossings' mean height
  CHECK(std::abs(s2.x[0] - 0.3) < 1e-9);
  CHECK(std::abs(s2.x[1] - 0.4) < 1e-9);
  CHECK(s1.rank == 1);
  CHECK(std::abs(s1.x[2] - 0.5) < 1e-9);
}

TEST_CASE("qef: a corner off the grid axes is found exactly") {
  std::mt19937 rng(2);
  const double corner[3] = {0.55, 0.45, 0.5};
  Qef q;
  const double axes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& axis : axes) {
    double n[3];
    rotate(axis, n);
    add_plane(q, corner, n, rng, 3);
  }
  Qef::Solution s = q.solve(kLo, kHi);
  CHECK(s.rank == 3);
  CHECK(distance(s.x, corner) < 1e-9);
}

TEST_CASE("qef: near-parallel planes and far corners keep the vertex in its cell") {
  std::mt19937 rng(3);
  // Two planes 0.5 degrees apart: their line is far away; the small eigenvalue is dropped and the
  // vertex stays between them, near the crossings.
  Qef q;
  const double at[3] = {0.5, 0.5, 0.5};
  const double a[3] = {1, 0.0044, 0}, b[3] = {1, -0.0044, 0};
  add_plane(q, at, a, rng), add_plane(q, at, b, rng);
  Qef::Solution s = q.solve(kLo, kHi);
  CHECK(s.rank == 1);
  CHECK(std::abs(s.x[0] - 0.5) < 0.01);
  for (int k = 0; k < 3; ++k) CHECK((s.x[k] >= 0 && s.x[k] <= 1));
  // A corner outside the cell: the planes' crossings are inside, their meeting point is not.
  Qef far;
  const double outside[3] = {1.6, 0.5, 0.5};
  const double n1[3] = {1, 1, 0}, n2[3] = {1, -1, 0}, n3[3] = {0, 0, 1};
  double p[3];
  for (const double* n : {n1, n2}) {
    for (double t : {0.1, 0.3, 0.5}) {  // points of the plane near x = 0.9
      double along[3] = {-n[1], n[0], 0};
      for (int k = 0; k < 3; ++k) p[k] = outside[k] + along[k] * (1.0 + t) * (n == n1 ? 1 : -1);
      p[2] = 0.2 + t;
      far.add(p, n);
    }
  }
  add_plane(far, outside, n3, rng);
  Qef::Solution f = far.solve(kLo, kHi);
  CHECK(f.rank < 3);
  for (int k = 0; k < 3; ++k) CHECK((f.x[k] >= 0 && f.x[k] <= 1));
}

TEST_CASE("qef: merging sums the planes; error is the sum of squared distances") {
  std::mt19937 rng(4);
  const double at[3] = {0.2, 0.7, 0.4};
  const double n1[3] = {1, 2, 0}, n2[3] = {0, 1, -1};
  Qef a, b, all;
  std::mt19937 rng2 = rng;
  add_plane(a, at, n1, rng), add_plane(b, at, n2, rng);
  add_plane(all, at, n1, rng2), add_plane(all, at, n2, rng2);
  a.merge(b);
  CHECK(a.count() == all.count());
  const double x[3] = {0.9, 0.1, 0.3};
  CHECK(std::abs(a.error(x) - all.error(x)) < 1e-12);
  // Every plane passes through `at`: the error at x is count * (distance to each plane)^2 summed.
  double d1 = ((x[0] - at[0]) * 1 + (x[1] - at[1]) * 2) / std::sqrt(5.0);
  double d2 = ((x[1] - at[1]) - (x[2] - at[2])) / std::sqrt(2.0);
  CHECK(std::abs(a.error(x) - 4 * (d1 * d1 + d2 * d2)) < 1e-9);
  Qef empty;
  Qef::Solution e = empty.solve(kLo, kHi);
  CHECK(e.x[0] == 0.5);
  CHECK(e.rank == 0);
}
