// Arrays per lane: one lane's operations, and the masked helpers the JITs call.
#include "backends/lane_arrays.h"

#include <algorithm>
#include <cstring>

#include "backends/runtime_errors.h"
#include "runtime/math/math.h"

namespace fscript::backends {
namespace {
bool on(const uint32_t* mask, uint32_t lane) { return mask[lane] != 0; }
}  // namespace

void LaneArrays::init(uint32_t lane_count, uint64_t budget, const std::vector<std::string>& slot_names) {
  lanes = lane_count;
  max_elements = budget;
  names.clear();
  for (const auto& n : slot_names) names.push_back(array_display_name(n));
  heap.resize(lanes);
  for (auto& h : heap) h.clear();  // storage kept: a VM thread inits once per batch
  off.assign(slot_names.size() * lanes, -1);
  len.assign(slot_names.size() * lanes, 0);
}

void LaneArrays::reset() {
  for (auto& h : heap) h.clear();
  std::fill(off.begin(), off.end(), -1);
  std::fill(len.begin(), len.end(), 0);
}

bool LaneArrays::created(uint32_t slot, uint32_t lane) {
  if (off[slot * lanes + lane] >= 0) return true;
  message = errors::array_unset(names[slot]);
  return false;
}

bool LaneArrays::create(uint32_t slot, uint32_t lane, float size) {
  float n = math::round(size);
  std::vector<float>& h = heap[lane];
  if (!(n >= 0) || n > static_cast<float>(max_elements) || h.size() + static_cast<size_t>(n) > max_elements) {
    message = errors::array_size(names[slot], size, max_elements);
    return false;
  }
  off[slot * lanes + lane] = static_cast<int64_t>(h.size());
  len[slot * lanes + lane] = static_cast<int64_t>(n);
  h.resize(h.size() + static_cast<size_t>(n), 0.0f);
  return true;
}

float* LaneArrays::element(uint32_t slot, uint32_t lane, float index) {
  if (!created(slot, lane)) return nullptr;
  long idx = math::array_index(index, len[slot * lanes + lane]);
  if (idx < 0) {
    message = errors::array_index(names[slot], index, len[slot * lanes + lane]);
    return nullptr;
  }
  return &heap[lane][static_cast<size_t>(off[slot * lanes + lane] + idx)];
}

bool LaneArrays::length(uint32_t slot, uint32_t lane, float& out) {
  if (!created(slot, lane)) return false;
  out = static_cast<float>(len[slot * lanes + lane]);
  return true;
}

void LaneArrays::enter(uint32_t first, uint32_t count, uint32_t lane, int64_t* save) {
  for (uint32_t k = 0; k < count; ++k) {
    size_t at = size_t{first + k} * lanes + lane;
    save[k] = off[at];
    save[count + k] = len[at];
    off[at] = -1;
    len[at] = 0;
  }
}

void LaneArrays::leave(uint32_t first, uint32_t count, uint32_t lane, const int64_t* save) {
  for (uint32_t k = 0; k < count; ++k) {
    size_t at = size_t{first + k} * lanes + lane;
    off[at] = save[k];
    len[at] = save[count + k];
  }
}

extern "C" {

uint32_t fs_lanes_reset(LaneArrays* s) {
  s->reset();
  return 0;
}

uint32_t fs_lanes_anew(LaneArrays* s, uint32_t slot, const float* size, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i)
    if (on(mask, i) && !s->create(slot, i, size[i])) return 1;
  return 0;
}

uint32_t fs_lanes_aload(LaneArrays* s, uint32_t slot, const float* index, float* out, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    out[i] = 0.0f;
    if (!on(mask, i)) continue;
    float* e = s->element(slot, i, index[i]);
    if (!e) return 1;
    out[i] = *e;
  }
  return 0;
}

uint32_t fs_lanes_astore(LaneArrays* s, uint32_t slot, const float* index, const float* value, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    if (!on(mask, i)) continue;
    float* e = s->element(slot, i, index[i]);
    if (!e) return 1;
    *e = value[i];
  }
  return 0;
}

uint32_t fs_lanes_alen(LaneArrays* s, uint32_t slot, float* out, const uint32_t* mask) {
  for (uint32_t i = 0; i < s->lanes; ++i) {
    out[i] = 0.0f;
    if (on(mask, i) && !s->length(slot, i, out[i])) return 1;
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

}  // namespace fscript::backends
