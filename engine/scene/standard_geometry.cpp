// Standard VRML97 geometry to meshes: a walk over grouping nodes carrying the Transform matrix.
#include "engine/scene/standard_geometry.h"

#include <cmath>
#include <optional>

#include "engine/scene/scene_model.h"
#include "engine/scene/shape_mesh.h"

namespace fscript::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSegments = 32;  // around a sphere, cylinder or cone

const std::vector<double>& nums(const vrml::Node* n, const char* field) {
  static const std::vector<double> none;
  const vrml::Value* v = n ? n->get(field) : nullptr;
  return v ? v->nums : none;
}

double number(const vrml::Node* n, const char* field, double fallback) {
  return n ? field_number(*n, field, 0, fallback) : fallback;
}

const vrml::Node* child(const vrml::Node* n, const char* field) {
  const vrml::Value* v = n ? n->get(field) : nullptr;
  return v && !v->nodes.empty() ? v->nodes[0].get() : nullptr;
}

mesh::Vec3 vec(const std::vector<double>& v, size_t i) {
  return {static_cast<float>(v[3 * i]), static_cast<float>(v[3 * i + 1]), static_cast<float>(v[3 * i + 2])};
}

mesh::Vec3 face_normal(const mesh::Vec3& a, const mesh::Vec3& b, const mesh::Vec3& c) {
  mesh::Vec3 u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  mesh::Vec3 n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  return len > 0 ? mesh::Vec3{n[0] / len, n[1] / len, n[2] / len} : mesh::Vec3{0, 0, 1};
}

// Faces split into fans; each face gets its own vertices (flat shading) unless normals are given.
void indexed_faces(const vrml::Node* g, mesh::Mesh& m) {
  const auto& pts = nums(child(g, "coord"), "point");
  const auto& idx = nums(g, "coordIndex");
  const auto& cols = nums(child(g, "color"), "color");
  const auto& col_idx = nums(g, "colorIndex");
  bool per_vertex = number(g, "colorPerVertex", 1) != 0;
  size_t npts = pts.size() / 3, ncols = cols.size() / 3, face = 0;
  std::vector<uint32_t> poly;
  auto colour_of = [&](size_t corner, uint32_t point) -> std::optional<mesh::Vec3> {
    if (ncols == 0) return std::nullopt;
    size_t c = per_vertex ? (corner < col_idx.size() && col_idx[corner] >= 0 ? size_t(col_idx[corner]) : point)
                          : (face < col_idx.size() && col_idx[face] >= 0 ? size_t(col_idx[face]) : face);
    return c < ncols ? std::optional<mesh::Vec3>(vec(cols, c)) : std::nullopt;
  };
  std::vector<size_t> corners;
  auto flush = [&] {
    if (poly.size() >= 3) {
      mesh::Vec3 n = face_normal(vec(pts, poly[0]), vec(pts, poly[1]), vec(pts, poly[2]));
      uint32_t base = static_cast<uint32_t>(m.positions.size());
      for (size_t k = 0; k < poly.size(); ++k) {
        m.positions.push_back(vec(pts, poly[k]));
        m.normals.push_back(n);
        auto c = colour_of(corners[k], poly[k]);
        if (c) m.colours.push_back(*c);
      }
      for (size_t k = 1; k + 1 < poly.size(); ++k)
        m.triangles.push_back({base, base + static_cast<uint32_t>(k), base + static_cast<uint32_t>(k + 1)});
    }
    poly.clear(), corners.clear();
    ++face;
  };
  for (size_t k = 0; k < idx.size(); ++k) {
    if (idx[k] < 0) {
      flush();
      continue;
    }
    if (size_t(idx[k]) < npts) poly.push_back(static_cast<uint32_t>(idx[k])), corners.push_back(k);
  }
  flush();
  if (m.colours.size() != m.positions.size()) m.colours.clear();
}

