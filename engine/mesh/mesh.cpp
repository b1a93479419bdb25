// Mesh helpers and the topology checks the tests and fvrml-meshdiff use.
#include "engine/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace fscript::mesh {

// Per-shape colours survive a merge: when only one side has vertex colours, or the two materials
// differ, each side without colours gets its material's diffuse colour on every vertex. The first
// material stays the merged mesh's.
void Mesh::append(const Mesh& o) {
  if (positions.empty() && triangles.empty() && polylines.empty()) {
    *this = o;
    return;
  }
  uint32_t base = static_cast<uint32_t>(positions.size());
  size_t n = positions.size(), on = o.positions.size();
  bool mine = colours.size() == n && n > 0, theirs = o.colours.size() == on && on > 0;
  bool coloured = mine || theirs || material != o.material;
  if (coloured && !mine) colours.assign(n, material.value_or(Material{}).diffuse);
  if (coloured) {
    if (theirs) colours.insert(colours.end(), o.colours.begin(), o.colours.end());
    else colours.insert(colours.end(), on, o.material.value_or(Material{}).diffuse);
  } else {
    colours.clear();
  }
  // Normals stay where every part with faces has them: a part of lines alone (a scene's axes
  // beside its shapes) needs none, and gets zeros rather than taking the shapes' away.
  bool my_normals = normals.size() == n || triangles.empty(),
       their_normals = o.normals.size() == on || o.triangles.empty();
  if (my_normals && their_normals && (normals.size() == n || o.normals.size() == on) && n + on > 0) {
    normals.resize(n, Vec3{0, 0, 0});
    if (o.normals.size() == on) normals.insert(normals.end(), o.normals.begin(), o.normals.end());
    else normals.insert(normals.end(), on, Vec3{0, 0, 0});
  } else {
    normals.clear();
  }
  if (!split_from.empty() || !o.split_from.empty()) {
    for (uint32_t i = static_cast<uint32_t>(split_from.size()); i < n; ++i) split_from.push_back(i);
    for (size_t i = 0; i < on; ++i)
      split_from.push_back(static_cast<uint32_t>(n) +
                           (i < o.split_from.size() ? o.split_from[i] : static_cast<uint32_t>(i)));
  }
  if (params.size() == n && o.params.size() == on) params.insert(params.end(), o.params.begin(), o.params.end());
  else params.clear();
  positions.insert(positions.end(), o.positions.begin(), o.positions.end());
  triangles.reserve(triangles.size() + o.triangles.size());
  for (auto t : o.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  for (const auto& l : o.polylines) {
    polylines.emplace_back();
    for (uint32_t i : l) polylines.back().push_back(i + base);
  }
}

namespace {

// Each vertex as the vertex it was split from (Mesh::split_from), or itself.
std::vector<uint32_t> welded(const Mesh& m) {
  std::vector<uint32_t> out(m.positions.size());
  for (uint32_t i = 0; i < out.size(); ++i)
    out[i] = i < m.split_from.size() && m.split_from[i] < out.size() ? m.split_from[i] : i;
  return out;
}

// Connected components (through shared vertices) and, per component, its signed volume.
void components(const Mesh& m, const std::vector<std::array<uint32_t, 3>>& tris, size_t vertices, Topology& t) {
  std::vector<uint32_t> parent(vertices);
  for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& tri : tris) parent[find(tri[1])] = find(tri[0]), parent[find(tri[2])] = find(tri[0]);
  std::map<uint32_t, double> volume;
  for (const auto& tri : tris) {
    const Vec3 &a = m.positions[tri[0]], &b = m.positions[tri[1]], &c = m.positions[tri[2]];
    double det = double(a[0]) * (double(b[1]) * c[2] - double(b[2]) * c[1]) -
        double(a[1]) * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
        double(a[2]) * (double(b[0]) * c[1] - double(b[1]) * c[0]);
    volume[find(tri[0])] += det / 6;
  }
  t.components = volume.size();
  for (const auto& [root, v] : volume) t.inverted_components += v < 0;
}

}  // namespace

