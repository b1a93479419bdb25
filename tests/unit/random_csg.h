#pragma once
// Random FScript expressions of x, y, z: unions, intersections and differences (min, max, minus) of
// balls, boxes and slabs, for tests that compare two ways of evaluating or drawing a shape.
#include <random>
#include <string>

namespace fscript::test {

inline std::string random_csg(std::mt19937& rng, int depth) {
  std::uniform_real_distribution<double> c(-0.8, 0.8), r(0.1, 0.5);
  auto num = [](double v) { return "(" + std::to_string(v) + ")"; };
  if (depth == 0) {
    switch (rng() % 3) {
      case 0:
        return num(r(rng) * r(rng) * 2) + " - (x-" + num(c(rng)) + ")*(x-" + num(c(rng)) + ") - (y-" + num(c(rng)) +
            ")^2 - (z-" + num(c(rng)) + ")^2";
      case 1:
        return "min(min(" + num(r(rng)) + " - abs(x-" + num(c(rng)) + "), " + num(r(rng)) + " - abs(y-" + num(c(rng)) +
            ")), " + num(r(rng)) + " - abs(z-" + num(c(rng)) + "))";
      default:
        return num(r(rng) / 2) + " - abs(" + num(c(rng)) + "*x + " + num(c(rng)) + "*y + z - " + num(c(rng)) + ")";
    }
  }
  std::string a = random_csg(rng, depth - 1),
              b = random_csg(rng, static_cast<int>(rng() % static_cast<unsigned>(depth)));
  switch (rng() % 3) {
    case 0: return "max(" + a + ", " + b + ")";
    case 1: return "min(" + a + ", " + b + ")";
    default: return "min(" + a + ", -(" + b + "))";
  }
}

}  // namespace fscript::test
