// Mesh readers. Each reports the first problem with a position ("line N" or "byte N").
#include "engine/mesh/mesh_read.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>

#include "runtime/support/files.h"

namespace fscript::mesh {
namespace {

bool ends_with(const std::string& s, const char* e) {
  size_t n = std::strlen(e);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != e[i]) return false;
  return true;
}

struct Prop {
  std::string name, type, list_count_type;
  bool list = false;
};
struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Prop> props;
};

size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

class BinaryReader {
 public:
  BinaryReader(const std::string& b, size_t pos, bool big) : b_(b), pos_(pos), big_(big) {}
  bool read(const std::string& type, double& out) {
    size_t n = type_size(type);
    if (n == 0 || pos_ + n > b_.size()) return false;
    unsigned char buf[8];
    std::memcpy(buf, b_.data() + pos_, n);
    if (big_) std::reverse(buf, buf + n);
    pos_ += n;
    if (type == "float" || type == "float32") {
      float f;
      std::memcpy(&f, buf, 4);
      out = f;
    } else if (type == "double" || type == "float64") {
      double d;
      std::memcpy(&d, buf, 8);
      out = d;
    } else if (type == "char" || type == "int8") out = static_cast<int8_t>(buf[0]);
    else if (type == "uchar" || type == "uint8") out = buf[0];
    else if (type == "short" || type == "int16") {
      int16_t v;
      std::memcpy(&v, buf, 2);
      out = v;
    } else if (type == "ushort" || type == "uint16") {
      uint16_t v;
      std::memcpy(&v, buf, 2);
      out = v;
    } else if (type == "int" || type == "int32") {
      int32_t v;
      std::memcpy(&v, buf, 4);
      out = v;
    } else {
      uint32_t v;
      std::memcpy(&v, buf, 4);
      out = v;
    }
    return true;
  }
  size_t pos() const { return pos_; }

 private:
  const std::string& b_;
  size_t pos_;
  bool big_;
};

bool parse_ply(const std::string& bytes, Mesh& m, std::string& error) {
  size_t end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || end == std::string::npos) {
    error = "not a PLY file (no 'ply' ... 'end_header')";
    return false;
  }
  std::istringstream head(bytes.substr(0, end));
  std::string line, format;
  std::vector<Element> elems;
  while (std::getline(head, line)) {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "format") ls >> format;
    else if (w == "element") {
      elems.emplace_back();
      ls >> elems.back().name >> elems.back().count;
    } else if (w == "property" && !elems.empty()) {
      Prop p;
      ls >> p.type;
      if (p.type == "list") {
        p.list = true;
        ls >> p.list_count_type >> p.type;
      }
      ls >> p.name;
      elems.back().props.push_back(p);
    }
  }
  size_t data = bytes.find('\n', end);
  if (data == std::string::npos) {
    error = "PLY header not terminated";
    return false;
  }
  ++data;
  bool ascii = format == "ascii";
  std::istringstream text(ascii ? bytes.substr(data) : std::string());
  BinaryReader bin(bytes, data, format == "binary_big_endian");
  auto next = [&](const std::string& type, double& v) {
    return ascii ? static_cast<bool>(text >> v) : bin.read(type, v);
  };
  bool normals = false;
  for (const auto& e : elems)
    for (const auto& pr : e.props) normals |= e.name == "vertex" && pr.name == "nx";
  for (const auto& e : elems) {
    for (size_t i = 0; i < e.count; ++i) {
      Vec3 p{0, 0, 0}, n{0, 0, 0};
      std::vector<uint32_t> face;
      for (const auto& pr : e.props) {
        double v;
        if (pr.list) {
          double n;
          if (!next(pr.list_count_type, n) || n < 0 || n > 1000) {
            error = "PLY: bad list in element '" + e.name + "'";
            return false;
          }
          for (int k = 0; k < static_cast<int>(n); ++k) {
            if (!next(pr.type, v)) {
              error = "PLY: truncated data";
              return false;
            }
            face.push_back(static_cast<uint32_t>(v));
          }
          continue;
        }
        if (!next(pr.type, v)) {
          error = "PLY: truncated data in element '" + e.name + "'";
          return false;
        }
        if (pr.name == "x") p[0] = static_cast<float>(v);
        if (pr.name == "y") p[1] = static_cast<float>(v);
        if (pr.name == "z") p[2] = static_cast<float>(v);
        if (pr.name == "nx" || pr.name == "ny" || pr.name == "nz")
          n[static_cast<size_t>(pr.name[1] - 'x')] = static_cast<float>(v);
      }
      if (e.name == "vertex") m.positions.push_back(p);
      if (e.name == "vertex" && normals) m.normals.push_back(n);
      if (e.name == "face")
        for (size_t k = 1; k + 1 < face.size(); ++k) m.triangles.push_back({face[0], face[k], face[k + 1]});
    }
  }
  return true;
}

