// Compact frames and the progressive frame cache.
#include "engine/mesh/frame_cache.h"

#include <algorithm>
#include <cmath>

#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

void put_varint(std::vector<uint8_t>& out, int64_t delta) {
  uint64_t z = (static_cast<uint64_t>(delta) << 1) ^ static_cast<uint64_t>(delta >> 63);  // zig-zag
  while (z >= 0x80) {
    out.push_back(static_cast<uint8_t>(z | 0x80));
    z >>= 7;
  }
  out.push_back(static_cast<uint8_t>(z));
}

int64_t get_varint(const std::vector<uint8_t>& in, size_t& at) {
  uint64_t z = 0;
  for (int shift = 0; at < in.size() && shift < 64; shift += 7) {
    uint8_t b = in[at++];
    z |= static_cast<uint64_t>(b & 0x7F) << shift;
    if (!(b & 0x80)) break;
  }
  return static_cast<int64_t>(z >> 1) ^ -static_cast<int64_t>(z & 1);
}

uint16_t unorm16(float v) { return static_cast<uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f)); }

// Octahedral encoding of a unit vector: the sphere folded onto the square [-1, 1]^2.
std::array<uint16_t, 2> encode_normal(const Vec3& n) {
  float s = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  if (!(s > 0) || !std::isfinite(s)) return {32768, 32768};
  float x = n[0] / s, y = n[1] / s;
  if (n[2] < 0) {
    float fx = (1 - std::fabs(y)) * (x >= 0 ? 1.0f : -1.0f), fy = (1 - std::fabs(x)) * (y >= 0 ? 1.0f : -1.0f);
    x = fx, y = fy;
  }
  return {unorm16(0.5f * x + 0.5f), unorm16(0.5f * y + 0.5f)};
}

Vec3 decode_normal(uint16_t a, uint16_t b) {
  float x = a / 65535.0f * 2 - 1, y = b / 65535.0f * 2 - 1, z = 1 - std::fabs(x) - std::fabs(y);
  if (z < 0) {
    float fx = (1 - std::fabs(y)) * (x >= 0 ? 1.0f : -1.0f), fy = (1 - std::fabs(x)) * (y >= 0 ? 1.0f : -1.0f);
    x = fx, y = fy;
  }
  float len = std::sqrt(x * x + y * y + z * z);
  return {x / len, y / len, z / len};
}

}  // namespace

size_t CompactMesh::bytes() const {
  return sizeof(CompactMesh) + positions.size() * 2 + normals.size() * 2 + colours.size() + indices.size() +
      polyline_sizes.size() * 4;
}

CompactMesh compress(const Mesh& m) {
  CompactMesh c;
  c.vertices = static_cast<uint32_t>(m.positions.size());
  c.triangles = static_cast<uint32_t>(m.triangles.size());
  c.material = m.material;
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  if (!m.positions.empty()) lo = hi = m.positions[0];
  for (const auto& p : m.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  for (int a = 0; a < 3; ++a) c.origin[a] = lo[a], c.step[a] = (hi[a] - lo[a]) / 65535.0f;
  c.positions.reserve(3 * m.positions.size());
  for (const auto& p : m.positions)
    for (int a = 0; a < 3; ++a) c.positions.push_back(c.step[a] > 0 ? unorm16((p[a] - lo[a]) / (hi[a] - lo[a])) : 0);
  if (m.normals.size() == m.positions.size())
    for (const auto& n : m.normals) {
      auto e = encode_normal(n);
      c.normals.insert(c.normals.end(), e.begin(), e.end());
    }
  if (m.colours.size() == m.positions.size())
    for (const auto& col : m.colours)
      for (float v : col) c.colours.push_back(static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)));
  int64_t last = 0;
  auto index = [&](uint32_t v) {
    put_varint(c.indices, static_cast<int64_t>(v) - last);
    last = v;
  };
  for (const auto& t : m.triangles)
    for (uint32_t v : t) index(v);
  for (const auto& l : m.polylines) {
    c.polyline_sizes.push_back(static_cast<uint32_t>(l.size()));
    for (uint32_t v : l) index(v);
  }
  return c;
}

