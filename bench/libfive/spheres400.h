// spheres400.fs as libfive's tree: min(d^2 - r^2) over its balls (balls.h, written by
// bench/libfive/build.sh), the model both peers of bench/libfive/ render.
#pragma once
#include "balls.h"  // kBalls[][4]: r^2, cx, cy, cz
#include "libfive/tree/tree.hpp"

inline libfive::Tree spheres400_tree() {
  using libfive::Tree;
  Tree x = Tree::X(), y = Tree::Y(), z = Tree::Z();
  Tree t = Tree::invalid();
  for (const auto& b : kBalls) {
    Tree d = (x - b[1]) * (x - b[1]) + (y - b[2]) * (y - b[2]) + (z - b[3]) * (z - b[3]) - b[0];
    t = t.is_valid() ? min(t, d) : d;
  }
  return t;
}
