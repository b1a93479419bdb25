#pragma once
// One big implicit shape over several machines (fvrml-run --shard K/M without --frames;
// docs/sharding.md). Dual contouring's blocks lie in layers along z: a shard samples its slab of
// layers (and the layer either side, which its cells' faces look into), works its blocks as one
// machine would and keeps them; the merge puts every shard's blocks back into the grid, then merges,
// numbers and connects them as one machine does, so the seams are welded and the mesh is the same.
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "engine/mesh/dc_block.h"
#include "engine/mesh/dual_contour.h"

namespace fscript::mesh {

// One job's layers from one shard.
struct Slab {
  uint32_t job = 0;        // the run's dual contouring jobs, numbered in the order it meshes them
  int first = 0, end = 0;  // block layers [first, end)
  // The lattice, each block position's class, the kept blocks' state: in `data` (made here, or a
  // whole part file read once: a big mesh's slabs are hundreds of megabytes, not copied again).
  std::shared_ptr<const std::string> data;
  std::string_view bytes;
};

class SlabSplit {
 public:
  using Ring = std::array<uint32_t, 4>;  // a crossing's four cells' vertices, as its shard names them

  // Making shard `index` of `count`: each job's slab is kept (slabs()).
  static std::unique_ptr<SlabSplit> make(int index, int count);
  // Joining every shard's slabs.
  static std::unique_ptr<SlabSplit> join(std::vector<Slab> slabs);

  bool joining() const { return joining_; }
  // The next job's number. Jobs start one after another, in the same order in every shard and in
  // the merge (the same scene and arguments).
  uint32_t next_job();
  // This shard's layers [first, end) of a job whose layers keep `kept[k]` blocks (those the surface
  // may cross): contiguous, in shard order, with about as many kept blocks in each shard.
  void layers_of(const std::vector<size_t>& kept, int& first, int& end) const;
  // Making: the blocks of layers [first, end) of `grid` as job `job`'s slab.
  void keep(uint32_t job, const BlockGrid& grid, int first, int end);
  const std::vector<Slab>& slabs() const { return slabs_; }
  // Joining: job `job`'s mesh from every shard's slab, the same as dual_contour makes on one
  // machine; false with what is missing or damaged.
  bool join(uint32_t job, const Lattice& g, double tolerance, Mesh& out, DualContourStats& stats,
            std::string& error) const;

 private:
  int index_ = 0, count_ = 1;
  bool joining_ = false;
  std::mutex lock_;
  uint32_t jobs_ = 0;
  std::vector<Slab> slabs_;

  // The grid of job `job`'s blocks, and each block's rings.
  bool read_slabs(uint32_t job, const Lattice& g, std::unique_ptr<BlockGrid>& out,
                  std::vector<std::vector<Ring>>& rings, std::string& error) const;
};

}  // namespace fscript::mesh
