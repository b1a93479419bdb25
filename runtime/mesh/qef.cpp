// Qef: accumulation in double, minimisation by a symmetric eigen-decomposition (Eigen) with small
// eigenvalues dropped relative to the largest, and rank reduction until the vertex is in its cell.
#include "runtime/mesh/qef.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fscript::mesh {

Plane Qef::plane(const double p[3], const double n[3]) {
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

void Qef::add(const Plane& q) {
  if (!q.valid) return;
  for (int k = 0; k < kQefTerms; ++k) s_[k] += q.w[k];
  ++count_;
}

void Qef::merge(const Qef& o) {
  for (int k = 0; k < kQefTerms; ++k) s_[k] += o.s_[k];
  count_ += o.count_;
}

namespace {

// The symmetric matrix of the first six terms.
Eigen::Matrix3d matrix(const double m[6]) {
  Eigen::Matrix3d a;
  a << m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5];
  return a;
}

}  // namespace

double Qef::error(const double x[3]) const {
  Eigen::Vector3d v(x[0], x[1], x[2]), atb(s_[kBX], s_[kBY], s_[kBZ]);
  return std::max(0.0, v.dot(matrix(s_) * v) - 2 * v.dot(atb) + s_[kBB]);
}

namespace {

// The cell, widened by a hair so a vertex on its face counts as inside.
bool in_cell(const Eigen::Vector3d& x, const double lo[3], const double hi[3]) {
  double slack = 1e-9 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
  bool inside = true;
  for (int a = 0; a < 3; ++a) inside &= x[a] >= lo[a] - slack && x[a] <= hi[a] + slack;
  return inside;
}

// The dominant eigenvector of `a` (a unit vector; its eigenvalue in `lambda`) when the other two
// eigenvalues are certainly under kCutoff times it: their sum, the trace minus it, is. Found by power
// iteration, which converges fast exactly then (by their ratio per step); false otherwise. The
// iterate is scaled by 1/trace, not normalised: a normalisation's square root and division on
// every step's chain were most of a solve (the largest eigenvalue is at least a third of the trace,
// so 24 steps shrink it by at most 3^-24). The direction is what converges: the angle between
// steps, from their cross product.
bool dominant(const Eigen::Matrix3d& a, double cutoff, Eigen::Vector3d& v, double& lambda) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (a(i, i) > a(k, k)) k = i;
  v = a.col(k);
  double trace = a.trace();
  if (!(trace > 0) || !(v.squaredNorm() > 0)) return false;
  const double inv = 1 / trace;
  for (int step = 0; step < 24; ++step) {
    Eigen::Vector3d next = (a * v) * inv;
    double moved = next.cross(v).squaredNorm(), scale = next.squaredNorm() * v.squaredNorm();
    v = next;
    if (!(scale > 0)) return false;
    if (moved < 1e-18 * scale) break;
  }
  v.normalize();
  lambda = v.dot(a * v);
  // The sum of the others, with room for the estimate's own error, under the cutoff.
  return lambda > 0 && (trace - lambda) + 1e-12 * trace < cutoff * lambda && (a * v - lambda * v).norm() < 1e-9 * trace;
}

}  // namespace

Qef::Solution Qef::solve(const double lo[3], const double hi[3]) const {
  Solution s;
  if (count_ == 0) {
    for (int a = 0; a < 3; ++a) s.x[a] = (lo[a] + hi[a]) / 2;
    return s;
  }
  Eigen::Matrix3d ata = matrix(s_);
  Eigen::Vector3d atb(s_[kBX], s_[kBY], s_[kBZ]);
  Eigen::Vector3d c = Eigen::Vector3d(s_[kMX], s_[kMY], s_[kMZ]) / static_cast<double>(count_);
  auto finish = [&](const Eigen::Vector3d& x, int rank) {
    for (int a = 0; a < 3; ++a) s.x[a] = std::clamp(x[a], lo[a], hi[a]);  // only the mass point may need it
    s.rank = rank;
    s.error = error(s.x);
    return s;
  };
  // Nearly parallel planes (most cells of a smooth surface): one direction, without the full
  // eigen-decomposition, whose closed form costs several times more.
  Eigen::Vector3d v;
  double lambda;
  if (dominant(ata, kCutoff, v, lambda)) {
    Eigen::Vector3d x = c + v * (v.dot(atb - ata * c) / lambda);
    return in_cell(x, lo, hi) ? finish(x, 1) : finish(c, 0);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(ata);  // closed form: several times faster than the iterative solver on 3x3
  const Eigen::Vector3d& values = eig.eigenvalues();  // ascending
  const Eigen::Matrix3d& vec = eig.eigenvectors();
  int usable = 0;
  for (int i = 0; i < 3; ++i) usable += values[i] > kCutoff * values[2] && values[i] > 0;
  Eigen::Vector3d r = atb - ata * c;
  for (int rank = usable; rank > 0; --rank) {
    Eigen::Vector3d x = c;
    for (int i = 3 - rank; i < 3; ++i) x += vec.col(i) * (vec.col(i).dot(r) / values[i]);
    if (in_cell(x, lo, hi)) return finish(x, rank);
  }
  return finish(c, 0);
}

}  // namespace fscript::mesh
