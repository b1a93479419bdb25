// Rasteriser: project, clip against the near plane (triangles wholly behind are dropped), fill
// with barycentric interpolation of depth, colour and normal, shade per sample, downsample.
#include "engine/render/raster.h"

#include "engine/render/direct.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fscript::render {
namespace {

V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
V3 norm(V3 a) {
  double l = std::sqrt(dot(a, a));
  return l > 0 ? V3{a[0] / l, a[1] / l, a[2] / l} : a;
}

// Rodrigues rotation of v by the VRML rotation r.
V3 rotate(const std::array<double, 4>& r, V3 v) {
  V3 k = norm({r[0], r[1], r[2]});
  double c = std::cos(r[3]), s = std::sin(r[3]);
  V3 kv = cross(k, v);
  double kd = dot(k, v);
  return {v[0] * c + kv[0] * s + k[0] * kd * (1 - c), v[1] * c + kv[1] * s + k[1] * kd * (1 - c),
          v[2] * c + kv[2] * s + k[2] * kd * (1 - c)};
}

struct View {
  V3 eye, right, up, back;  // camera frame: looking along -back
  double focal;             // pixels
  double cx, cy;
};

// Where the automatic camera stands: the view direction from azimuth and elevation, then the
// distance at which the mesh's outline, measured across the view at its middle depth, fills 80%
// of the smaller side (and its nearest points still fit), looking at the outline's centre.
// The automatic camera looks along minus this.
V3 automatic_back(const RenderOptions& o) {
  const double deg = 3.14159265358979323846 / 180;
  double az = o.azimuth * deg, el = std::clamp(o.elevation, -89.0, 89.0) * deg;
  return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

void frame_mesh(const mesh::Mesh& m, const std::vector<mesh::Vec3>& extra, const RenderOptions& o, double fov,
                uint32_t w, uint32_t h, View& v) {
  v.back = automatic_back(o);
  v.right = norm(cross({0, 1, 0}, v.back));
  v.up = cross(v.back, v.right);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};  // along right, up, back
  for (const auto* set : {&m.positions, &extra})
    for (const auto& p : *set) {
      V3 q = {p[0], p[1], p[2]};
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2])) continue;
      double c[3] = {dot(q, v.right), dot(q, v.up), dot(q, v.back)};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
  if (lo[0] > hi[0])
    for (int a = 0; a < 3; ++a) lo[a] = -1, hi[a] = 1;
  double half_r = std::max(1e-6, (hi[0] - lo[0]) / 2), half_u = std::max(1e-6, (hi[1] - lo[1]) / 2);
  double side = std::min(w, h);
  double tan_r = std::tan(fov / 2) * w / side, tan_u = std::tan(fov / 2) * h / side;
  double zoom = o.zoom > 0 ? o.zoom : 1;
  double fit = 0.8 * zoom, near_fit = 0.95 * zoom;
  double depth = (hi[2] - lo[2]) / 2;
  double dist = std::max({half_r / (fit * tan_r), half_u / (fit * tan_u),
                          depth + std::max(half_r / (near_fit * tan_r), half_u / (near_fit * tan_u))});
  double mid[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 + dist};
  for (int k = 0; k < 3; ++k) v.eye[k] = v.right[k] * mid[0] + v.up[k] * mid[1] + v.back[k] * mid[2];
}

View make_view(const mesh::Mesh& m, const std::vector<mesh::Vec3>& extra, const RenderOptions& o, uint32_t w,
               uint32_t h) {
  View v;
  bool fixed = o.camera && !o.view_given;
  double fov = fixed ? o.camera->field_of_view : 0.6;
  if (fixed) {
    v.eye = {o.camera->position[0], o.camera->position[1], o.camera->position[2]};
    v.right = rotate(o.camera->orientation, {1, 0, 0});
    v.up = rotate(o.camera->orientation, {0, 1, 0});
    v.back = rotate(o.camera->orientation, {0, 0, 1});
    if (o.zoom > 0 && o.zoom != 1) fov = 2 * std::atan(std::tan(fov / 2) / o.zoom);
  } else {
    frame_mesh(m, extra, o, fov, w, h, v);
  }
  v.focal = 0.5 * std::min(w, h) / std::tan(fov / 2);
  v.cx = w / 2.0, v.cy = h / 2.0;
  return v;
}

struct Sample {
  std::vector<float> depth;
  std::vector<std::array<float, 3>> rgb;
};

