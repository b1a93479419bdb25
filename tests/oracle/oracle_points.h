#pragma once
// The node oracle's inputs: the points a generated program runs on (special values, ties at .5,
// huge, tiny and random floats) and the transcendental built-ins with their accuracy bounds.
#include <random>
#include <string>
#include <vector>

namespace fscript::oracle {

// n points of (x, y, z, t), as 4n floats.
std::vector<float> program_points(std::mt19937_64& rng, int n);

struct BuiltinCheck {
  std::string name, fs, js;  // FRep(x, y, z, t) returning the built-in of x (and y); its JavaScript
  int arity = 1;
  int max_ulps = 1;  // against node's Math rounded to float (docs/language.md, "Accuracy")
};
std::vector<BuiltinCheck> builtin_checks();
// The points a built-in is checked on: every pair of special values, then random ones.
std::vector<float> builtin_points(std::mt19937_64& rng, int arity);

}  // namespace fscript::oracle
