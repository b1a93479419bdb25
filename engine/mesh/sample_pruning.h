#pragma once
// Which parts of an implicit job's sample grid the surface may cross: an octree of interval bounds
// over the grid's points (regions of 64, 32, 16 and then 8 points a side). A brick of 8^3 points
// whose bound is all inside or all outside is not sampled (a level whose bounds decide nothing is
// given up); the polygonizer evaluates only the
// decided points that a surface cube touches, so the mesh is the one the dense grid gives.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/mesh/field.h"

namespace fscript::mesh {

enum class BrickClass : uint8_t { Open, Inside, Outside };

struct OctreeLevel {
  int size = 0;  // region side in grid points
  size_t empty = 0, full = 0, ambiguous = 0;
};

struct PruneStats {
  bool pruned = false;   // false: the field cannot bound itself, or --no-prune
  std::vector<OctreeLevel> levels;
  size_t points = 0;     // grid samples inside the box
  size_t evaluated = 0;  // of those, evaluated: the open bricks and the decided points next to the surface
  size_t fallbacks = 0;  // jobs re-run dense because a bound disagreed with a point (a bug if ever > 0)
  void add(const PruneStats& o);
};

// Pruning figures of every implicit job since the process started (fvrml-run --stats).
PruneStats& prune_totals();
void add_prune_totals(const PruneStats& s);

class BrickMap {
 public:
  static constexpr int kBrick = 8;
  // The side of the regions that keep their field (local_at): a dual-contouring block's.
  static constexpr int kLocal = 16;

  // axis[a][i]: the coordinate of grid point i along axis a, exactly as the samples are evaluated.
  // Classifies every brick; with `threads` workers, the same result for any count.
  BrickMap(const Field& f, const std::array<std::vector<float>, 3>& axis, int threads);

  BrickClass at(int bi, int bj, int bk) const {
    return cls_[(static_cast<size_t>(bk) * nb_[1] + static_cast<size_t>(bj)) * nb_[0] + static_cast<size_t>(bi)];
  }
  // Whether every brick of the layer of bricks bk is open (the plane is sampled whole).
  bool layer_open(int bk) const { return layer_open_[static_cast<size_t>(bk)] != 0; }
  const PruneStats& stats() const { return stats_; }
  // The points of open bricks in regions with no field of their own: what the whole field samples.
  uint64_t points_on_whole() const;
  // The field simplified for the region of kLocal^3 points (i, j, k) (Field::local, as the octree
  // descended), good at every point within 1.5 grid steps of it; null: the whole field's. An index
  // past the last region names the last (a block there holds only the grid's last samples).
  const std::shared_ptr<const Field>& local_at(int i, int j, int k) const {
    auto at = [this](int v, int a) { return static_cast<size_t>(std::min(v, nl_[a] - 1)); };
    return local_[(at(k, 2) * static_cast<size_t>(nl_[1]) + at(j, 1)) * static_cast<size_t>(nl_[0]) + at(i, 0)];
  }

 private:
  struct Region {
    int lo[3], hi[3];  // grid points [lo, hi) per axis
  };
  struct Walk {  // one top region's classification
    PruneStats& stats;
    size_t seen[8], decided[8];  // regions bounded and decided, per level
  };
  // `known`: the region's bound, when its parent bounded it with its siblings.
  void classify(const Field& root, const std::shared_ptr<const Field>& here,
                const std::array<std::vector<float>, 3>& axis, const Region& r, size_t level, Walk& w,
                const math::Interval* known);
  Box3 box_of(const std::array<std::vector<float>, 3>& axis, const Region& r) const;
  void mark(const Region& r, BrickClass c);
  void keep_local(const Region& r, const std::shared_ptr<const Field>& f);

  int n_[3], nb_[3], nl_[3];
  double step_[3];
  std::vector<std::shared_ptr<const Field>> local_;
  std::vector<BrickClass> cls_;
  std::vector<uint8_t> layer_open_;
  PruneStats stats_;
};

}  // namespace fscript::mesh