class Raster {
 public:
  // `outline`: points around the direct shapes, which the automatic camera frames with the mesh.
  Raster(const mesh::Mesh& m, const std::vector<DirectShape>& direct, const std::vector<mesh::Vec3>& outline,
         const RenderOptions& o)
      : m_(m), direct_(direct), o_(o), w_(o.width * o.supersample), h_(o.height * o.supersample),
        v_(make_view(m, outline, o, w_, h_)) {
    depth_.assign(size_t(w_) * h_, std::numeric_limits<float>::infinity());
    light_.lights = o.lights, light_.headlight = o.headlight, light_.material = m.material;
    light_.right = v_.right, light_.up = v_.up, light_.back = v_.back;
    rgb_.assign(size_t(w_) * h_, o.background);
  }

  std::vector<uint8_t> run() {
    if (m_.normals.size() != m_.positions.size()) corner_ = mesh::crease_normals(m_, o_.crease_angle);
    proj_.resize(m_.positions.size());
    for (size_t i = 0; i < m_.positions.size(); ++i) proj_[i] = project(m_.positions[i]);
    for (size_t t = 0; t < m_.triangles.size(); ++t) triangle(t);
    for (const auto& l : m_.polylines)
      for (size_t k = 0; k + 1 < l.size(); ++k) line(l[k], l[k + 1]);
    return downsample();
  }

  // The meshes, then each direct shape; false on the first direct shape's runtime error.
  bool run(std::vector<uint8_t>& out, backends::RuntimeError& err, size_t& failed) {
    for (failed = 0; failed < direct_.size(); ++failed)
      if (!direct(direct_[failed], err)) return false;
    out = run();
    return true;
  }

 private:
  // Screen x, y and view depth (positive in front of the eye).
  V3 project(const mesh::Vec3& p) const {
    V3 d = sub({p[0], p[1], p[2]}, v_.eye);
    double z = -dot(d, v_.back);
    return {v_.cx + v_.focal * dot(d, v_.right) / z, v_.cy - v_.focal * dot(d, v_.up) / z, z};
  }

  std::array<float, 3> colour(uint32_t i) const {
    if (m_.colours.size() == m_.positions.size()) return m_.colours[i];
    return m_.material ? m_.material->diffuse : o_.default_colour;
  }

