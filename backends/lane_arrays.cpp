// The array helpers of the JIT backends, lane by lane.
#include "backends/lane_arrays.h"

#include <algorithm>
#include <cstring>

#include "backends/runtime_errors.h"
#include "runtime/math/math.h"

namespace fscript::backend {
namespace {

bool on(const uint32_t* mask, uint32_t lane) { return mask[lane] != 0; }

bool created(LaneArrays* s, uint32_t slot, uint32_t lane) {
  if (s->off[slot * s->lanes + lane] >= 0) return true;
  s->message = errors::array_unset(s->names[slot]);
  return false;
}

}  // namespace

void LaneArrays::init(uint32_t lane_count, uint64_t budget, const std::vector<std::string>& slot_names) {
  lanes = lane_count;
  max_elements = budget;
  names.clear();
  for (const auto& n : slot_names) names.push_back(array_display_name(n));
  heap.assign(lanes, {});
  off.assign(slot_names.size() * lanes, -1);
  len.assign(slot_names.size() * lanes, 0);
}

extern "C" {

uint32_t fs_lanes_reset(LaneArrays* s) {
  for (auto& h : s->heap) h.clear();
  std::fill(s->off.begin(), s->off.end(), -1);
  std::fill(s->len.begin(), s->len.end(), 0);
  return 0;
}

uint32_t fs_lanes_anew(LaneArrays* s, uint32_t slot, const float* size, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    if (!on(mask, i)) continue;
    float n = math::round(size[i]);
    if (!(n >= 0) || n > static_cast<float>(s->max_elements) ||
        s->heap[i].size() + static_cast<size_t>(n) > s->max_elements) {
      s->message = errors::array_size(s->names[slot], size[i], s->max_elements);
      return 1;
    }
    s->off[slot * s->lanes + i] = static_cast<int64_t>(s->heap[i].size());
    s->len[slot * s->lanes + i] = static_cast<int64_t>(n);
    s->heap[i].resize(s->heap[i].size() + static_cast<size_t>(n), 0.0f);
  }
  return 0;
}

// The element of lane i, or nullptr with the message set.
static float* element(LaneArrays* s, uint32_t slot, const float* index, uint32_t i) {
  if (!created(s, slot, i)) return nullptr;
  long idx = math::array_index(index[i], s->len[slot * s->lanes + i]);
  if (idx < 0) {
    s->message = errors::array_index(s->names[slot], index[i], s->len[slot * s->lanes + i]);
    return nullptr;
  }
  return &s->heap[i][static_cast<size_t>(s->off[slot * s->lanes + i] + idx)];
}

uint32_t fs_lanes_aload(LaneArrays* s, uint32_t slot, const float* index, float* out, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    out[i] = 0.0f;
    if (!on(mask, i)) continue;
    float* e = element(s, slot, index, i);
    if (!e) return 1;
    out[i] = *e;
  }
  return 0;
}

uint32_t fs_lanes_astore(LaneArrays* s, uint32_t slot, const float* index, const float* value, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    if (!on(mask, i)) continue;
    float* e = element(s, slot, index, i);
    if (!e) return 1;
    *e = value[i];
  }
  return 0;
}

uint32_t fs_lanes_alen(LaneArrays* s, uint32_t slot, float* out, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    out[i] = 0.0f;
    if (!on(mask, i)) continue;
    if (!created(s, slot, i)) return 1;
    out[i] = static_cast<float>(s->len[slot * s->lanes + i]);
  }
  return 0;
}

uint32_t fs_lanes_enter(LaneArrays* s, uint32_t first, uint32_t count, int64_t* save) {
  size_t n = size_t{count} * s->lanes, at = size_t{first} * s->lanes;
  std::copy_n(s->off.begin() + at, n, save);
  std::copy_n(s->len.begin() + at, n, save + n);
  std::fill_n(s->off.begin() + at, n, -1);
  std::fill_n(s->len.begin() + at, n, 0);
  return 0;
}

uint32_t fs_lanes_leave(LaneArrays* s, uint32_t first, uint32_t count, const int64_t* save) {
  size_t n = size_t{count} * s->lanes, at = size_t{first} * s->lanes;
  std::copy_n(save, n, s->off.begin() + at);
  std::copy_n(save + n, n, s->len.begin() + at);
  return 0;
}

}  // extern "C"

}  // namespace fscript::backend
