// The brick map: top regions of 64^3 grid points shared out to the threads, each bounded by the
// field and split in eight while its bound straddles zero, down to bricks of 8^3 points. Every
// region writes only its own bricks, so the map does not depend on the schedule.
#include "engine/mesh/sample_pruning.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "runtime/support/parallel.h"

namespace fscript::mesh {
namespace {

// Region sides per level, in grid points; the last is the brick. Chosen by measurement
// (docs/performance.md, "Decisions": octree bricks).
constexpr int kSizes[] = {64, 32, 16, BrickMap::kBrick};
constexpr size_t kLevels = sizeof(kSizes) / sizeof(kSizes[0]);
// Within one top region, a level stops being split further once kTrials of its regions were bounded
// and fewer than one in kRate was decided.
constexpr size_t kTrials = 8, kRate = 8;

std::mutex totals_lock;

}  // namespace

void PruneStats::add(const PruneStats& o) {
  pruned = pruned || o.pruned;
  if (levels.size() < o.levels.size()) levels.resize(o.levels.size());
  for (size_t l = 0; l < o.levels.size(); ++l) {
    levels[l].size = o.levels[l].size;
    levels[l].empty += o.levels[l].empty;
    levels[l].full += o.levels[l].full;
    levels[l].ambiguous += o.levels[l].ambiguous;
  }
  points += o.points;
  evaluated += o.evaluated;
  fallbacks += o.fallbacks;
}

PruneStats& prune_totals() {
  static PruneStats totals;
  return totals;
}

void add_prune_totals(const PruneStats& s) {
  std::lock_guard<std::mutex> hold(totals_lock);  // frames are meshed in parallel
  prune_totals().add(s);
}

BrickMap::BrickMap(const Field& f, const std::array<std::vector<float>, 3>& axis, int threads) {
  for (int a = 0; a < 3; ++a) {
    n_[a] = static_cast<int>(axis[a].size());
    nb_[a] = (n_[a] + kBrick - 1) / kBrick;
    nl_[a] = (n_[a] + kLocal - 1) / kLocal;
    step_[a] = n_[a] > 1 ? std::abs(double(axis[a][1]) - double(axis[a][0])) : 0.0;
  }
  local_.assign(static_cast<size_t>(nl_[0]) * nl_[1] * nl_[2], nullptr);
  cls_.assign(static_cast<size_t>(nb_[0]) * nb_[1] * nb_[2], BrickClass::Open);
  std::vector<Region> tops;
  const int s = kSizes[0];
  for (int k = 0; k < n_[2]; k += s)
    for (int j = 0; j < n_[1]; j += s)
      for (int i = 0; i < n_[0]; i += s)
        tops.push_back({{i, j, k}, {std::min(i + s, n_[0]), std::min(j + s, n_[1]), std::min(k + s, n_[2])}});
  int parts = std::max(1, std::min(threads, static_cast<int>(tops.size())));
  std::vector<PruneStats> part_stats(static_cast<size_t>(parts));
  for (auto& st : part_stats)
    for (int size : kSizes) st.levels.push_back({size, 0, 0, 0});
  std::atomic<size_t> next{0};
  support::run_parts(parts, [&](int p) {
    for (size_t t; (t = next.fetch_add(1)) < tops.size();) {
      Walk w{part_stats[static_cast<size_t>(p)], {}, {}};  // each top region learns on its own: any schedule
      classify(f, nullptr, axis, tops[t], 0, w, nullptr);
    }
    return true;
  });
  stats_.pruned = true;
  for (const auto& st : part_stats) stats_.add(st);
  layer_open_.assign(static_cast<size_t>(nb_[2]), 1);
  for (int bk = 0; bk < nb_[2]; ++bk)
    for (int bj = 0; bj < nb_[1] && layer_open_[static_cast<size_t>(bk)]; ++bj)
      for (int bi = 0; bi < nb_[0]; ++bi)
        if (at(bi, bj, bk) != BrickClass::Open) {
          layer_open_[static_cast<size_t>(bk)] = 0;
          break;
        }
}

Box3 BrickMap::box_of(const std::array<std::vector<float>, 3>& axis, const Region& r) const {
  Box3 box;
  for (int a = 0; a < 3; ++a) {
    float p = axis[a][static_cast<size_t>(r.lo[a])], q = axis[a][static_cast<size_t>(r.hi[a] - 1)];
    box.lo[a] = std::min(p, q), box.hi[a] = std::max(p, q);
  }
  return box;
}

void BrickMap::classify(const Field& root, const std::shared_ptr<const Field>& here,
                        const std::array<std::vector<float>, 3>& axis, const Region& r, size_t level, Walk& w,
                        const math::Interval* known) {
  const Field& f = here ? *here : root;
  const Box3 box = box_of(axis, r);
  math::Interval v = known ? *known : f.bound(box);
  OctreeLevel& l = w.stats.levels[level];
  ++w.seen[level];
  const bool keeps = kSizes[level] >= kLocal;
  if (!v.nan && v.lo > 0) {
    if (keeps) keep_local(r, here);  // a sample here may still be evaluated (next to an open brick)
    return ++l.full, ++w.decided[level], mark(r, BrickClass::Inside);
  }
  if (v.empty() || v.hi <= 0) {  // 0, NaN: outside
    if (keeps) keep_local(r, here);
    return ++l.empty, ++w.decided[level], mark(r, BrickClass::Outside);
  }
  ++l.ambiguous;
  if (!keeps) return;  // an open brick
  // The region's field, simplified for its box and 1.5 steps around it: what its children are
  // bounded with, and what a block of dual contouring (its samples reach one step below the region)
  // evaluates with.
  Box3 wide = box;
  for (int a = 0; a < 3; ++a)
    wide.lo[a] = static_cast<float>(box.lo[a] - 1.5 * step_[a]),
    wide.hi[a] = static_cast<float>(box.hi[a] + 1.5 * step_[a]);
  std::shared_ptr<const Field> narrowed = f.local(wide);
  const std::shared_ptr<const Field>& mine = narrowed ? narrowed : here;
  keep_local(r, mine);
  if (level + 1 == kLevels) return;
  // A level whose bounds rarely decide is not worth more of them: a blend of spheres, say, is bounded
  // loosely everywhere, and one bound costs about as much as sampling a brick of 8^3 points.
  if (w.seen[level + 1] >= kTrials && w.decided[level + 1] * kRate < w.seen[level + 1]) return;
  // The children (at most eight) bounded together on this region's field, then classified.
  const int s = kSizes[level + 1];
  Region children[8];
  Box3 boxes[8];
  math::Interval bounds[8];
  size_t n = 0;
  for (int k = r.lo[2]; k < r.hi[2]; k += s)
    for (int j = r.lo[1]; j < r.hi[1]; j += s)
      for (int i = r.lo[0]; i < r.hi[0]; i += s, ++n) {
        children[n] = {{i, j, k}, {std::min(i + s, r.hi[0]), std::min(j + s, r.hi[1]), std::min(k + s, r.hi[2])}};
        boxes[n] = box_of(axis, children[n]);
      }
  (mine ? *mine : root).bounds(boxes, n, bounds);
  for (size_t c = 0; c < n; ++c) classify(root, mine, axis, children[c], level + 1, w, &bounds[c]);
}

uint64_t BrickMap::points_on_whole() const {
  uint64_t n = 0;
  for (int bk = 0; bk < nb_[2]; ++bk)
    for (int bj = 0; bj < nb_[1]; ++bj)
      for (int bi = 0; bi < nb_[0]; ++bi)
        if (at(bi, bj, bk) == BrickClass::Open &&
            !local_at(bi * kBrick / kLocal, bj * kBrick / kLocal, bk * kBrick / kLocal))
          n += kBrick * kBrick * kBrick;
  return n;
}

void BrickMap::keep_local(const Region& r, const std::shared_ptr<const Field>& f) {
  for (int k = r.lo[2] / kLocal; k * kLocal < r.hi[2]; ++k)
    for (int j = r.lo[1] / kLocal; j * kLocal < r.hi[1]; ++j)
      for (int i = r.lo[0] / kLocal; i * kLocal < r.hi[0]; ++i)
        local_[(static_cast<size_t>(k) * nl_[1] + static_cast<size_t>(j)) * nl_[0] + static_cast<size_t>(i)] = f;
}

void BrickMap::mark(const Region& r, BrickClass c) {
  for (int bk = r.lo[2] / kBrick; bk * kBrick < r.hi[2]; ++bk)
    for (int bj = r.lo[1] / kBrick; bj * kBrick < r.hi[1]; ++bj)
      for (int bi = r.lo[0] / kBrick; bi * kBrick < r.hi[0]; ++bi)
        cls_[(static_cast<size_t>(bk) * nb_[1] + static_cast<size_t>(bj)) * nb_[0] + static_cast<size_t>(bi)] = c;
}

}  // namespace fscript::mesh
