#include "engine/gi/vlm/grid.hpp"

#include "engine/gi/vlm/grid_detail.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

#include "engine/core/parallel.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::vlm {

namespace detail {

void selectBest(std::uint64_t* a, std::uint32_t n, std::uint32_t k) {
  static thread_local std::vector<std::uint64_t> partitioned;
  partitioned.resize(n);
  std::uint64_t* t = partitioned.data();
  std::uint32_t lo = 0, hi = n;  // all of [0, lo) < all of [lo, hi) < all of [hi, n)
  while (lo < k && k < hi) {
    // Pivot: from five keys spread over the range, the one whose rank among them is nearest k's
    // rank in the range (k is ~2/3 of the way for K 32 among ~48 candidates), moved to the end.
    const std::uint32_t last = hi - 1, span = hi - lo;
    std::uint32_t at[5];
    for (std::uint32_t s = 0; s < 5; ++s) at[s] = lo + std::uint32_t(std::uint64_t(span - 1) * s / 4);
    for (std::uint32_t s = 1; s < 5; ++s)
      for (std::uint32_t t = s; t > 0 && a[at[t]] < a[at[t - 1]]; --t) std::swap(at[t], at[t - 1]);
    const std::uint32_t pick = at[std::min<std::uint32_t>(4, std::uint32_t((std::uint64_t(k - lo) * 5) / span))];
    std::swap(a[pick], a[last]);
    const std::uint64_t pivot = a[last];
    // Smaller keys fill t from lo upwards, larger ones from last downwards; each key is written to
    // both free ends and only its side's end moves, so there is no branch on the comparison.
    std::uint32_t less = lo, more = last;
    for (std::uint32_t j = lo; j < last; ++j) {
      const std::uint64_t key = a[j];
      const bool smaller = key < pivot;
      t[less] = key;
      t[more] = key;
      less += smaller;
      more -= !smaller;
    }
    t[less] = pivot;  // the one slot left, between the sides
    std::copy(t + lo, t + hi, a + lo);
    const std::uint32_t i = less;
    if (i + 1 == k || i == k) return;
    if (i > k) hi = i;
    else lo = i + 1;
  }
}

std::vector<ActiveHemisphere> hemispheres(std::span<const GridLight> lights, float range) {
  std::vector<ActiveHemisphere> h(lights.size());
  parallelFor(0, lights.size(), [&](std::size_t i) { h[i] = activeHemisphere(lights[i], range); }, 1024);
  return h;
}

// The floor() guess (it may be a cell off either way) is corrected cell by cell, so no padding is
// needed (a cell of padding each side would visit (n+3)³ instead of (n+1)³ cells).
void cellRange(const GridDesc& d, const ActiveHemisphere& h, glm::uvec3& lo, glm::uvec3& hi) {
  const glm::vec3 perCell = 1.0f / d.cellSize;  // only the first guess uses it
  for (int a = 0; a < 3; ++a) {
    const auto n = std::int64_t(d.dims[a]);
    auto cellLo = [&](std::int64_t c) { return d.origin[a] + float(c) * d.cellSize[a]; };
    auto cellHi = [&](std::int64_t c) { return d.origin[a] + float(c + 1) * d.cellSize[a]; };
    // First cell with cellHi ≥ h.lo, last cell with cellLo ≤ h.hi.
    // The guess is clamped in float (NaN to 0) before it becomes an integer; truncation is floor
    // there, the values being ≥ 0.
    auto guess = [&](float p) {
      const float f = (p - d.origin[a]) * perCell[a];
      return std::int64_t(f >= 0.0f ? std::min(f, float(n - 1)) : 0.0f);
    };
    std::int64_t first = guess(h.lo[a]);
    while (first > 0 && !(cellHi(first - 1) < h.lo[a])) --first;
    while (first < n && cellHi(first) < h.lo[a]) ++first;
    std::int64_t last = guess(h.hi[a]);
    while (last < n - 1 && !(cellLo(last + 1) > h.hi[a])) ++last;
    while (last >= 0 && cellLo(last) > h.hi[a]) --last;
    if (first > last) {
      lo = glm::uvec3(1u), hi = glm::uvec3(0u);
      return;
    }
    lo[a] = std::uint32_t(first), hi[a] = std::uint32_t(last);
  }
}

}  // namespace detail

using namespace detail;

GridDesc fitGrid(glm::vec3 lo, glm::vec3 hi, glm::uvec3 dims, std::uint32_t k, float range) {
  GridDesc d;
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-4f));
  d.origin = lo;
  d.dims = glm::max(dims, glm::uvec3(1u));
  d.cellSize = extent / glm::vec3(d.dims);
  d.k = std::max(k, 1u);
  d.range = range;
  return d;
}

