#include "engine/core/suggest.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace bounce {

std::size_t editDistance(std::string_view a, std::string_view b) {
  auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
  const std::size_t n = a.size(), m = b.size();
  // d_i[j]: distance between the first i characters of a and the first j of b. Row i needs rows
  // i − 1 and i − 2 (the swap), so three rows of m + 1 suffice: memory O(|b|), not O(|a|·|b|)
  // (a 10 MB key in a level took 10 M row allocations per candidate name).
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::optional<std::string> nearestName(std::string_view given, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::max<std::size_t>(1, given.size() / 3);
  std::optional<std::string> best;
  std::size_t bestDistance = limit + 1;
  for (const auto& c : candidates) {
    if (c == given) continue;
    // Only insertions and deletions change the length, one each, so the distance is at least the
    // length difference: a candidate that cannot beat bestDistance is not measured (a long hostile
    // key costs O(|key|) here instead of O(|key|·|name|) per name). The result is the same.
    const std::size_t lengthGap = given.size() > c.size() ? given.size() - c.size() : c.size() - given.size();
    if (lengthGap >= bestDistance) continue;
    const std::size_t d = editDistance(given, c);
    if (d < bestDistance) bestDistance = d, best = c;
  }
  return best;
}

std::string didYouMean(std::string_view given, const std::vector<std::string>& candidates) {
  const auto n = nearestName(given, candidates);
  return n ? ", did you mean \"" + *n + "\"?" : std::string();
}

}  // namespace bounce
