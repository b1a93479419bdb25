// Shading: without scene lights a headlight and a key light with a fixed mix; with them the VRML97
// model (emissive, ambient, diffuse, specular with exponent 128 * shininess) per light.
#include "engine/render/shading.h"

#include <algorithm>
#include <cmath>

namespace fscript::render {
namespace {

double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 norm(V3 a) {
  double l = std::sqrt(dot(a, a));
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : a;
}

// x^e for x in [0, 1]: by squaring where e is a whole number (the usual exponents: 40, 128 *
// shininess), which takes a tenth of pow's time in a picture's million pixels.
double power(double x, double e) {
  if (!(e >= 1 && e <= 4096 && e == std::floor(e))) return std::pow(x, e);
  double r = 1;
  for (auto k = static_cast<unsigned>(e); k; k >>= 1, x *= x)
    if (k & 1) r *= x;
  return r;
}

const mesh::Material kDefaultMaterial{};

// The built-in key light, above the camera and a little to its right.
V3 key_light(const Shading& s) {
  const V3 &b = s.back, &u = s.up, &r = s.right;
  return norm({b[0] + u[0] + 0.5 * r[0], b[1] + u[1] + 0.5 * r[1], b[2] + u[2] + 0.5 * r[2]});
}

// Without scene lights: the headlight and the key light (key, and hv halfway to the viewer), for
// n already unit and facing the viewer.
std::array<float, 3> key_lit(const Shading& sh, std::array<float, 3> base, V3 n, V3 view_dir, V3 key, V3 hv) {
  const mesh::Material& mat = sh.material ? *sh.material : kDefaultMaterial;
  double diff = (sh.headlight ? 0.55 * std::max(0.0, dot(n, view_dir)) : 0.0) + 0.35 * std::max(0.0, dot(n, key));
  double exponent = sh.material ? std::max(1.0, 128.0 * mat.shininess) : 40.0;
  double spec = power(std::max(0.0, dot(n, hv)), exponent);
  std::array<float, 3> out;
  for (int k = 0; k < 3; ++k) {
    double s = sh.material ? 0.6 * mat.specular[k] : 0.25;
    out[k] = static_cast<float>(std::min(1.0, mat.emissive[k] + base[k] * (0.2 + diff) + s * spec));
  }
  return out;
}

}  // namespace

FixedViewShading::FixedViewShading(const Shading& s, V3 view_dir) : s_(s), view_(view_dir) {
  key_ = key_light(s);
  hv_ = norm({key_[0] + view_dir[0], key_[1] + view_dir[1], key_[2] + view_dir[2]});
}

std::array<float, 3> FixedViewShading::shade(std::array<float, 3> base, V3 n) const {
  if (!s_.lights.empty()) return s_.shade(base, n, view_);
  n = norm(n);
  if (dot(n, view_) < 0) n = {-n[0], -n[1], -n[2]};
  return key_lit(s_, base, n, view_, key_, hv_);
}

std::array<float, 3> Shading::shade(std::array<float, 3> base, V3 n, V3 view_dir) const {
  n = norm(n);
  if (dot(n, view_dir) < 0) n = {-n[0], -n[1], -n[2]};
  const mesh::Material& mat = material ? *material : kDefaultMaterial;
  std::array<float, 3> out;
  if (lights.empty()) {
    const V3 key = key_light(*this), hv = norm({key[0] + view_dir[0], key[1] + view_dir[1], key[2] + view_dir[2]});
    return key_lit(*this, base, n, view_dir, key, hv);
  }
  std::array<double, 3> sum{mat.emissive[0], mat.emissive[1], mat.emissive[2]};
  auto add = [&](V3 to_light, const std::array<float, 3>& colour, double intensity, double ambient) {
    double d = std::max(0.0, dot(n, to_light));
    V3 h = norm({to_light[0] + view_dir[0], to_light[1] + view_dir[1], to_light[2] + view_dir[2]});
    double s = d > 0 ? power(std::max(0.0, dot(n, h)), std::max(1.0, 128.0 * mat.shininess)) : 0.0;
    for (int k = 0; k < 3; ++k)
      sum[k] +=
          colour[k] * (ambient * mat.ambient_intensity * base[k] + intensity * (base[k] * d + mat.specular[k] * s));
  };
  if (headlight) add(view_dir, {1, 1, 1}, 1.0, 0.0);
  for (const auto& l : lights)
    add(norm({-l.direction[0], -l.direction[1], -l.direction[2]}), l.colour, l.intensity, l.ambient);
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::clamp(sum[k], 0.0, 1.0));
  return out;
}

}  // namespace fscript::render