ActiveHemisphere activeHemisphere(const GridLight& l, float range) {
  ActiveHemisphere h;
  h.centre = (l.v0 + l.v1 + l.v2) / 3.0f;
  const glm::vec3 n = glm::cross(l.v1 - l.v0, l.v2 - l.v0);
  const float len = glm::length(n);
  if (!(len > 0.0f) || !std::isfinite(len)) return h;  // degenerate: never a candidate
  h.normal = n / len;
  h.area = 0.5f * len;
  h.extent = std::sqrt(std::max({glm::dot(l.v0 - h.centre, l.v0 - h.centre), glm::dot(l.v1 - h.centre, l.v1 - h.centre),
                                 glm::dot(l.v2 - h.centre, l.v2 - h.centre)}));
  h.radius = range * h.extent;
  h.weight = l.weight;
  // Box of the half-ball {|p − c| ≤ r, n·(p − c) ≥ 0}: along axis a it reaches c ± r on the side
  // the normal points to, and only the rim disc, r·√(1 − n_a²), on the other.
  for (int a = 0; a < 3; ++a) {
    const float rim = h.radius * std::sqrt(std::max(0.0f, 1.0f - h.normal[a] * h.normal[a]));
    h.lo[a] = h.centre[a] - (h.normal[a] > 0.0f ? rim : h.radius);
    h.hi[a] = h.centre[a] + (h.normal[a] < 0.0f ? rim : h.radius);
  }
  return h;
}

void cellBox(const GridDesc& d, glm::uvec3 c, glm::vec3& lo, glm::vec3& hi) {
  lo = d.origin + glm::vec3(c) * d.cellSize;
  hi = d.origin + glm::vec3(c + 1u) * d.cellSize;
}

bool touchesCell(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) { return touches(h, lo, hi); }

float cellBound(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) { return bound(h, lo, hi); }

std::int64_t Grid::cellOf(glm::vec3 p) const {
  const glm::vec3 f = glm::floor((p - desc.origin) / desc.cellSize);
  if (!glm::all(glm::greaterThanEqual(f, glm::vec3(0.0f))) || !glm::all(glm::lessThan(f, glm::vec3(desc.dims))))
    return -1;
  const glm::uvec3 c(f);
  return std::int64_t((std::uint64_t(c.z) * desc.dims.y + c.y) * desc.dims.x + c.x);
}

Grid buildGridGather(std::span<const GridLight> lights, const GridDesc& desc) {
  const auto hs = hemispheres(lights, desc.range);
  const std::size_t cells = desc.cellCount();
  const std::uint32_t nx = desc.dims.x, ny = desc.dims.y;
  // The thesis's build (§4.2): each cell evaluates the heuristic for every light.
  auto pass = [&](std::uint32_t capacity, auto&& makeCell, auto&& done) {
    parallelFor(0, cells, [&](std::size_t i) {
      static thread_local std::vector<std::uint64_t> scratch;
      scratch.resize(capacity);
      auto cell = makeCell(scratch.data());
      const glm::uvec3 c(std::uint32_t(i % nx), std::uint32_t((i / nx) % ny), std::uint32_t(i / (std::size_t(nx) * ny)));
      glm::vec3 lo, hi;
      cellBox(desc, c, lo, hi);
      for (std::uint32_t l = 0; l < hs.size(); ++l)
        if (touches(hs[l], lo, hi)) cell.offer(rankKey(bound(hs[l], lo, hi), l));
      done(i, cell);
    }, 16);
  };
  Grid g;
  finishGrid(desc, pass, g);
  return g;
}

std::string formatOverflow(const OverflowReport& r) {
  char line[256];
  std::snprintf(line, sizeof line, "vlm overflow: static %llu/%llu cells, dynamic %llu/%llu (most %llu), K %u",
                static_cast<unsigned long long>(r.staticCells), static_cast<unsigned long long>(r.cellsPerGrid),
                static_cast<unsigned long long>(r.dynamicCells), static_cast<unsigned long long>(r.cellsPerGrid),
                static_cast<unsigned long long>(r.dynamicMaxCells), r.k);
  std::string out = line;
  if (r.conservative) {
    std::snprintf(line, sizeof line, ", conservative: %llu candidates above the threshold dropped",
                  static_cast<unsigned long long>(r.droppedAboveThreshold));
    out += line;
  }
  return out;
}

}  // namespace bounce::gi::vlm

namespace bounce::gi::vlm {

std::vector<GridLight> randomGridScene(std::uint32_t count, std::uint64_t seed) {
  std::vector<GridLight> lights(count);
  const float size = 1.5f / std::cbrt(float(std::max(count, 1u)));
  parallelFor(0, count, [&](std::size_t i) {
    math::Pcg32 rng(seed, i);  // one stream per light: the same scene whatever the thread count
    auto next3 = [&] { return rng.nextFloat3(); };
    const glm::vec3 c = next3();
    GridLight& l = lights[i];
    l.v0 = c + (next3() - 0.5f) * size, l.v1 = c + (next3() - 0.5f) * size, l.v2 = c + (next3() - 0.5f) * size;
    l.weight = 0.1f + rng.nextFloat();
  }, 1024);
  return lights;
}

}  // namespace bounce::gi::vlm
