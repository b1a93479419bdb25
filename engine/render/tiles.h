#pragma once
// Rectangles of a picture's samples and their split into tiles: the regions the quadtree and the
// direct renderer descend through.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace fscript::render {

struct Rect {
  uint32_t c0, r0, c1, r1;  // columns [c0, c1), rows [r0, r1)
};

// The regions of side `s` that cover r, row by row (into `out`, whose storage is reused).
inline void split(Rect r, uint32_t s, std::vector<Rect>& out) {
  out.clear();
  for (uint32_t row = r.r0; row < r.r1; row += s)
    for (uint32_t col = r.c0; col < r.c1; col += s)
      out.push_back({col, row, std::min(col + s, r.c1), std::min(row + s, r.r1)});
}

inline std::vector<Rect> split(Rect r, uint32_t s) {
  std::vector<Rect> out;
  split(r, s, out);
  return out;
}

}  // namespace fscript::render