Topology topology(const Mesh& mesh) {
  // The welded mesh: positions stay, indices name each position's first vertex.
  std::vector<uint32_t> canon = welded(mesh);
  Mesh m;
  m.positions = mesh.positions;
  m.triangles.reserve(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) m.triangles.push_back({canon[tri[0]], canon[tri[1]], canon[tri[2]]});
  Topology t;
  // Every directed edge and every undirected one, sorted (runs count the triangles using each):
  // sorting beats hashing several times on the millions of edges of a dense reference mesh.
  std::vector<uint64_t> directed, undirected;
  auto key = [](uint32_t a, uint32_t b) { return (static_cast<uint64_t>(a) << 32) | b; };
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> fans(m.positions.size());
  directed.reserve(3 * m.triangles.size()), undirected.reserve(3 * m.triangles.size());
  for (const auto& tri : m.triangles) {
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      ++t.degenerate_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      uint32_t a = tri[k], b = tri[(k + 1) % 3];
      directed.push_back(key(a, b)), undirected.push_back(key(std::min(a, b), std::max(a, b)));
      fans[tri[k]].push_back({tri[(k + 1) % 3], tri[(k + 2) % 3]});
    }
  }
  std::sort(directed.begin(), directed.end()), std::sort(undirected.begin(), undirected.end());
  t.watertight = true;
  t.oriented = true;
  size_t edges = 0;
  for (size_t i = 0, j; i < undirected.size(); i = j, ++edges) {
    for (j = i; j < undirected.size() && undirected[j] == undirected[i]; ++j) {}
    if (j - i != 2) t.watertight = false;
    if (j - i == 1) ++t.boundary_edges;
  }
  for (size_t i = 0; i < directed.size(); ++i) {
    uint64_t e = directed[i];
    if (i + 1 < directed.size() && directed[i + 1] == e) t.oriented = false;
    uint32_t a = static_cast<uint32_t>(e >> 32), b = static_cast<uint32_t>(e);
    if (!std::binary_search(directed.begin(), directed.end(), key(b, a))) t.oriented = false;
  }
  // 2-manifold vertices: the triangles around each vertex form a single fan (walk the ring).
  t.manifold = true;
  size_t used_vertices = 0;
  for (const auto& fan : fans) {
    if (fan.empty()) continue;
    ++used_vertices;
    std::map<uint32_t, uint32_t> next;
    for (auto [b, c] : fan) next[b] = c;
    uint32_t start = fan[0].first, cur = start;
    size_t steps = 0;
    do {
      auto it = next.find(cur);
      if (it == next.end()) break;
      cur = it->second;
      ++steps;
    } while (cur != start && steps <= fan.size());
    if (steps != fan.size() || cur != start) t.manifold = false;
  }
  size_t faces = m.triangles.size() - t.degenerate_triangles;
  t.euler = static_cast<long>(used_vertices) - static_cast<long>(edges) + static_cast<long>(faces);
  std::vector<std::array<uint32_t, 3>> proper;
  for (const auto& tri : m.triangles)
    if (tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]) proper.push_back(tri);
  components(m, proper, m.positions.size(), t);
  return t;
}

std::vector<Vec3> crease_normals(const Mesh& m, double crease) {
  const size_t nt = m.triangles.size();
  std::vector<std::array<double, 3>> face(nt);  // area-weighted
  std::vector<double> length(nt);
  for (size_t t = 0; t < nt; ++t) {
    const Vec3 &a = m.positions[m.triangles[t][0]], &b = m.positions[m.triangles[t][1]],
               &c = m.positions[m.triangles[t][2]];
    double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    face[t] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    length[t] = std::sqrt(face[t][0] * face[t][0] + face[t][1] * face[t][1] + face[t][2] * face[t][2]);
  }
  // The triangles around each vertex, as one array cut by offsets.
  std::vector<uint32_t> start(m.positions.size() + 1, 0), around(3 * nt);
  for (const auto& t : m.triangles)
    for (uint32_t v : t) ++start[v + 1];
  for (size_t v = 0; v < m.positions.size(); ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t t = 0; t < nt; ++t)
    for (uint32_t v : m.triangles[t]) around[fill[v]++] = static_cast<uint32_t>(t);
  const double cos_crease = std::cos(crease);
  std::vector<Vec3> out(3 * nt);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t v = m.triangles[t][static_cast<size_t>(k)];
      double n[3] = {0, 0, 0};
      for (uint32_t q = start[v]; q < start[v + 1]; ++q) {
        uint32_t o = around[q];
        double d = face[t][0] * face[o][0] + face[t][1] * face[o][1] + face[t][2] * face[o][2];
        if (o != t && !(d >= cos_crease * length[t] * length[o])) continue;  // across a crease
        for (int a = 0; a < 3; ++a) n[a] += face[o][a];
      }
      double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int a = 0; a < 3; ++a)
        out[3 * t + static_cast<size_t>(k)][static_cast<size_t>(a)] = len > 0 ? float(n[a] / len) : 0.0f;
    }
  return out;
}

}  // namespace fscript::mesh
