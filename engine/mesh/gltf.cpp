// GLB writer: a JSON chunk (nlohmann-json) and a BIN chunk, both padded to 4 bytes.
#include "engine/mesh/gltf.h"

#include <algorithm>
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
  j["bufferViews"].push_back(
      {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}, {"target", kArrayBuffer}});
  nlohmann::json acc = {
      {"bufferView", j["bufferViews"].size() - 1}, {"componentType", kFloat}, {"count", data.size()}, {"type", "VEC3"}};
  if (with_bounds) acc["min"] = lo, acc["max"] = hi;
  j["accessors"].push_back(acc);
  return static_cast<int>(j["accessors"].size()) - 1;
}

// A material for the mesh: white under per-vertex colours (COLOR_0 multiplies the base colour),
// else the mesh's diffuse colour; transparency as alpha.
int add_material(const Mesh& m, nlohmann::json& j) {
  Material mat = m.material.value_or(Material{});
  bool coloured = m.colours.size() == m.positions.size() && !m.positions.empty();
  Vec3 base = coloured ? Vec3{1, 1, 1} : mat.diffuse;
  float alpha = std::clamp(1.0f - mat.transparency, 0.0f, 1.0f);
  nlohmann::json pbr = {{"baseColorFactor", {base[0], base[1], base[2], alpha}},
                        {"metallicFactor", 0.0},
                        {"roughnessFactor", std::clamp(1.0f - mat.shininess, 0.0f, 1.0f)}};
  nlohmann::json out = {{"pbrMetallicRoughness", pbr}, {"doubleSided", true}};
  if (mat.emissive != Vec3{0, 0, 0}) out["emissiveFactor"] = {mat.emissive[0], mat.emissive[1], mat.emissive[2]};
  if (alpha < 1) out["alphaMode"] = "BLEND";
  j["materials"].push_back(out);
  return static_cast<int>(j["materials"].size()) - 1;
}

// The triangles (or the polylines) of `m` with only the vertices they use, renumbered.
Mesh part(const Mesh& m, bool lines) {
  Mesh out;
  out.material = m.material;
  std::vector<uint32_t> at(m.positions.size(), ~uint32_t{0});
  auto use = [&](uint32_t v) {
    if (at[v] == ~uint32_t{0}) {
      at[v] = static_cast<uint32_t>(out.positions.size());
      out.positions.push_back(m.positions[v]);
      if (m.normals.size() == m.positions.size()) out.normals.push_back(m.normals[v]);
      if (m.colours.size() == m.positions.size()) out.colours.push_back(m.colours[v]);
    }
    return at[v];
  };
  if (lines)
    for (const auto& l : m.polylines) {
      out.polylines.emplace_back();
      for (uint32_t v : l) out.polylines.back().push_back(use(v));
    }
  else
    for (const auto& t : m.triangles) out.triangles.push_back({use(t[0]), use(t[1]), use(t[2])});
  return out;
}

// One primitive of `m`: its triangles (mode 4), or its polylines as line segments (mode 1), with
// their attributes and material; null when it has none.
nlohmann::json add_primitive(const Mesh& m, bool lines, std::string& bin, nlohmann::json& j) {
  std::vector<uint32_t> index;
  if (lines) {
    for (const auto& l : m.polylines)
      for (size_t k = 0; k + 1 < l.size(); ++k) index.insert(index.end(), {l[k], l[k + 1]});
  } else {
    for (const auto& t : m.triangles) index.insert(index.end(), t.begin(), t.end());
  }
  if (m.positions.empty() || index.empty()) return nullptr;
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
  j["bufferViews"].push_back(
      {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}, {"target", kElementBuffer}});
  j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1},
                            {"componentType", kUint},
                            {"count", index.size()},
                            {"type", "SCALAR"}});
  int material = add_material(m, j);
  return {
      {"attributes", attrs}, {"indices", j["accessors"].size() - 1}, {"mode", lines ? 1 : 4}, {"material", material}};
}

// Appends the mesh: a primitive of its triangles and one of its lines (the standard geometry of a
// scene has both: shapes and axes); its index in "meshes", or -1 when empty.
int add_mesh(const Mesh& m, std::string& bin, nlohmann::json& j) {
  nlohmann::json primitives = nlohmann::json::array();
  bool both = !m.triangles.empty() && !m.polylines.empty();
  for (bool lines : {false, true}) {
    if ((lines ? m.polylines.empty() : m.triangles.empty())) continue;
    nlohmann::json p = both ? add_primitive(part(m, lines), lines, bin, j) : add_primitive(m, lines, bin, j);
    if (!p.is_null()) primitives.push_back(p);
  }
  if (primitives.empty()) return -1;
  j["meshes"].push_back({{"primitives", primitives}});
  return static_cast<int>(j["meshes"].size()) - 1;
}

