// The array helpers of SSE kernels, lane by lane.
#include "backends/sse/sse_arrays.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "runtime/math/math.h"

namespace fscript::sse {
namespace {

bool on(const float* mask, int lane) {
  uint32_t b;
  std::memcpy(&b, mask + lane, 4);
  return b != 0;
}

std::string fmt(float v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", static_cast<double>(v));
  return b;
}

bool created(ArrayState* s, uint32_t slot, int lane) {
  if (s->off[slot][lane] >= 0) return true;
  s->message = "array '" + s->names[slot] + "' is used before it is created";
  return false;
}

}  // namespace

extern "C" {

uint32_t fs_sse_arrays_reset(ArrayState* s) {
  for (auto& h : s->heap) h.clear();
  for (auto& o : s->off) o.fill(-1);
  for (auto& l : s->len) l.fill(0);
  return 0;
}

uint32_t fs_sse_anew(ArrayState* s, uint32_t slot, const float* size, const float* mask) {
  for (int i = 0; i < 4; ++i) {
    if (!on(mask, i)) continue;
    float n = math::round(size[i]);
    if (!(n >= 0) || n > static_cast<float>(s->max_elements) ||
        s->heap[i].size() + static_cast<size_t>(n) > s->max_elements) {
      s->message = "array '" + s->names[slot] + "' of " + fmt(size[i]) +
                   " elements: sizes must be whole numbers from 0 to the budget of " +
                   std::to_string(s->max_elements) + " elements per evaluation";
      return 1;
    }
    s->off[slot][i] = static_cast<int64_t>(s->heap[i].size());
    s->len[slot][i] = static_cast<int64_t>(n);
    s->heap[i].resize(s->heap[i].size() + static_cast<size_t>(n), 0.0f);
  }
  return 0;
}

// The element of lane i, or nullptr with the message set.
static float* element(ArrayState* s, uint32_t slot, const float* index, int i) {
  if (!created(s, slot, i)) return nullptr;
  long idx = math::array_index(index[i], s->len[slot][i]);
  if (idx < 0) {
    s->message = "index " + fmt(index[i]) + " is out of range for array '" + s->names[slot] + "' of " +
                 std::to_string(s->len[slot][i]) + " elements";
    return nullptr;
  }
  return &s->heap[i][static_cast<size_t>(s->off[slot][i] + idx)];
}

uint32_t fs_sse_aload(ArrayState* s, uint32_t slot, const float* index, float* out, const float* mask) {
  for (int i = 0; i < 4; ++i) {
    out[i] = 0.0f;
    if (!on(mask, i)) continue;
    float* e = element(s, slot, index, i);
    if (!e) return 1;
    out[i] = *e;
  }
  return 0;
}

uint32_t fs_sse_astore(ArrayState* s, uint32_t slot, const float* index, const float* value, const float* mask) {
  for (int i = 0; i < 4; ++i) {
    if (!on(mask, i)) continue;
    float* e = element(s, slot, index, i);
    if (!e) return 1;
    *e = value[i];
  }
  return 0;
}

uint32_t fs_sse_alen(ArrayState* s, uint32_t slot, float* out, const float* mask) {
  for (int i = 0; i < 4; ++i) {
    out[i] = 0.0f;
    if (!on(mask, i)) continue;
    if (!created(s, slot, i)) return 1;
    out[i] = static_cast<float>(s->len[slot][i]);
  }
  return 0;
}

uint32_t fs_sse_arrays_enter(ArrayState* s, uint32_t first, uint32_t count, int64_t* save) {
  for (uint32_t k = 0; k < count; ++k) {
    std::copy(s->off[first + k].begin(), s->off[first + k].end(), save + 8 * k);
    std::copy(s->len[first + k].begin(), s->len[first + k].end(), save + 8 * k + 4);
    s->off[first + k].fill(-1);
    s->len[first + k].fill(0);
  }
  return 0;
}

uint32_t fs_sse_arrays_leave(ArrayState* s, uint32_t first, uint32_t count, const int64_t* save) {
  for (uint32_t k = 0; k < count; ++k) {
    std::copy(save + 8 * k, save + 8 * k + 4, s->off[first + k].begin());
    std::copy(save + 8 * k + 4, save + 8 * k + 8, s->len[first + k].begin());
  }
  return 0;
}

}  // extern "C"

}  // namespace fscript::sse