  void triangle(size_t ti) {
    const std::array<uint32_t, 3>& t = m_.triangles[ti];
    const V3 &a = proj_[t[0]], &b = proj_[t[1]], &c = proj_[t[2]];
    if (a[2] <= 1e-6 || b[2] <= 1e-6 || c[2] <= 1e-6) return;  // behind or at the eye
    double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0 || !std::isfinite(area)) return;
    int x0 = std::max(0, int(std::floor(std::min({a[0], b[0], c[0]}))));
    int x1 = std::min(int(w_) - 1, int(std::ceil(std::max({a[0], b[0], c[0]}))));
    int y0 = std::max(0, int(std::floor(std::min({a[1], b[1], c[1]}))));
    int y1 = std::min(int(h_) - 1, int(std::ceil(std::max({a[1], b[1], c[1]}))));
    bool normals = m_.normals.size() == m_.positions.size();
    V3 face = cross(sub(to3(m_.positions[t[1]]), to3(m_.positions[t[0]])),
                    sub(to3(m_.positions[t[2]]), to3(m_.positions[t[0]])));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        double px = x + 0.5, py = y + 0.5;
        double w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
        double w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
        double w2 = 1 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        // Perspective-correct interpolation through 1/z.
        double iz = w0 / a[2] + w1 / b[2] + w2 / c[2];
        double z = 1 / iz;
        size_t idx = size_t(y) * w_ + x;
        if (z >= depth_[idx]) continue;
        depth_[idx] = static_cast<float>(z);
        double q0 = w0 / a[2] * z, q1 = w1 / b[2] * z, q2 = w2 / c[2] * z;
        std::array<float, 3> base;
        auto ca = colour(t[0]), cb = colour(t[1]), cc = colour(t[2]);
        for (int k = 0; k < 3; ++k) base[k] = static_cast<float>(q0 * ca[k] + q1 * cb[k] + q2 * cc[k]);
        V3 n = face;
        const mesh::Vec3* c = normals ? nullptr : &corner_[3 * ti];  // no vertex normals: by corner
        auto normal = [&](int q) { return normals ? m_.normals[t[static_cast<size_t>(q)]] : c[q]; };
        if (normals || (face[0] != 0 || face[1] != 0 || face[2] != 0))
          for (int k = 0; k < 3; ++k) n[k] = q0 * normal(0)[k] + q1 * normal(1)[k] + q2 * normal(2)[k];
        V3 p;
        for (int k = 0; k < 3; ++k)
          p[k] = q0 * m_.positions[t[0]][k] + q1 * m_.positions[t[1]][k] + q2 * m_.positions[t[2]][k];
        rgb_[idx] = light_.shade(base, n, norm(sub(v_.eye, p)));
      }
  }

  static V3 to3(const mesh::Vec3& p) { return {p[0], p[1], p[2]}; }

  // Polylines: a few samples wide, depth-tested, unlit.
  void line(uint32_t i, uint32_t j) {
    const V3 &a = proj_[i], &b = proj_[j];
    if (a[2] <= 1e-6 || b[2] <= 1e-6) return;
    double len = std::max(std::fabs(b[0] - a[0]), std::fabs(b[1] - a[1]));
    int steps = std::max(1, int(std::ceil(len)));
    int half = std::max(1, o_.supersample);
    auto ca = colour(i), cb = colour(j);
    for (int s = 0; s <= steps; ++s) {
      double f = double(s) / steps;
      double x = a[0] + f * (b[0] - a[0]), y = a[1] + f * (b[1] - a[1]), z = a[2] + f * (b[2] - a[2]);
      for (int dy = -half; dy <= half; ++dy)
        for (int dx = -half; dx <= half; ++dx) {
          int px = int(x) + dx, py = int(y) + dy;
          if (px < 0 || py < 0 || px >= int(w_) || py >= int(h_)) continue;
          size_t idx = size_t(py) * w_ + px;
          if (z >= depth_[idx]) continue;
          depth_[idx] = static_cast<float>(z);
          for (int k = 0; k < 3; ++k) rgb_[idx][k] = static_cast<float>(0.8 * (ca[k] + f * (cb[k] - ca[k])));
        }
    }
  }

  std::vector<uint8_t> downsample() const {
    int s = o_.supersample;
    std::vector<uint8_t> out(size_t(o_.width) * o_.height * 3);
    for (uint32_t y = 0; y < o_.height; ++y)
      for (uint32_t x = 0; x < o_.width; ++x)
        for (int k = 0; k < 3; ++k) {
          double sum = 0;
          for (int dy = 0; dy < s; ++dy)
            for (int dx = 0; dx < s; ++dx) sum += rgb_[size_t(y * s + dy) * w_ + x * s + dx][k];
          out[(size_t(y) * o_.width + x) * 3 + k] =
              static_cast<uint8_t>(std::lround(std::clamp(sum / (s * s), 0.0, 1.0) * 255));
        }
    return out;
  }

  bool direct(const DirectShape& d, backends::RuntimeError& err);
  RayGrid rays(const DirectShape& d, const std::array<double, 16>& inv, uint32_t step, uint32_t row0,
               uint32_t rows) const;
  // The pixels a direct shape's samples are traced in: those whose centre's hit differs from a
  // neighbour's (an outline, a fold), or lies on both sides of a mesh's depths there.
  std::vector<char> edges(const Hits& centre) const;

  const mesh::Mesh& m_;
  const std::vector<DirectShape>& direct_;
  std::vector<mesh::Vec3> corner_;  // crease_normals, where the mesh has no vertex normals
  const RenderOptions& o_;
  uint32_t w_, h_;
  View v_;
  Shading light_;
  std::vector<V3> proj_;
  std::vector<float> depth_;
  std::vector<std::array<float, 3>> rgb_;
};