// Plain floats (animation keys) as an accessor without a buffer-view target.
int float_accessor(const std::vector<float>& data, const char* type, bool with_bounds, std::string& bin,
                   nlohmann::json& j) {
  size_t offset = bin.size();
  for (float v : data) put(bin, v);
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}});
  size_t per = std::string(type) == "VEC3" ? 3 : 1;
  nlohmann::json acc = {{"bufferView", j["bufferViews"].size() - 1},
                        {"componentType", kFloat},
                        {"count", data.size() / per},
                        {"type", type}};
  if (with_bounds)
    acc["min"] = {*std::min_element(data.begin(), data.end())},
    acc["max"] = {*std::max_element(data.begin(), data.end())};
  j["accessors"].push_back(acc);
  return static_cast<int>(j["accessors"].size()) - 1;
}

// Frames as sibling nodes under one parent; a STEP animation of their scales shows frame k during
// [k T / N, (k + 1) T / N) (or from its given start to the next) and hides the others (scale 0). A
// last key at T repeats the first, so the animation lasts exactly one cycle.
void add_animation(const GltfAnimation& a, std::string& bin, nlohmann::json& j) {
  size_t n = a.frames.size();
  if (n == 0) return;
  nlohmann::json parent = {{"name", a.name.empty() ? "animation" : a.name}, {"children", nlohmann::json::array()}};
  std::vector<float> times;
  for (size_t k = 0; k <= n; ++k)
    times.push_back(static_cast<float>(a.starts.size() == n && k < n ? a.starts[k] : a.cycle_interval * k / n));
  int input = float_accessor(times, "SCALAR", true, bin, j);
  nlohmann::json samplers = nlohmann::json::array(), channels = nlohmann::json::array();
  for (size_t f = 0; f < n; ++f) {
    nlohmann::json node = {{"name", "frame " + std::to_string(f)}};
    if (int mesh = add_mesh(a.frames[f], bin, j); mesh >= 0) node["mesh"] = mesh;
    float shown = f == 0 ? 1.0f : 0.0f;
    node["scale"] = {shown, shown, shown};
    j["nodes"].push_back(node);
    size_t index = j["nodes"].size() - 1;
    parent["children"].push_back(index);
    std::vector<float> scales;
    for (size_t k = 0; k <= n; ++k) {
      float v = (k % n) == f ? 1.0f : 0.0f;
      scales.insert(scales.end(), {v, v, v});
    }
    samplers.push_back(
        {{"input", input}, {"output", float_accessor(scales, "VEC3", false, bin, j)}, {"interpolation", "STEP"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", index}, {"path", "scale"}}}});
  }
  j["nodes"].push_back(parent);
  j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  j["animations"].push_back({{"name", parent["name"]}, {"samplers", samplers}, {"channels", channels}});
}

}  // namespace

std::string encode_glb(const Mesh& m, const std::vector<GltfAnimation>& animations) {
  nlohmann::json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "fvrml-run"}};
  j["scene"] = 0;
  // Arrays of one element spelt out: nested braces of one element read as the element itself or
  // as an array of it depending on the compiler (GCC and Clang differ: CWG 1467).
  j["scenes"] = nlohmann::json::array({nlohmann::json::object({{"nodes", nlohmann::json::array({0})}})});
  j["nodes"] = nlohmann::json::array({nlohmann::json::object()});
  for (const char* k : {"bufferViews", "accessors", "meshes", "materials", "animations"})
    j[k] = nlohmann::json::array();
  std::string bin;
  if (int mesh = add_mesh(m, bin, j); mesh >= 0) j["nodes"][0]["mesh"] = mesh;
  for (const auto& a : animations) add_animation(a, bin, j);
  for (const char* k : {"bufferViews", "accessors", "meshes", "materials", "animations"})
    if (j[k].empty()) j.erase(k);
  if (!bin.empty()) j["buffers"] = nlohmann::json::array({nlohmann::json::object({{"byteLength", bin.size()}})});
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
