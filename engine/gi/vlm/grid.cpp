#include "engine/gi/vlm/grid.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>

#include "engine/core/parallel.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::vlm {

namespace {

constexpr float kPi = 3.14159265358979f;

// The heuristic and the bound (public as touchesCell / cellBound), split per axis so the scatter
// build can compute a row's y and z parts once. Both builds combine the parts in the same order,
// x + (y + z), so they agree bit for bit.
struct AxisTerms {
  bool overlaps;  // the cell's extent meets the half-ball box's along this axis
  float gap2;     // squared distance from the centre to the cell along this axis
  float front;    // this axis's share of n·(support point − centre), the box's furthest corner along n
};
inline AxisTerms axisTerms(const ActiveHemisphere& h, int a, float lo, float hi) {
  const float g = std::clamp(h.centre[a], lo, hi) - h.centre[a];
  return {!(h.lo[a] > hi) && !(h.hi[a] < lo), g * g,
          h.normal[a] * (0.5f * (lo + hi) - h.centre[a]) + std::abs(h.normal[a]) * (0.5f * (hi - lo))};
}
// Given the y + z parts: inside the sphere, and some corner strictly in front of the light's plane.
inline bool accepts(const ActiveHemisphere& h, const AxisTerms& x, float yzGap2, float yzFront) {
  return x.overlaps && x.gap2 + yzGap2 <= h.radius * h.radius && x.front + yzFront > 0.0f;
}
// E = π L F with F ≤ 1 and F ≤ A/(π d²): E ≤ L · min(π, A/d²), d from the light's bounding sphere.
inline float boundAt(const ActiveHemisphere& h, float gap2) {
  const float d = std::max(std::sqrt(gap2) - h.extent, 0.0f);
  const float shape = d > 0.0f ? std::min(kPi, h.area / (d * d)) : kPi;
  return h.weight * shape;
}

inline bool touches(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  if (!(h.radius > 0.0f)) return false;
  const AxisTerms x = axisTerms(h, 0, lo.x, hi.x), y = axisTerms(h, 1, lo.y, hi.y), z = axisTerms(h, 2, lo.z, hi.z);
  return y.overlaps && z.overlaps && accepts(h, x, y.gap2 + z.gap2, y.front + z.front);
}

inline float bound(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  const AxisTerms x = axisTerms(h, 0, lo.x, hi.x), y = axisTerms(h, 1, lo.y, hi.y), z = axisTerms(h, 2, lo.z, hi.z);
  return boundAt(h, x.gap2 + (y.gap2 + z.gap2));
}

struct Entry {
  std::uint32_t light;
  float bound;
};

// Canonical order inside a cell: largest bound first, then lowest index, so that any build that
// finds the same candidate set produces the same list.
bool before(const Entry& a, const Entry& b) {
  return a.bound != b.bound ? a.bound > b.bound : a.light < b.light;
}

// Sorts a cell's candidates, keeps the first k, pads with kNullLight. Returns whether it overflowed.
bool finishCell(Entry* begin, Entry* end, std::uint32_t k, std::uint32_t* out) {
  const std::size_t n = std::size_t(end - begin);
  auto order = [](const Entry& a, const Entry& b) { return before(a, b); };  // inlined, unlike a function pointer
  // The order is total (one entry per light in a cell), so nth_element picks a unique set: the
  // same list as a partial_sort, in O(n + k log k) rather than O(n log k).
  if (n > k) {
    std::nth_element(begin, begin + k, end, order);
    std::sort(begin, begin + k, order);
  } else {
    std::sort(begin, end, order);
  }
  const std::size_t kept = std::min<std::size_t>(n, k);
  for (std::size_t i = 0; i < kept; ++i) out[i] = begin[i].light;
  for (std::size_t i = kept; i < k; ++i) out[i] = kNullLight;
  return n > k;
}

Grid emptyGrid(const GridDesc& desc) {
  Grid g;
  g.desc = desc;
  g.slots.assign(desc.cellCount() * desc.k, kNullLight);
  return g;
}

std::vector<ActiveHemisphere> hemispheres(std::span<const GridLight> lights, float range) {
  std::vector<ActiveHemisphere> h(lights.size());
  parallelFor(0, lights.size(), [&](std::size_t i) { h[i] = activeHemisphere(lights[i], range); }, 1024);
  return h;
}

// The cells [lo, hi] along each axis whose boxes (cellBox) overlap the half-ball's box [h.lo, h.hi]
// exactly as touchesCell() compares them in float: the floor() guess is corrected cell by cell, so
// no padding is needed (a cell of padding each side would visit (n+3)³ instead of (n+1)³ cells).
// Empty (lo > hi) when the box misses the grid.
void cellRange(const GridDesc& d, const ActiveHemisphere& h, glm::uvec3& lo, glm::uvec3& hi) {
  for (int a = 0; a < 3; ++a) {
    const auto n = std::int64_t(d.dims[a]);
    auto cellLo = [&](std::int64_t c) { return d.origin[a] + float(c) * d.cellSize[a]; };
    auto cellHi = [&](std::int64_t c) { return d.origin[a] + float(c + 1) * d.cellSize[a]; };
    // First cell with cellHi ≥ h.lo, last cell with cellLo ≤ h.hi.
    std::int64_t first = std::clamp<std::int64_t>(std::int64_t(std::floor((h.lo[a] - d.origin[a]) / d.cellSize[a])), 0, n - 1);
    while (first > 0 && !(cellHi(first - 1) < h.lo[a])) --first;
    while (first < n && cellHi(first) < h.lo[a]) ++first;
    std::int64_t last = std::clamp<std::int64_t>(std::int64_t(std::floor((h.hi[a] - d.origin[a]) / d.cellSize[a])), 0, n - 1);
    while (last < n - 1 && !(cellLo(last + 1) > h.hi[a])) ++last;
    while (last >= 0 && cellLo(last) > h.hi[a]) --last;
    if (first > last) {
      lo = glm::uvec3(1u), hi = glm::uvec3(0u);
      return;
    }
    lo[a] = std::uint32_t(first), hi[a] = std::uint32_t(last);
  }
}

// Both builds end here. `visit(fn)` calls fn(cell, begin, end) once for every cell, in parallel,
// with that cell's candidates [begin, end) in any order (fn may reorder them). Sorts and truncates
// every list; conservative mode first visits once more to size the lists (header comment).
template <class Visit>
Grid finishGrid(const GridDesc& desc, Visit&& visit) {
  const std::size_t cells = desc.cellCount();
  GridDesc built = desc;
  std::vector<std::uint32_t> above;
  const bool conservative = desc.conservativeThreshold > 0.0f;
  if (conservative) {
    above.assign(cells, 0u);
    visit([&](std::size_t i, Entry* begin, Entry* end) {
      above[i] = std::uint32_t(std::count_if(begin, end, [&](const Entry& e) { return e.bound >= desc.conservativeThreshold; }));
    });
    const std::uint32_t need = cells ? *std::max_element(above.begin(), above.end()) : 0u;
    built.k = std::clamp(need, desc.k, std::max(desc.k, desc.maxK));
  }
  Grid g = emptyGrid(built);
  std::atomic<std::uint64_t> overflow{0}, dropped{0}, candidates{0};
  visit([&](std::size_t i, Entry* begin, Entry* end) {
    candidates.fetch_add(std::uint64_t(end - begin), std::memory_order_relaxed);
    if (finishCell(begin, end, built.k, g.slots.data() + i * built.k)) overflow.fetch_add(1, std::memory_order_relaxed);
    if (conservative && above[i] > built.k) dropped.fetch_add(above[i] - built.k, std::memory_order_relaxed);
  });
  g.overflowCells = overflow;
  g.droppedAboveThreshold = dropped;
  g.candidates = candidates;
  return g;
}

}  // namespace

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
  std::vector<std::vector<Entry>> found(cells);
  // The thesis's build (§4.2): each cell evaluates the heuristic for every light.
  parallelFor(0, cells, [&](std::size_t i) {
    const glm::uvec3 c(std::uint32_t(i % nx), std::uint32_t((i / nx) % ny), std::uint32_t(i / (std::size_t(nx) * ny)));
    glm::vec3 lo, hi;
    cellBox(desc, c, lo, hi);
    for (std::uint32_t l = 0; l < hs.size(); ++l)
      if (touches(hs[l], lo, hi)) found[i].push_back({l, bound(hs[l], lo, hi)});
  }, 16);
  return finishGrid(desc, [&](auto&& fn) {
    parallelFor(0, cells, [&](std::size_t i) { fn(i, found[i].data(), found[i].data() + found[i].size()); }, 256);
  });
}