// Lines are unlit (VRML97 6.24): each vertex takes the Color node's colour (per vertex, or per
// polyline with colorPerVertex FALSE, through colorIndex when given), else the Material's
// emissiveColor; with neither, the viewer's default. Each polyline vertex is its own point, so
// its colour stays its own when the picture's meshes are merged.
void indexed_lines(const vrml::Node* shape, const vrml::Node* g, mesh::Mesh& m) {
  const auto& pts = nums(child(g, "coord"), "point");
  const auto& idx = nums(g, "coordIndex");
  const auto& cols = nums(child(g, "color"), "color");
  const auto& col_idx = nums(g, "colorIndex");
  bool per_vertex = number(g, "colorPerVertex", 1) != 0;
  size_t npts = pts.size() / 3, ncols = cols.size() / 3, line = 0;
  std::optional<mesh::Vec3> emissive;
  if (const vrml::Node* mat = child(child(shape, "appearance"), "material")) {
    const auto& e = nums(mat, "emissiveColor");
    emissive = e.size() >= 3 ? vec(e, 0) : mesh::Vec3{0, 0, 0};
  }
  auto colour_of = [&](size_t corner, size_t point) -> std::optional<mesh::Vec3> {
    if (ncols == 0) return emissive;
    size_t c = per_vertex ? (corner < col_idx.size() && col_idx[corner] >= 0 ? size_t(col_idx[corner]) : point)
                          : (line < col_idx.size() && col_idx[line] >= 0 ? size_t(col_idx[line]) : line);
    return c < ncols ? std::optional<mesh::Vec3>(vec(cols, c)) : emissive;
  };
  m.polylines.emplace_back();
  for (size_t k = 0; k < idx.size(); ++k) {
    double i = idx[k];
    if (i < 0 || size_t(i) >= npts) {
      if (!m.polylines.back().empty()) m.polylines.emplace_back();
      if (i < 0) ++line;
      continue;
    }
    m.polylines.back().push_back(static_cast<uint32_t>(m.positions.size()));
    m.positions.push_back(vec(pts, size_t(i)));
    if (auto c = colour_of(k, size_t(i))) m.colours.push_back(*c);
  }
  if (m.polylines.back().empty()) m.polylines.pop_back();
  if (m.colours.size() != m.positions.size()) m.colours.clear();
}

// A quad as two triangles with its own vertices and normal n.
void quad(mesh::Mesh& m, const mesh::Vec3& a, const mesh::Vec3& b, const mesh::Vec3& c, const mesh::Vec3& d,
          const mesh::Vec3& n) {
  uint32_t base = static_cast<uint32_t>(m.positions.size());
  for (const auto& p : {a, b, c, d}) m.positions.push_back(p), m.normals.push_back(n);
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangles.push_back({base, base + 2, base + 3});
}

void box(const vrml::Node* g, mesh::Mesh& m) {
  const auto& s = nums(g, "size");
  float h[3] = {1, 1, 1};
  for (int a = 0; a < 3 && a < static_cast<int>(s.size()); ++a) h[a] = static_cast<float>(s[a] / 2);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto corner = [&](float su, float sv) {
        mesh::Vec3 p{};
        p[axis] = side * h[axis], p[u] = su * h[u], p[v] = sv * h[v];
        return p;
      };
      mesh::Vec3 n{0, 0, 0};
      n[axis] = static_cast<float>(side);
      if (side > 0) quad(m, corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), n);
      else quad(m, corner(-1, -1), corner(-1, 1), corner(1, 1), corner(1, -1), n);
    }
}

void sphere(const vrml::Node* g, mesh::Mesh& m) {
  float r = static_cast<float>(number(g, "radius", 1));
  int rings = kSegments / 2;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i <= kSegments; ++i) {
      double th = kPi * j / rings, ph = 2 * kPi * i / kSegments;
      mesh::Vec3 n = {float(std::sin(th) * std::sin(ph)), float(std::cos(th)), float(std::sin(th) * std::cos(ph))};
      m.positions.push_back({r * n[0], r * n[1], r * n[2]});
      m.normals.push_back(n);
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < kSegments; ++i) {
      uint32_t a = j * (kSegments + 1) + i, b = a + 1, c = a + kSegments + 1, d = c + 1;
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a, d, b});
    }
}

