#pragma once
// The frame cache of animated shapes (the paper's section on caching): frames are stored compactly
// (positions quantised to 16 bits per axis over the frame's bounding box, normals octahedral in
// 2 x 16 bits, colours in 8 bits per channel, indices as variable-length deltas) and filled
// progressively: asking for a frame that is cached also makes the next missing one.
#include <array>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "backends/backend.h"
#include "engine/mesh/mesh.h"

namespace fscript::mesh {

// A mesh in about 40% of the bytes of `Mesh`; expand() gives it back within the quantisation step
// (the bounding box / 65535 per axis; normals within 1e-4 rad; colours within 1/510).
struct CompactMesh {
  std::array<float, 3> origin{}, step{};  // position = origin + q * step
  std::vector<uint16_t> positions;        // 3 per vertex
  std::vector<uint16_t> normals;          // 2 per vertex (octahedral), or empty
  std::vector<uint8_t> colours;           // 3 per vertex, or empty
  std::vector<uint8_t> indices;           // triangles, then polylines: zig-zag varint deltas
  uint32_t triangles = 0, vertices = 0;
  std::vector<uint32_t> polyline_sizes;
  std::optional<Material> material;

  size_t bytes() const;
  bool operator==(const CompactMesh&) const = default;
};

CompactMesh compress(const Mesh& m);
Mesh expand(const CompactMesh& c);

// Frames 0 .. n-1 of one animation, made on demand by `make(i, mesh, err)`.
class FrameCache {
 public:
  // 0 .. n-1 coarse to fine: 0, n/2, n/4, 3n/4, ... (bit-reversed), each index once.
  static std::vector<size_t> progressive_order(size_t n);

  using Maker = std::function<bool(size_t frame, Mesh& out, backends::RuntimeError& err)>;
  FrameCache(size_t frames, Maker make) : frames_(frames), make_(std::move(make)), slots_(frames) {}

  // The mesh of frame i: made and cached when missing; when it was cached, the next missing frame
  // is made as well, so repeated playback fills the cache progressively.
  bool get(size_t i, Mesh& out, backends::RuntimeError& err);
  // Makes every missing frame, `threads` frames at a time, coarse to fine in time (the order of
  // progressive_order), so the frames made so far always span the cycle. `made(cached)`, when
  // given, is called after each frame is stored, one call at a time.
  bool fill(int threads, backends::RuntimeError& err, const std::function<void(size_t cached)>& made = {});

  // A frame made elsewhere (a preview's meshes of the last run), and a cached frame as stored.
  void put(size_t i, CompactMesh c);
  std::optional<CompactMesh> compact(size_t i) const;

  // A cached frame, expanded; false when frame i is not cached (nothing is made).
  bool peek(size_t i, Mesh& out) const;

  size_t size() const { return frames_; }
  size_t cached() const;
  bool has(size_t i) const;
  size_t bytes() const;      // of the compact frames
  size_t triangles() const;  // over the cached frames
  bool all_same() const;     // every frame cached and identical to the first (nothing moves)

 private:
  bool make(size_t i, backends::RuntimeError& err);

  size_t frames_;
  Maker make_;
  std::vector<std::optional<CompactMesh>> slots_;
  mutable std::mutex mutex_;
};

}  // namespace fscript::mesh
