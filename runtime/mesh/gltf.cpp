// GLB writer: a JSON chunk (nlohmann-json) and a BIN chunk, both padded to 4 bytes.
#include "runtime/mesh/gltf.h"

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

namespace fscript::mesh {
namespace {

constexpr int kFloat = 5126, kUint = 5125, kArrayBuffer = 34962, kElementBuffer = 34963;

template <class T>
void put(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s.append(b, sizeof(T));
}

// Appends a vec3 attribute to `bin` and describes it (bufferView + accessor).
int vec3_attribute(const std::vector<Vec3>& data, bool with_bounds, std::string& bin, nlohmann::json& j) {
  size_t offset = bin.size();
  Vec3 lo = data.empty() ? Vec3{0, 0, 0} : data[0], hi = lo;
  for (const auto& v : data)
    for (int a = 0; a < 3; ++a) {
      put(bin, v[a]);
      lo[a] = std::fmin(lo[a], v[a]);
      hi[a] = std::fmax(hi[a], v[a]);
    }
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset},
                              {"target", kArrayBuffer}});
  nlohmann::json acc = {{"bufferView", j["bufferViews"].size() - 1}, {"componentType", kFloat},
                        {"count", data.size()}, {"type", "VEC3"}};
  if (with_bounds) acc["min"] = lo, acc["max"] = hi;
  j["accessors"].push_back(acc);
  return static_cast<int>(j["accessors"].size()) - 1;
}

}  // namespace

std::string encode_glb(const Mesh& m) {
  nlohmann::json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "fvrml-run"}};
  j["scene"] = 0;
  j["scenes"] = {{{"nodes", {0}}}};
  j["nodes"] = {nlohmann::json::object()};
  j["bufferViews"] = nlohmann::json::array();
  j["accessors"] = nlohmann::json::array();
  std::string bin;
  std::vector<uint32_t> index;
  bool lines = m.triangles.empty() && !m.polylines.empty();
  if (lines) {
    for (const auto& l : m.polylines)
      for (size_t k = 0; k + 1 < l.size(); ++k) index.insert(index.end(), {l[k], l[k + 1]});
  } else {
    for (const auto& t : m.triangles) index.insert(index.end(), t.begin(), t.end());
  }
  if (!m.positions.empty() && !index.empty()) {
    nlohmann::json attrs;
    attrs["POSITION"] = vec3_attribute(m.positions, true, bin, j);
    if (!lines && m.normals.size() == m.positions.size()) {
      std::vector<Vec3> unit = m.normals;
      for (auto& n : unit) {
        float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        n = len > 0 && std::isfinite(len) ? Vec3{n[0] / len, n[1] / len, n[2] / len} : Vec3{0, 0, 1};
      }
      attrs["NORMAL"] = vec3_attribute(unit, false, bin, j);
    }
    if (m.colours.size() == m.positions.size()) attrs["COLOR_0"] = vec3_attribute(m.colours, false, bin, j);
    size_t offset = bin.size();
    for (uint32_t i : index) put(bin, i);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset},
                                {"target", kElementBuffer}});
    j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1}, {"componentType", kUint},
                              {"count", index.size()}, {"type", "SCALAR"}});
    j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 1.0}}, {"metallicFactor", 0.0},
                                                 {"roughnessFactor", 0.8}}},
                       {"doubleSided", true}}};
    j["meshes"] = {{{"primitives", {{{"attributes", attrs}, {"indices", j["accessors"].size() - 1},
                                     {"mode", lines ? 1 : 4}, {"material", 0}}}}}};
    j["nodes"][0]["mesh"] = 0;
  }
  if (!bin.empty()) j["buffers"] = {{{"byteLength", bin.size()}}};
  else j.erase("bufferViews"), j.erase("accessors");
  std::string json = j.dump();
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out;
  put(out, uint32_t{0x46546C67});  // "glTF"
  put(out, uint32_t{2});
  put(out, static_cast<uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  put(out, static_cast<uint32_t>(json.size()));
  put(out, uint32_t{0x4E4F534A});  // "JSON"
  out += json;
  if (!bin.empty()) {
    put(out, static_cast<uint32_t>(bin.size()));
    put(out, uint32_t{0x004E4942});  // "BIN\0"
    out += bin;
  }
  return out;
}

}  // namespace fscript::mesh
