#pragma once
// Where an implicit job's evaluation goes (fvrml-run --profile, fscript profile): every field the
// mesher asks, the whole function's and each region's simplified one, is wrapped so that the points
// it evaluates, the time they take and the boxes it bounds are counted against its tapes, and each
// point's operations are added to a picture of the box seen from +z.
#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <vector>

#include "engine/mesh/field.h"
#include "engine/mesh/sample_pruning.h"

namespace fscript::mesh {

// One field the mesher asked, the whole function's (no box) or a region's, with what it did. Its
// tapes are copied when its job ends: the fields and the shape they came from are gone by the report.
struct FieldRecord {
  bool has_box = false;
  Box3 box{};
  uint64_t points = 0, point_ns = 0;        // values evaluated, and their time
  uint64_t gradients = 0, gradient_ns = 0;  // gradients evaluated
  uint64_t bounds = 0, bound_ns = 0;        // boxes bounded by intervals
  // The tapes it runs (Field::part_tapes: one, or an FTransform's parts'); none where it runs no
  // tape, or no gradient was asked.
  std::vector<std::shared_ptr<const ir::IntervalTape>> value, gradient;
};

class FieldProfile {
 public:
  // The job's box (x0 x1 y0 y1 z0 z1) and grid cells: the picture has a column per grid column
  // over x and y. Later jobs (frames of an animation) add to the same picture.
  void begin(const std::array<double, 6>& box, const std::array<int, 3>& cells);

  const std::deque<FieldRecord>& records() const { return records_; }
  const PruneStats& prune() const { return prune_; }
  void add_prune(const PruneStats& s);
  void add_records(std::deque<FieldRecord>&& done);
  int width() const { return width_; }
  int height() const { return height_; }
  // Per picture column (row-major from the top, +y up): operations evaluated (values and
  // gradients), and of values alone the operations and the points.
  uint64_t column_work(int i, int j) const { return work_[at(i, j)].load(); }
  uint64_t column_value_ops(int i, int j) const { return value_ops_[at(i, j)].load(); }
  uint64_t column_values(int i, int j) const { return values_[at(i, j)].load(); }

  // Adds `ops` per point at (x[i], y[i]) for i < n (y[i / row] where rows of `row` points share
  // one y); `value`: the points are values (else gradients).
  void add_points(const float* x, const float* y, size_t n, uint32_t ops, bool value, size_t row = 1);

 private:
  size_t at(int i, int j) const {
    return static_cast<size_t>(j) * static_cast<size_t>(width_) + static_cast<size_t>(i);
  }
  int column(float v, int axis) const;
  std::mutex lock_;
  std::deque<FieldRecord> records_;
  PruneStats prune_;
  std::once_flag begun_;
  double lo_[2]{}, scale_[2]{};
  int width_ = 0, height_ = 0;
  std::unique_ptr<std::atomic<uint64_t>[]> work_, value_ops_, values_;
};

struct ImplicitJob;
struct Mesh;
// polygonize() of a job with a profile: its field wrapped, simplified tapes keeping their sources.
bool polygonize_profiled(const ImplicitJob& job, Mesh& out, backends::RuntimeError& err);

// Which profile each mesh job adds to: one per shape (frames of an animation share their shape's).
class Profiler {
 public:
  // The profile of `key` (a shape's node), made at the first ask.
  FieldProfile& of(const void* key);
  // The profiles in the order they were first asked for.
  const std::vector<std::pair<const void*, std::unique_ptr<FieldProfile>>>& profiles() const { return profiles_; }

 private:
  std::mutex lock_;
  std::vector<std::pair<const void*, std::unique_ptr<FieldProfile>>> profiles_;
};

}  // namespace fscript::mesh