// Affine maps, column-major as VRML's Transform makes them.
using M4 = std::array<double, 16>;
V3 map_point(const M4& m, V3 p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12], m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}
V3 linear(const M4& m, V3 v) {
  return {m[0] * v[0] + m[4] * v[1] + m[8] * v[2], m[1] * v[0] + m[5] * v[1] + m[9] * v[2],
          m[2] * v[0] + m[6] * v[1] + m[10] * v[2]};
}
bool invert(const M4& m, M4& out) {
  double a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], i = m[10];
  double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
  double r[9] = {(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det,
                 (f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det,
                 (d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det};  // row-major
  out = {r[0], r[3], r[6], 0, r[1], r[4], r[7], 0, r[2], r[5], r[8], 0, 0, 0, 0, 1};
  V3 t = linear(out, {m[12], m[13], m[14]});
  out[12] = -t[0], out[13] = -t[1], out[14] = -t[2];
  return true;
}

// The rays of a direct shape's samples in rows [row0, row0 + rows), or of every `step`-th sample a
// side (the pixels' centres when `step` is the supersampling), moved into the shape's frame (an
// affine map keeps a ray a ray, its parameter still the view depth) and probed over the depths of
// its extent.
RayGrid Raster::rays(const DirectShape& d, const M4& inv, uint32_t step, uint32_t row0, uint32_t rows) const {
  double zmin = HUGE_VAL, zmax = -HUGE_VAL;
  for (int k = 0; k < 8; ++k) {
    V3 c = {d.extent[k & 1], d.extent[2 + ((k >> 1) & 1)], d.extent[4 + ((k >> 2) & 1)]};
    double z = -dot(sub(c, v_.eye), v_.back);
    zmin = std::min(zmin, z), zmax = std::max(zmax, z);
  }
  RayGrid g;
  g.w = w_ / step, g.h = rows / step;
  g.steps = std::max({64u, w_ / step, h_ / step});
  g.near = std::max(zmin, 1e-4 * zmax), g.far = std::max(zmax, g.near);
  V3 eye = map_point(inv, v_.eye);
  V3 d0, dc, dr;
  const double first = 0.5 * step, top = row0 + 0.5 * step;  // the first ray's sample coordinates
  for (int k = 0; k < 3; ++k) {
    d0[k] = v_.right[k] * (first - v_.cx) / v_.focal - v_.up[k] * (top - v_.cy) / v_.focal - v_.back[k];
    dc[k] = v_.right[k] * step / v_.focal, dr[k] = -v_.up[k] * step / v_.focal;
  }
  V3 ld0 = linear(inv, d0), ldc = linear(inv, dc), ldr = linear(inv, dr);
  for (int k = 0; k < 3; ++k) {
    g.origin[k] = eye[k], g.dir[k] = ld0[k], g.dir_col[k] = ldc[k], g.dir_row[k] = ldr[k];
    g.box.lo[k] = static_cast<float>(d.box[2 * k]), g.box.hi[k] = static_cast<float>(d.box[2 * k + 1]);
  }
  return g;
}

std::vector<char> Raster::edges(const Hits& c) const {
  const uint32_t s = static_cast<uint32_t>(o_.supersample), w = w_ / s, h = h_ / s;
  auto depth = [&](int64_t x, int64_t y) {
    x = std::clamp<int64_t>(x, 0, w - 1), y = std::clamp<int64_t>(y, 0, h - 1);
    return c.depth[size_t(y) * w + size_t(x)];
  };
  std::vector<char> fine(size_t(w_) * h_, 0);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      float d = depth(x, y);
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy)
        for (int dx = -1; dx <= 1 && !edge; ++dx) {
          float e = depth(int64_t(x) + dx, int64_t(y) + dy);
          edge = std::isfinite(d) != std::isfinite(e) || (std::isfinite(d) && std::fabs(d - e) > 0.02f * d);
        }
      if (std::isfinite(d) && !edge)  // a mesh in front of part of the pixel and behind the rest
        for (uint32_t k = 0; k < s * s && !edge; ++k) {
          float m = depth_[size_t(y * s + k / s) * w_ + x * s + k % s];
          edge = (m < d) != (depth_[size_t(y * s) * w_ + x * s] < d);
        }
      if (!edge) continue;
      for (uint32_t k = 0; k < s * s; ++k) fine[size_t(y * s + k / s) * w_ + x * s + k % s] = 1;
    }
  return fine;
}

