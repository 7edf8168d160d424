#include "nearest_name.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::app {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // optimal string alignment: Levenshtein plus adjacent swaps, the commonest typing slip
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

std::string nearest_name(std::string_view typed, const std::vector<std::string>& candidates) {
  const std::size_t near_enough = std::max<std::size_t>(1, typed.size() / 3);
  std::string best;
  std::size_t best_distance = near_enough + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(typed, c);
    if (d < best_distance || (d == best_distance && c < best)) {
      best = c;
      best_distance = d;
    }
  }
  if (!best.empty()) return best;
  // a name cut short: `rigid camp` means campaign when nothing else begins so
  std::vector<std::string> begun;
  for (const std::string& c : candidates) {
    if (typed.size() >= 2 && c.size() > typed.size() && c.compare(0, typed.size(), typed) == 0) begun.push_back(c);
  }
  return begun.size() == 1 ? begun.front() : std::string();
}

}  // namespace rigid::app
