// Mesh writers.
#include "runtime/mesh/mesh_io.h"

#include "runtime/support/files.h"
#include "runtime/mesh/gltf.h"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace fscript::mesh {
namespace {

template <class T>
void put(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

std::string ply(const Mesh& m) {
  bool normals = m.normals.size() == m.positions.size() && !m.positions.empty();
  bool colours = m.colours.size() == m.positions.size() && !m.positions.empty();
  std::string s = "ply\nformat binary_little_endian 1.0\ncomment written by fvrml-run\n";
  s += "element vertex " + std::to_string(m.positions.size()) + "\n";
  s += "property float x\nproperty float y\nproperty float z\n";
  if (normals) s += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colours) s += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  s += "element face " + std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\n";
  s += "end_header\n";
  // Sized once and filled through a cursor: meshes of millions of triangles are common.
  size_t header = s.size(), vertex = 12 + (normals ? 12 : 0) + (colours ? 3 : 0);
  s.resize(header + m.positions.size() * vertex + m.triangles.size() * 13);
  char* out = s.data() + header;
  auto emit = [&out](const void* p, size_t n) { std::memcpy(out, p, n), out += n; };
  for (size_t i = 0; i < m.positions.size(); ++i) {
    emit(m.positions[i].data(), 12);
    if (normals) emit(m.normals[i].data(), 12);
    if (colours)
      for (float v : m.colours[i]) *out++ = static_cast<char>(std::lround(std::fmin(std::fmax(v, 0.0f), 1.0f) * 255));
  }
  for (const auto& t : m.triangles) {
    *out++ = 3;
    emit(t.data(), 12);
  }
  return s;
}

std::string obj(const Mesh& m) {
  bool normals = m.normals.size() == m.positions.size() && !m.positions.empty();
  std::string s = "# written by fvrml-run\n";
  char buf[128];
  for (const auto& p : m.positions) {
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    s += buf;
  }
  if (normals)
    for (const auto& n : m.normals) {
      std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", n[0], n[1], n[2]);
      s += buf;
    }
  for (const auto& t : m.triangles) {
    if (normals)
      std::snprintf(buf, sizeof buf, "f %u//%u %u//%u %u//%u\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
    else
      std::snprintf(buf, sizeof buf, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
    s += buf;
  }
  for (const auto& l : m.polylines) {
    s += "l";
    for (uint32_t v : l) s += " " + std::to_string(v + 1);
    s += "\n";
  }
  return s;
}

std::string stl(const Mesh& m) {
  std::string s(80, '\0');
  std::memcpy(s.data(), "binary STL written by fvrml-run", 31);
  put(s, static_cast<uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    float n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                  (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                  (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (float v : n) put(s, len > 0 ? v / len : 0.0f);
    for (const Vec3* p : {&a, &b, &c})
      for (float v : *p) put(s, v);
    put(s, static_cast<uint16_t>(0));
  }
  return s;
}

}  // namespace

std::string encode_mesh(const Mesh& m, MeshFormat f) {
  switch (f) {
    case MeshFormat::Ply: return ply(m);
    case MeshFormat::Obj: return obj(m);
    case MeshFormat::Stl: return stl(m);
    case MeshFormat::Glb: return encode_glb(m);
  }
  return "";
}

bool write_mesh(const Mesh& m, MeshFormat f, const std::string& path, std::string& error) {
  return support::write_file_atomic(path, encode_mesh(m, f), error);
}

}  // namespace fscript::mesh