Mesh expand(const CompactMesh& c) {
  Mesh m;
  m.material = c.material;
  m.positions.resize(c.vertices);
  for (size_t i = 0; i < c.vertices; ++i)
    for (int a = 0; a < 3; ++a) m.positions[i][a] = c.origin[a] + c.positions[3 * i + a] * c.step[a];
  if (!c.normals.empty()) {
    m.normals.resize(c.vertices);
    for (size_t i = 0; i < c.vertices; ++i) m.normals[i] = decode_normal(c.normals[2 * i], c.normals[2 * i + 1]);
  }
  if (!c.colours.empty()) {
    m.colours.resize(c.vertices);
    for (size_t i = 0; i < c.vertices; ++i)
      for (int a = 0; a < 3; ++a) m.colours[i][a] = c.colours[3 * i + a] / 255.0f;
  }
  size_t at = 0;
  int64_t last = 0;
  auto index = [&] { return static_cast<uint32_t>(last += get_varint(c.indices, at)); };
  m.triangles.resize(c.triangles);
  for (auto& t : m.triangles)
    for (uint32_t& v : t) v = index();
  for (uint32_t n : c.polyline_sizes) {
    m.polylines.emplace_back(n);
    for (uint32_t& v : m.polylines.back()) v = index();
  }
  return m;
}

bool FrameCache::make(size_t i, backends::RuntimeError& err) {
  Mesh m;
  if (!make_(i, m, err)) return false;
  CompactMesh c = compress(m);
  std::lock_guard<std::mutex> lock(mutex_);
  slots_[i] = std::move(c);
  return true;
}

bool FrameCache::get(size_t i, Mesh& out, backends::RuntimeError& err) {
  if (i >= frames_) {
    err.message = "frame " + std::to_string(i) + " is outside the animation's " + std::to_string(frames_) + " frames";
    return false;
  }
  bool hit = has(i);
  if (!hit && !make(i, err)) return false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    out = expand(*slots_[i]);
  }
  if (hit)
    for (size_t k = 1; k < frames_; ++k)
      if (size_t next = (i + k) % frames_; !has(next)) return make(next, err);
  return true;
}

std::vector<size_t> FrameCache::progressive_order(size_t n) {
  size_t bits = 0;
  while ((size_t{1} << bits) < n) ++bits;
  std::vector<size_t> order;
  std::vector<char> taken(n, 0);
  for (size_t p = 0; p < (size_t{1} << bits); ++p) {
    size_t r = 0;
    for (size_t b = 0; b < bits; ++b) r |= ((p >> b) & 1) << (bits - 1 - b);
    size_t i = (r * n) >> bits;  // the bit-reversed position scaled to n (collisions skipped)
    if (!taken[i]) taken[i] = 1, order.push_back(i);
  }
  for (size_t i = 0; i < n; ++i)
    if (!taken[i]) order.push_back(i);
  return order;
}

bool FrameCache::fill(int threads, backends::RuntimeError& err, const std::function<void(size_t)>& made) {
  std::vector<size_t> missing;
  for (size_t i : progressive_order(frames_))
    if (!has(i)) missing.push_back(i);
  int n = std::max(1, std::min<int>(threads, static_cast<int>(missing.size())));
  std::mutex report;
  return support::run_parts(
      n,
      [&](int w, backends::RuntimeError& e) {  // frames w, w + n, ... of the order
        for (size_t k = static_cast<size_t>(w); k < missing.size(); k += static_cast<size_t>(n)) {
          if (!make(missing[k], e)) return false;
          if (made) {
            std::lock_guard<std::mutex> hold(report);
            made(cached());
          }
        }
        return true;
      },
      err);
}

void FrameCache::put(size_t i, CompactMesh c) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (i < frames_) slots_[i] = std::move(c);
}

std::optional<CompactMesh> FrameCache::compact(size_t i) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return i < frames_ ? slots_[i] : std::nullopt;
}

bool FrameCache::peek(size_t i, Mesh& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (i >= frames_ || !slots_[i]) return false;
  out = expand(*slots_[i]);
  return true;
}

bool FrameCache::has(size_t i) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return i < frames_ && slots_[i].has_value();
}

size_t FrameCache::cached() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<size_t>(std::count_if(slots_.begin(), slots_.end(), [](const auto& s) { return s.has_value(); }));
}

size_t FrameCache::bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t b = 0;
  for (const auto& s : slots_)
    if (s) b += s->bytes();
  return b;
}

bool FrameCache::all_same() const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& s : slots_)
    if (!s || !(*s == *slots_[0])) return false;
  return true;
}

size_t FrameCache::triangles() const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t t = 0;
  for (const auto& s : slots_)
    if (s) t += s->triangles;
  return t;
}

}  // namespace fscript::mesh
