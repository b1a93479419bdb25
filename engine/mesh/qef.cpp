// Qef: accumulation in double, minimisation by a symmetric eigen-decomposition (Eigen) with small
// eigenvalues dropped relative to the largest, and rank reduction until the vertex is in its cell.
#include "engine/mesh/qef.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace fscript::mesh {

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
// eigenvalues are certainly under kCutoff times it: their sum, the trace minus it, is. Then their
// ratio to it is under kCutoff too, so (a / trace)^16, four squarings, has every column along the
// dominant direction to within kCutoff^16 = 1e-16: the one with the largest diagonal is taken. Power
// iteration needed five to twenty dependent steps, each waiting on the last and on a convergence
// test; a squaring's 18 products are independent (it was most of a solve, and solves 12% of a mesh).
// The certificate is the same: the trace, and the residual of the unit vector found.
bool dominant(const Eigen::Matrix3d& a, double cutoff, Eigen::Vector3d& v, double& lambda) {
  double trace = a.trace();
  if (!(trace > 0) || !std::isfinite(trace)) return false;
  const double inv = 1 / trace;
  // Symmetric, so six entries: xx xy xz yy yz zz.
  double m[6] = {a(0, 0) * inv, a(0, 1) * inv, a(0, 2) * inv, a(1, 1) * inv, a(1, 2) * inv, a(2, 2) * inv};
  for (int step = 0; step < 4; ++step) {
    const double xx = m[0], xy = m[1], xz = m[2], yy = m[3], yz = m[4], zz = m[5];
    m[0] = xx * xx + xy * xy + xz * xz, m[1] = xx * xy + xy * yy + xz * yz, m[2] = xx * xz + xy * yz + xz * zz;
    m[3] = xy * xy + yy * yy + yz * yz, m[4] = xy * xz + yy * yz + yz * zz, m[5] = xz * xz + yz * yz + zz * zz;
  }
  const double diagonal[3] = {m[0], m[3], m[5]};
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (diagonal[i] > diagonal[k]) k = i;
  v = k == 0   ? Eigen::Vector3d(m[0], m[1], m[2])
      : k == 1 ? Eigen::Vector3d(m[1], m[3], m[4])
               : Eigen::Vector3d(m[2], m[4], m[5]);
  // Normalised by the squared length: no square root on the chain (the residual is compared squared).
  double length2 = v.squaredNorm();
  if (!(length2 > 0) || !std::isfinite(length2)) return false;
  v /= std::sqrt(length2);
  Eigen::Vector3d av = a * v;
  lambda = v.dot(av);
  // The sum of the others, with room for the estimate's own error, under the cutoff.
  return lambda > 0 && (trace - lambda) + 1e-12 * trace < cutoff * lambda &&
      (av - lambda * v).squaredNorm() < 1e-18 * trace * trace;
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