// Normals (`vn`, named by each corner's `v//vn`) become the normals of the corners' vertices.
bool parse_obj(const std::string& bytes, Mesh& m, std::string& error) {
  std::istringstream in(bytes);
  std::string line;
  std::vector<Vec3> vn;
  std::vector<std::pair<uint32_t, long>> corner_normals;
  for (size_t ln = 1; std::getline(in, line); ++ln) {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "v") {
      Vec3 p;
      if (!(ls >> p[0] >> p[1] >> p[2])) {
        error = "OBJ line " + std::to_string(ln) + ": a vertex needs three numbers";
        return false;
      }
      m.positions.push_back(p);
    } else if (w == "vn") {
      Vec3 n;
      if (!(ls >> n[0] >> n[1] >> n[2])) {
        error = "OBJ line " + std::to_string(ln) + ": a normal needs three numbers";
        return false;
      }
      vn.push_back(n);
    } else if (w == "f") {
      std::vector<uint32_t> f;
      std::string tok;
      while (ls >> tok) {
        long idx = std::strtol(tok.c_str(), nullptr, 10);
        if (idx < 0) idx = static_cast<long>(m.positions.size()) + idx + 1;
        if (idx <= 0) {
          error = "OBJ line " + std::to_string(ln) + ": bad vertex index '" + tok + "'";
          return false;
        }
        f.push_back(static_cast<uint32_t>(idx - 1));
        if (size_t slashes = tok.find("//"); slashes != std::string::npos) {
          long n = std::strtol(tok.c_str() + slashes + 2, nullptr, 10);
          corner_normals.push_back({static_cast<uint32_t>(idx - 1), n < 0 ? static_cast<long>(vn.size()) + n + 1 : n});
        }
      }
      for (size_t k = 1; k + 1 < f.size(); ++k) m.triangles.push_back({f[0], f[k], f[k + 1]});
    }
  }
  if (corner_normals.empty()) return true;
  m.normals.assign(m.positions.size(), Vec3{0, 0, 0});
  for (auto [v, n] : corner_normals) {
    if (n <= 0 || static_cast<size_t>(n) > vn.size() || v >= m.positions.size()) {
      error = "OBJ: a face names normal " + std::to_string(n) + " of " + std::to_string(vn.size());
      return false;
    }
    m.normals[v] = vn[static_cast<size_t>(n - 1)];
  }
  return true;
}

// STL stores each corner separately: corners at the same position become one vertex.
void add_stl_triangle(Mesh& m, std::map<std::array<float, 3>, uint32_t>& index, const Vec3 (&c)[3]) {
  std::array<uint32_t, 3> t;
  for (int k = 0; k < 3; ++k) {
    auto [it, fresh] = index.try_emplace(c[k], static_cast<uint32_t>(m.positions.size()));
    if (fresh) m.positions.push_back(c[k]);
    t[k] = it->second;
  }
  m.triangles.push_back(t);
}

bool parse_stl(const std::string& bytes, Mesh& m, std::string& error) {
  std::map<std::array<float, 3>, uint32_t> index;
  if (bytes.size() >= 84) {
    uint32_t n;
    std::memcpy(&n, bytes.data() + 80, 4);
    if (84 + static_cast<size_t>(n) * 50 == bytes.size()) {
      for (uint32_t i = 0; i < n; ++i) {
        Vec3 c[3];
        for (int k = 0; k < 3; ++k) std::memcpy(c[k].data(), bytes.data() + 84 + i * 50 + 12 + k * 12, 12);
        add_stl_triangle(m, index, c);
      }
      return true;
    }
  }
  if (bytes.rfind("solid", 0) != 0) {
    error = "not an STL file (neither binary of the right size nor ascii 'solid')";
    return false;
  }
  std::istringstream in(bytes);
  std::string w;
  Vec3 c[3];
  int k = 0;
  while (in >> w)
    if (w == "vertex") {
      if (!(in >> c[k][0] >> c[k][1] >> c[k][2])) {
        error = "STL: a vertex needs three numbers";
        return false;
      }
      if (++k == 3) {
        add_stl_triangle(m, index, c);
        k = 0;
      }
    }
  return true;
}

}  // namespace

bool parse_mesh(const std::string& bytes, const std::string& name, Mesh& out, std::string& error) {
  out = Mesh{};
  bool ok = ends_with(name, ".ply") ? parse_ply(bytes, out, error)
      : ends_with(name, ".obj")     ? parse_obj(bytes, out, error)
      : ends_with(name, ".stl")     ? parse_stl(bytes, out, error)
                                    : (error = "unknown mesh format (use .ply, .obj or .stl)", false);
  if (!ok) return false;
  for (const auto& t : out.triangles)
    for (uint32_t v : t)
      if (v >= out.positions.size()) {
        error = "a face refers to vertex " + std::to_string(v) + " of " + std::to_string(out.positions.size());
        return false;
      }
  return true;
}

bool read_mesh(const std::string& path, Mesh& out, std::string& error) {
  std::string bytes;
  if (!support::read_file(path, bytes, error)) {
    error = "cannot read the file: " + error;
    return false;
  }
  return parse_mesh(bytes, path, out, error);
}

}  // namespace fscript::mesh