// Cylinder (top radius = bottom) and Cone (top radius 0) along y, with their caps.
void round_solid(const vrml::Node* g, bool cone, mesh::Mesh& m) {
  float r = static_cast<float>(number(g, cone ? "bottomRadius" : "radius", 1)),
        h = static_cast<float>(number(g, "height", 2));
  float top_r = cone ? 0.0f : r, y0 = -h / 2, y1 = h / 2;
  float slope = r - top_r;
  for (int i = 0; i < kSegments; ++i) {
    double a0 = 2 * kPi * i / kSegments, a1 = 2 * kPi * (i + 1) / kSegments;
    mesh::Vec3 d0 = {float(std::sin(a0)), 0, float(std::cos(a0))}, d1 = {float(std::sin(a1)), 0, float(std::cos(a1))};
    auto side_n = [&](const mesh::Vec3& d) {
      mesh::Vec3 n = {d[0] * h, slope, d[2] * h};
      float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      return mesh::Vec3{n[0] / len, n[1] / len, n[2] / len};
    };
    if (number(g, "side", 1) != 0) {
      uint32_t base = static_cast<uint32_t>(m.positions.size());
      m.positions.insert(m.positions.end(),
                         {{r * d0[0], y0, r * d0[2]},
                          {r * d1[0], y0, r * d1[2]},
                          {top_r * d1[0], y1, top_r * d1[2]},
                          {top_r * d0[0], y1, top_r * d0[2]}});
      m.normals.insert(m.normals.end(), {side_n(d0), side_n(d1), side_n(d1), side_n(d0)});
      m.triangles.push_back({base, base + 1, base + 2});
      m.triangles.push_back({base, base + 2, base + 3});
    }
    if (number(g, "bottom", 1) != 0)
      quad(m, {0, y0, 0}, {r * d1[0], y0, r * d1[2]}, {r * d0[0], y0, r * d0[2]}, {0, y0, 0}, {0, -1, 0});
    if (!cone && number(g, "top", 1) != 0)
      quad(m, {0, y1, 0}, {r * d0[0], y1, r * d0[2]}, {r * d1[0], y1, r * d1[2]}, {0, y1, 0}, {0, 1, 0});
  }
}

void material(const vrml::Node* shape, mesh::Mesh& m) {
  const vrml::Node* mat = child(child(shape, "appearance"), "material");
  if (!mat) return;
  mesh::Material out;
  auto colour = [&](const char* f, mesh::Vec3 fallback) {
    const auto& v = nums(mat, f);
    return v.size() >= 3 ? vec(v, 0) : fallback;
  };
  out.diffuse = colour("diffuseColor", out.diffuse);
  out.emissive = colour("emissiveColor", out.emissive);
  out.specular = colour("specularColor", out.specular);
  out.ambient_intensity = static_cast<float>(number(mat, "ambientIntensity", out.ambient_intensity));
  out.shininess = static_cast<float>(number(mat, "shininess", out.shininess));
  out.transparency = static_cast<float>(number(mat, "transparency", out.transparency));
  m.material = out;
}

void walk(const vrml::Node* n, const Mat4& m, std::vector<mesh::Mesh>& out, int depth) {
  if (!n || n->fvrml || n->proto || depth > 1000) return;
  if (n->type == "Shape") {
    const vrml::Node* g = child(n, "geometry");
    if (!g || g->fvrml) return;
    mesh::Mesh mesh;
    if (g->type == "IndexedFaceSet") indexed_faces(g, mesh);
    else if (g->type == "IndexedLineSet") indexed_lines(n, g, mesh);
    else if (g->type == "Box") box(g, mesh);
    else if (g->type == "Sphere") sphere(g, mesh);
    else if (g->type == "Cylinder" || g->type == "Cone") round_solid(g, g->type == "Cone", mesh);
    else return;
    material(n, mesh);
    transform_mesh(m, mesh);
    out.push_back(std::move(mesh));
    return;
  }
  if (n->type == "Inline") {  // a local file's nodes (vrml::load_inlines)
    for (const auto& c : n->inlined) walk(c.get(), m, out, depth + 1);
    return;
  }
  Mat4 here = m;
  if (n->type == "Transform") here = multiply(m, transform_matrix(*n));
  if (n->type == "Switch") {  // only the chosen child is drawn
    int which = static_cast<int>(number(n, "whichChoice", -1));
    const vrml::Value* v = n->get("choice");
    if (v && which >= 0 && which < static_cast<int>(v->nodes.size())) walk(v->nodes[which].get(), here, out, depth + 1);
    return;
  }
  if (n->type == "LOD") {  // the most detailed level
    const vrml::Value* v = n->get("level");
    if (v && !v->nodes.empty()) walk(v->nodes[0].get(), here, out, depth + 1);
    return;
  }
  if (const vrml::Value* v = n->get("children"))
    for (const auto& c : v->nodes) walk(c.get(), here, out, depth + 1);
}

}  // namespace

std::vector<mesh::Mesh> standard_meshes(const vrml::Scene& scene) {
  std::vector<mesh::Mesh> out;
  for (const auto& n : scene.roots) walk(n.get(), identity(), out, 0);
  return out;
}

std::optional<std::array<float, 3>> background_colour(const vrml::Scene& scene) {
  for (const auto& n : scene.roots)
    if (n && n->type == "Background") {
      const auto& sky = nums(n.get(), "skyColor");
      if (sky.size() >= 3) return std::array<float, 3>{float(sky[0]), float(sky[1]), float(sky[2])};
      return std::array<float, 3>{0, 0, 0};  // the VRML97 default sky is black
    }
  return std::nullopt;
}

}  // namespace fscript::scene
