// Mesh writers.
#include "engine/mesh/mesh_io.h"

#include "runtime/support/files.h"
#include "engine/mesh/gltf.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

namespace fscript::mesh {
namespace {

// Bytes out: into a string (encode_mesh) or into a file through a fixed buffer (write_mesh), so
// writing a mesh of millions of triangles never holds its whole file in memory.
class Out {
 public:
  explicit Out(std::string& s) : s_(&s) {}
  explicit Out(std::FILE* f) : f_(f), buf_(kChunk) {}
  void put(const void* p, size_t n) {
    if (n == 0) return;  // an empty mesh's arrays have no data (memcpy from null is undefined)
    if (s_) return void(s_->append(static_cast<const char*>(p), n));
    if (used_ + n > buf_.size()) flush();
    if (n > buf_.size()) return void(ok_ = ok_ && std::fwrite(p, 1, n, f_) == n);
    std::memcpy(buf_.data() + used_, p, n);
    used_ += n;
  }
  void text(std::string_view t) { put(t.data(), t.size()); }
  template <class T>
  void value(T v) {
    put(&v, sizeof(T));
  }
  void reserve(size_t n) {
    if (s_) s_->reserve(s_->size() + n);
  }
  bool finish() {
    flush();
    return ok_;
  }

 private:
  static constexpr size_t kChunk = size_t{1} << 18;
  void flush() {
    if (f_ && used_) ok_ = ok_ && std::fwrite(buf_.data(), 1, used_, f_) == used_;
    used_ = 0;
  }
  std::string* s_ = nullptr;
  std::FILE* f_ = nullptr;
  std::vector<char> buf_;
  size_t used_ = 0;
  bool ok_ = true;
};

// The face records: a count of 3 and three 32-bit indices each, 13 bytes.
void ply_faces(const Mesh& m, Out& out) {
  constexpr size_t kFaces = 4096;
  char buf[kFaces * 13];
  for (size_t first = 0; first < m.triangles.size(); first += kFaces) {
    size_t n = std::min(kFaces, m.triangles.size() - first);
    for (size_t i = 0; i < n; ++i) {
      buf[13 * i] = 3;
      std::memcpy(buf + 13 * i + 1, m.triangles[first + i].data(), 12);
    }
    out.put(buf, 13 * n);
  }
}

void ply(const Mesh& m, Out& out) {
  bool normals = m.normals.size() == m.positions.size() && !m.positions.empty();
  bool colours = m.colours.size() == m.positions.size() && !m.positions.empty();
  std::string h = "ply\nformat binary_little_endian 1.0\ncomment written by fvrml-run\n";
  h += "element vertex " + std::to_string(m.positions.size()) + "\n";
  h += "property float x\nproperty float y\nproperty float z\n";
  if (normals) h += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colours) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  h += "element face " + std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\n";
  h += "end_header\n";
  size_t vertex = 12 + (normals ? 12 : 0) + (colours ? 3 : 0);
  out.reserve(h.size() + m.positions.size() * vertex + m.triangles.size() * 13);
  out.text(h);
  // Plain positions are the file's vertex records as they lie in memory; faces go through a local
  // buffer. A put per record was most of writing a mesh of a million triangles.
  static_assert(sizeof(Vec3) == 12, "a vertex record is three packed floats");
  if (!normals && !colours) {
    out.put(m.positions.data(), m.positions.size() * sizeof(m.positions[0]));
    ply_faces(m, out);
    return;
  }
  // Records with normals or colours are assembled a few thousand at a time, then put at once.
  constexpr size_t kVertices = 4096;
  std::vector<char> buf(kVertices * vertex);
  for (size_t first = 0; first < m.positions.size(); first += kVertices) {
    size_t n = std::min(kVertices, m.positions.size() - first);
    for (size_t q = 0; q < n; ++q) {
      char* v = buf.data() + q * vertex;
      size_t i = first + q;
      std::memcpy(v, m.positions[i].data(), 12);
      if (normals) std::memcpy(v + 12, m.normals[i].data(), 12);
      if (colours)
        for (size_t c = 0; c < 3; ++c)
          v[vertex - 3 + c] = static_cast<char>(std::lround(std::fmin(std::fmax(m.colours[i][c], 0.0f), 1.0f) * 255));
    }
    out.put(buf.data(), n * vertex);
  }
  ply_faces(m, out);
}

// OBJ names a corner's position and normal apart: a vertex split for its normals
// (Mesh::split_from) is written once, so the file keeps the surface's topology.
void obj(const Mesh& m, Out& out) {
  bool normals = m.normals.size() == m.positions.size() && !m.positions.empty();
  bool split = m.split_from.size() == m.positions.size();
  std::vector<uint32_t> at(m.positions.size());  // each vertex's position line, from 1
  uint32_t written = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) at[i] = !split || m.split_from[i] == i ? ++written : 0;
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!at[i]) at[i] = at[m.split_from[i] < i ? m.split_from[i] : i];
  out.text("# written by fvrml-run\n");
  char buf[128];
  auto line = [&](int n) { out.put(buf, static_cast<size_t>(n)); };
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!split || m.split_from[i] == i)
      line(std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", m.positions[i][0], m.positions[i][1],
                         m.positions[i][2]));
  if (normals)
    for (const auto& n : m.normals) line(std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", n[0], n[1], n[2]));
  for (const auto& t : m.triangles) {
    if (normals)
      line(std::snprintf(buf, sizeof buf, "f %u//%u %u//%u %u//%u\n", at[t[0]], t[0] + 1, at[t[1]], t[1] + 1, at[t[2]],
                         t[2] + 1));
    else line(std::snprintf(buf, sizeof buf, "f %u %u %u\n", at[t[0]], at[t[1]], at[t[2]]));
  }
  for (const auto& l : m.polylines) {
    std::string s = "l";
    for (uint32_t v : l) s += " " + std::to_string(at[v]);
    out.text(s + "\n");
  }
}

void stl(const Mesh& m, Out& out) {
  char head[80] = "binary STL written by fvrml-run";
  out.reserve(84 + 50 * m.triangles.size());
  out.put(head, sizeof head);
  out.value(static_cast<uint32_t>(m.triangles.size()));
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    float n[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                  (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                  (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    float r[12];
    for (int k = 0; k < 3; ++k) r[k] = len > 0 ? n[k] / len : 0.0f;
    for (int k = 0; k < 3; ++k) r[3 + k] = a[k], r[6 + k] = b[k], r[9 + k] = c[k];
    out.put(r, sizeof r);
    out.value(static_cast<uint16_t>(0));
  }
}

bool encode(const Mesh& m, MeshFormat f, Out& out) {
  switch (f) {
    case MeshFormat::Ply: ply(m, out); break;
    case MeshFormat::Obj: obj(m, out); break;
    case MeshFormat::Stl: stl(m, out); break;
    case MeshFormat::Glb: out.text(encode_glb(m)); break;
  }
  return out.finish();
}

}  // namespace

std::string encode_mesh(const Mesh& m, MeshFormat f) {
  std::string s;
  Out out(s);
  encode(m, f, out);
  return s;
}

bool write_mesh(const Mesh& m, MeshFormat f, const std::string& path, std::string& error) {
  return support::write_file_atomic(
      path,
      [&](std::FILE* file) {
        Out out(file);
        return encode(m, f, out);
      },
      error);
}

}  // namespace fscript::mesh