Grid buildGridScatter(std::span<const GridLight> lights, const GridDesc& desc) {
  const auto hs = hemispheres(lights, desc.range);
  const std::uint32_t nx = desc.dims.x, ny = desc.dims.y;
  // Two levels, so that no step writes to memory at random: lights are binned into blocks of
  // kBlock³ cells (a light's half-ball box covers a few blocks), then each block, on one thread,
  // scatters its lights into per-cell lists that stay in cache and finishes its cells.
  constexpr std::uint32_t kBlock = 8;
  const glm::uvec3 blocks = (desc.dims + (kBlock - 1u)) / kBlock;
  const std::size_t blockCount = std::size_t(blocks.x) * blocks.y * blocks.z;
  std::vector<glm::uvec3> rangeLo(hs.size()), rangeHi(hs.size());
  std::vector<std::uint8_t> live(hs.size(), 0);
  parallelFor(0, hs.size(), [&](std::size_t l) {
    if (!(hs[l].radius > 0.0f)) return;
    cellRange(desc, hs[l], rangeLo[l], rangeHi[l]);
    live[l] = glm::all(glm::lessThanEqual(rangeLo[l], rangeHi[l]));
  }, 1024);
  auto forEachBlock = [&](std::size_t l, auto&& fn) {
    const glm::uvec3 b0 = rangeLo[l] / kBlock, b1 = rangeHi[l] / kBlock;
    for (std::uint32_t z = b0.z; z <= b1.z; ++z)
      for (std::uint32_t y = b0.y; y <= b1.y; ++y)
        for (std::uint32_t x = b0.x; x <= b1.x; ++x) fn((std::size_t(z) * blocks.y + y) * blocks.x + x);
  };
  // Bin: count, prefix-sum, fill (the order inside a block does not matter: cells are sorted).
  auto counts = std::make_unique<std::atomic<std::uint32_t>[]>(blockCount);
  for (std::size_t b = 0; b < blockCount; ++b) counts[b].store(0, std::memory_order_relaxed);
  parallelFor(0, hs.size(), [&](std::size_t l) {
    if (live[l]) forEachBlock(l, [&](std::size_t b) { counts[b].fetch_add(1, std::memory_order_relaxed); });
  }, 1024);
  std::vector<std::uint64_t> offsets(blockCount + 1, 0);
  for (std::size_t b = 0; b < blockCount; ++b) {
    offsets[b + 1] = offsets[b] + counts[b].load(std::memory_order_relaxed);
    counts[b].store(0, std::memory_order_relaxed);
  }
  std::vector<std::uint32_t> binned(offsets[blockCount]);
  parallelFor(0, hs.size(), [&](std::size_t l) {
    if (live[l])
      forEachBlock(l, [&](std::size_t b) { binned[offsets[b] + counts[b].fetch_add(1, std::memory_order_relaxed)] = std::uint32_t(l); });
  }, 1024);

  // Per block: every cell of the block under each binned light's half-ball box that the heuristic
  // accepts, with the y and z terms computed once per row. Slabs and rows whose distance from the
  // centre along z (and y) alone exceeds the radius are skipped: touchesCell would reject each of
  // their cells (x² + (y² + z²) ≥ y² + z² ≥ z² in float too: rounding is monotone).
  auto visit = [&](auto&& fn) {
    parallelFor(0, blockCount, [&](std::size_t b) {
      const glm::uvec3 bc(std::uint32_t(b % blocks.x), std::uint32_t(b / blocks.x % blocks.y),
                          std::uint32_t(b / (std::size_t(blocks.x) * blocks.y)));
      const glm::uvec3 c0 = bc * kBlock, c1 = glm::min(c0 + kBlock, desc.dims) - 1u;
      // Per-thread lists, reused from block to block (their capacity stays).
      static thread_local std::vector<std::vector<Entry>> local;
      local.resize(kBlock * kBlock * kBlock);
      for (auto& list : local) list.clear();
      for (std::uint64_t i = offsets[b]; i < offsets[b + 1]; ++i) {
        const std::uint32_t l = binned[i];
        const ActiveHemisphere& h = hs[l];
        const float r2 = h.radius * h.radius;
        auto cellLo = [&](int a, std::uint32_t c) { return desc.origin[a] + float(c) * desc.cellSize[a]; };
        auto cellHi = [&](int a, std::uint32_t c) { return desc.origin[a] + float(c + 1) * desc.cellSize[a]; };
        const glm::uvec3 lo = glm::max(rangeLo[l], c0), hi = glm::min(rangeHi[l], c1);
        for (std::uint32_t z = lo.z; z <= hi.z; ++z) {
          const AxisTerms zt = axisTerms(h, 2, cellLo(2, z), cellHi(2, z));
          if (!zt.overlaps || zt.gap2 > r2) continue;
          for (std::uint32_t y = lo.y; y <= hi.y; ++y) {
            const AxisTerms yt = axisTerms(h, 1, cellLo(1, y), cellHi(1, y));
            const float yzGap2 = yt.gap2 + zt.gap2, yzFront = yt.front + zt.front;
            if (!yt.overlaps || yzGap2 > r2) continue;
            auto* row = local.data() + ((z - c0.z) * kBlock + (y - c0.y)) * kBlock;
            for (std::uint32_t x = lo.x; x <= hi.x; ++x) {
              const AxisTerms xt = axisTerms(h, 0, cellLo(0, x), cellHi(0, x));
              if (accepts(h, xt, yzGap2, yzFront)) row[x - c0.x].push_back({l, boundAt(h, xt.gap2 + yzGap2)});
            }
          }
        }
      }
      for (std::uint32_t z = c0.z; z <= c1.z; ++z)
        for (std::uint32_t y = c0.y; y <= c1.y; ++y)
          for (std::uint32_t x = c0.x; x <= c1.x; ++x) {
            auto& list = local[((z - c0.z) * kBlock + (y - c0.y)) * kBlock + (x - c0.x)];
            fn((std::size_t(z) * ny + y) * nx + x, list.data(), list.data() + list.size());
          }
    });
  };
  return finishGrid(desc, visit);
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

}  // namespace bounce::vlm

namespace bounce::vlm {

std::vector<GridLight> randomGridScene(std::uint32_t count, std::uint64_t seed) {
  std::vector<GridLight> lights(count);
  const float size = 1.5f / std::cbrt(float(std::max(count, 1u)));
  parallelFor(0, count, [&](std::size_t i) {
    math::Pcg32 rng(seed, i);  // one stream per light: the same scene whatever the thread count
    auto next3 = [&] { return glm::vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()); };
    const glm::vec3 c = next3();
    GridLight& l = lights[i];
    l.v0 = c + (next3() - 0.5f) * size, l.v1 = c + (next3() - 0.5f) * size, l.v2 = c + (next3() - 0.5f) * size;
    l.weight = 0.1f + rng.nextFloat();
  }, 1024);
  return lights;
}

}  // namespace bounce::vlm
