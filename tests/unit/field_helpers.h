#pragma once
// Fields from C++ functions and a fixed rotation off the grid axes, for the mesher tests.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

#include "engine/mesh/marching_tetrahedra.h"

namespace fscript::test {

// A field from a C++ function (inside where f > 0).
struct FnField : mesh::Field {
  std::function<double(double, double, double)> f;
  explicit FnField(std::function<double(double, double, double)> fn) : f(std::move(fn)) {}
  bool eval(const float* x, const float* y, const float* z, size_t n, float* out,
            backends::RuntimeError&) const override {
    for (size_t i = 0; i < n; ++i) out[i] = static_cast<float>(f(x[i], y[i], z[i]));
    return true;
  }
};

// The same with its gradient, as a scene's kernels have one (ir/passes/gradient).
struct GradField : FnField {
  std::function<void(double, double, double, double[3])> grad;
  GradField(std::function<double(double, double, double)> fn, std::function<void(double, double, double, double[3])> g)
      : FnField(std::move(fn)), grad(std::move(g)) {}
  bool has_gradient() const override { return true; }
  bool eval_gradient(const float* x, const float* y, const float* z, size_t n, float* const out[4],
                     backends::RuntimeError&) const override {
    for (size_t i = 0; i < n; ++i) {
      double g[3];
      grad(x[i], y[i], z[i], g);
      out[0][i] = static_cast<float>(f(x[i], y[i], z[i]));
      for (int a = 0; a < 3; ++a) out[1 + a][i] = static_cast<float>(g[a]);
    }
    return true;
  }
};

// The job over the cube [-half, half]^3 with `cells` samples a side.
inline mesh::ImplicitJob job(const mesh::Field& f, int cells, double half = 1.0) {
  mesh::ImplicitJob j;
  j.field = &f;
  j.box = {-half, half, -half, half, -half, half};
  j.cells = {cells, cells, cells};
  return j;
}

// The job meshed by `kind` at `tolerance`, which must succeed.
inline mesh::Mesh meshed(mesh::ImplicitJob j, mesh::Mesher kind,
                         double tolerance = mesh::MesherOptions::kDefaultTolerance) {
  j.mesher.kind = kind;
  j.mesher.tolerance = tolerance;
  mesh::Mesh m;
  backends::RuntimeError err;
  REQUIRE(mesh::polygonize(j, m, err));
  return m;
}

// The rotation about (1, 2, 3) through 0.6 radians, and its inverse (the transpose).
struct Turn {
  double m[3][3];
  Turn() {
    double k[3] = {1 / std::sqrt(14.0), 2 / std::sqrt(14.0), 3 / std::sqrt(14.0)}, c = std::cos(0.6), s = std::sin(0.6);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
    m[0][1] -= s * k[2], m[0][2] += s * k[1], m[1][0] += s * k[2], m[1][2] -= s * k[0], m[2][0] -= s * k[1],
        m[2][1] += s * k[0];
  }
  void apply(const double p[3], double out[3], bool inverse) const {
    for (int i = 0; i < 3; ++i) out[i] = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out[i] += (inverse ? m[j][i] : m[i][j]) * p[j];
  }
};

}  // namespace fscript::test
