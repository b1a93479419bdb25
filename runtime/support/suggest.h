#pragma once
// The nearest known name to a misspelt one, for "did you mean" in every tool and language: an
// option, a command, a VRML field, an FScript function.
#include <algorithm>
#include <string>
#include <vector>

namespace fscript::support {

// Edits (insert, delete, replace, swap two neighbours) from a to b.
inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// The name of `names` nearest to `word`, if near enough to be a slip (a third of its letters, at
// least two), else "".
inline std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& n : names)
    if (size_t d = edit_distance(word, n); d < best_d) best = n, best_d = d;
  return best;
}

}  // namespace fscript::support