// One direct shape: its rays traced through the pixels' centres, then through every sample of the
// pixels on an edge, a band of rows at a time (the samples' hits take memory); a pixel inside the
// shape takes its centre's hit for all its samples. Where a sample meets the shape in front of what
// is there, it is shaded like a mesh's surface.
bool Raster::direct(const DirectShape& d, backends::RuntimeError& err) {
  M4 inv;
  if (!invert(d.to_world, inv)) return true;  // a zero scale: nothing shows
  const uint32_t s = static_cast<uint32_t>(o_.supersample);
  RayGrid coarse = rays(d, inv, s, 0, h_);
  if (!(coarse.far > 0)) return true;  // wholly behind the eye
  DirectOptions o;
  o.threads = o_.threads, o.prune = o_.prune;
  Hits centre, fine;
  DirectStats stats;
  if (!trace(*d.field, coarse, o, centre, stats, err)) return false;
  std::vector<char> wanted = edges(centre), band_wanted;
  constexpr uint32_t kBand = 256;  // rows of samples traced at once
  Shading light = light_;
  light.material = d.material;
  const std::array<float, 3> base = d.material ? d.material->diffuse : o_.default_colour;
  std::vector<size_t> shown;
  std::vector<std::array<float, 3>> points, normals, colours;
  for (uint32_t r0 = 0; r0 < h_; r0 += kBand) {
    const uint32_t rows = std::min(kBand, h_ - r0);
    const size_t first = size_t(r0) * w_, count = size_t(rows) * w_;
    band_wanted.assign(wanted.begin() + static_cast<long>(first), wanted.begin() + static_cast<long>(first + count));
    bool any = s > 1 && std::find(band_wanted.begin(), band_wanted.end(), 1) != band_wanted.end();
    if (any) {
      o.wanted = &band_wanted;
      if (!trace(*d.field, rays(d, inv, 1, r0, rows), o, fine, stats, err)) return false;
    }
    shown.clear(), points.clear(), normals.clear();
    for (size_t k = 0; k < count; ++k) {
      const size_t i = first + k;
      const size_t c = size_t(i / w_ / s) * coarse.w + (i % w_) / s;
      const bool own = any && band_wanted[k];
      float depth = own ? fine.depth[k] : centre.depth[c];
      if (!(depth < depth_[i])) continue;
      depth_[i] = depth;
      shown.push_back(i);
      points.push_back(own ? fine.point[k] : centre.point[c]);
      normals.push_back(own ? fine.normal[k] : centre.normal[c]);
    }
    if (d.colour && !d.colour(points, colours, err)) return false;
    for (size_t j = 0; j < shown.size(); ++j) {
      const auto& p = points[j];
      const auto& n = normals[j];
      V3 world = map_point(d.to_world, {p[0], p[1], p[2]}), nw;
      for (int r = 0; r < 3; ++r) nw[r] = inv[r * 4] * n[0] + inv[r * 4 + 1] * n[1] + inv[r * 4 + 2] * n[2];
      rgb_[shown[j]] = light.shade(colours.size() == shown.size() ? colours[j] : base, nw, norm(sub(v_.eye, world)));
    }
  }
  return true;
}

}  // namespace

std::vector<uint8_t> render(const mesh::Mesh& m, const RenderOptions& opts) { return Raster(m, {}, {}, opts).run(); }

namespace {

// What the automatic camera frames of the direct shapes: their surfaces seen along the view from
// the front and from the back (the outline across the view and the nearest and farthest points),
// in 128 x 128 rays each; a shape they miss (too thin) by the corners of its cells.
bool outline(const std::vector<DirectShape>& direct, const RenderOptions& opts, std::vector<mesh::Vec3>& out,
             backends::RuntimeError& err, size_t& failed) {
  V3 back = automatic_back(opts);
  DirectOptions o;
  o.threads = opts.threads, o.prune = opts.prune;
  for (failed = 0; failed < direct.size(); ++failed) {
    const DirectShape& d = direct[failed];
    M4 inv;
    if (!invert(d.to_world, inv)) continue;
    V3 away = linear(inv, {-back[0], -back[1], -back[2]});
    size_t found = 0;
    for (double sign : {1.0, -1.0}) {
      Hits hits;
      DirectStats stats;
      if (!trace(*d.field, parallel(d.box, {sign * away[0], sign * away[1], sign * away[2]}, 128), o, hits, stats, err))
        return false;
      for (size_t i = 0; i < hits.depth.size(); ++i) {
        if (!std::isfinite(hits.depth[i])) continue;
        const auto& p = hits.point[i];
        V3 w = map_point(d.to_world, {p[0], p[1], p[2]});
        out.push_back({static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2])}), ++found;
      }
    }
    if (found == 0) out.insert(out.end(), d.outline.begin(), d.outline.end());
  }
  return true;
}

}  // namespace

bool render(const mesh::Mesh& m, const std::vector<DirectShape>& direct, const RenderOptions& opts,
            std::vector<uint8_t>& out, backends::RuntimeError& err, size_t& failed) {
  std::vector<mesh::Vec3> around;
  bool automatic = !opts.camera || opts.view_given;
  if (automatic && !outline(direct, opts, around, err, failed)) return false;
  return Raster(m, direct, around, opts).run(out, err, failed);
}

}  // namespace fscript::render
