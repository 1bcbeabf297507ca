#include "engine/gi/vlm/grid.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "engine/core/parallel.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::vlm {

namespace {

constexpr float kPi = 3.14159265358979f;

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
  if (n > k) std::partial_sort(begin, begin + k, end, before);
  else std::sort(begin, end, before);
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

// Cells whose boxes may overlap [c − r, c + r]: one cell of padding each side so that rounding in
// the index arithmetic can never leave out a cell that touchesCell() accepts.
void cellRange(const GridDesc& d, const ActiveHemisphere& h, glm::uvec3& lo, glm::uvec3& hi) {
  for (int a = 0; a < 3; ++a) {
    const float f0 = std::floor((h.centre[a] - h.radius - d.origin[a]) / d.cellSize[a]) - 1.0f;
    const float f1 = std::floor((h.centre[a] + h.radius - d.origin[a]) / d.cellSize[a]) + 1.0f;
    const float top = float(d.dims[a]) - 1.0f;
    lo[a] = std::uint32_t(std::clamp(f0, 0.0f, top));
    hi[a] = std::uint32_t(std::clamp(f1, 0.0f, top));
    if (f1 < 0.0f || f0 > top) hi[a] = 0, lo[a] = 1;  // wholly outside: empty range
  }
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
  return h;
}

void cellBox(const GridDesc& d, glm::uvec3 c, glm::vec3& lo, glm::vec3& hi) {
  lo = d.origin + glm::vec3(c) * d.cellSize;
  hi = d.origin + glm::vec3(c + 1u) * d.cellSize;
}

bool touchesCell(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  if (!(h.radius > 0.0f)) return false;
  // Bounding boxes first: cheap, and part of the predicate so both builds agree bit for bit.
  if (glm::any(glm::greaterThan(h.centre - h.radius, hi)) || glm::any(glm::lessThan(h.centre + h.radius, lo))) return false;
  const glm::vec3 closest = glm::clamp(h.centre, lo, hi) - h.centre;
  if (glm::dot(closest, closest) > h.radius * h.radius) return false;
  // Some corner strictly in front of the light's plane (the box's support point along the normal).
  const glm::vec3 mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  return glm::dot(h.normal, mid - h.centre) + glm::dot(glm::abs(h.normal), half) > 0.0f;
}

float cellBound(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 closest = glm::clamp(h.centre, lo, hi) - h.centre;
  const float d = std::max(glm::length(closest) - h.extent, 0.0f);
  // E = π L F with F ≤ 1 and F ≤ A/(π d²): E ≤ L · min(π, A/d²).
  const float shape = d > 0.0f ? std::min(kPi, h.area / (d * d)) : kPi;
  return h.weight * shape;
}

std::int64_t Grid::cellOf(glm::vec3 p) const {
  const glm::vec3 f = glm::floor((p - desc.origin) / desc.cellSize);
  if (!glm::all(glm::greaterThanEqual(f, glm::vec3(0.0f))) || !glm::all(glm::lessThan(f, glm::vec3(desc.dims))))
    return -1;
  const glm::uvec3 c(f);
  return std::int64_t((std::uint64_t(c.z) * desc.dims.y + c.y) * desc.dims.x + c.x);
}

Grid buildGridGather(std::span<const GridLight> lights, const GridDesc& desc) {
  Grid g = emptyGrid(desc);
  const auto hs = hemispheres(lights, desc.range);
  std::atomic<std::uint64_t> overflow{0}, candidates{0};
  const std::uint32_t nx = desc.dims.x, ny = desc.dims.y;
  // The thesis's build (§4.2): each cell evaluates the heuristic for every light.
  parallelFor(0, desc.cellCount(), [&](std::size_t i) {
    const glm::uvec3 c(std::uint32_t(i % nx), std::uint32_t((i / nx) % ny), std::uint32_t(i / (std::size_t(nx) * ny)));
    glm::vec3 lo, hi;
    cellBox(desc, c, lo, hi);
    std::vector<Entry> found;
    for (std::uint32_t l = 0; l < hs.size(); ++l)
      if (touchesCell(hs[l], lo, hi)) found.push_back({l, cellBound(hs[l], lo, hi)});
    candidates += found.size();
    if (finishCell(found.data(), found.data() + found.size(), desc.k, g.slots.data() + i * desc.k)) ++overflow;
  }, 16);
  g.overflowCells = overflow;
  g.candidates = candidates;
  return g;
}

Grid buildGridScatter(std::span<const GridLight> lights, const GridDesc& desc) {
  Grid g = emptyGrid(desc);
  const auto hs = hemispheres(lights, desc.range);
  const std::size_t cells = desc.cellCount();
  const std::uint32_t nx = desc.dims.x, ny = desc.dims.y;
  auto counts = std::make_unique<std::atomic<std::uint32_t>[]>(cells);
  for (std::size_t i = 0; i < cells; ++i) counts[i].store(0, std::memory_order_relaxed);

  // Visits every cell under light l's hemisphere box that the heuristic accepts.
  auto forEachCell = [&](std::uint32_t l, auto&& fn) {
    glm::uvec3 lo, hi;
    cellRange(desc, hs[l], lo, hi);
    for (std::uint32_t z = lo.z; z <= hi.z; ++z)
      for (std::uint32_t y = lo.y; y <= hi.y; ++y)
        for (std::uint32_t x = lo.x; x <= hi.x; ++x) {
          glm::vec3 blo, bhi;
          cellBox(desc, {x, y, z}, blo, bhi);
          if (touchesCell(hs[l], blo, bhi)) fn((std::size_t(z) * ny + y) * nx + x, blo, bhi);
        }
  };
  // Pass 1: count per cell.
  parallelFor(0, hs.size(), [&](std::size_t l) {
    if (hs[l].radius > 0.0f)
      forEachCell(std::uint32_t(l), [&](std::size_t cell, glm::vec3, glm::vec3) { counts[cell].fetch_add(1, std::memory_order_relaxed); });
  }, 64);
  // Exclusive prefix sum into offsets; counts become per-cell write cursors.
  std::vector<std::uint64_t> offsets(cells + 1, 0);
  for (std::size_t i = 0; i < cells; ++i) {
    offsets[i + 1] = offsets[i] + counts[i].load(std::memory_order_relaxed);
    counts[i].store(0, std::memory_order_relaxed);
  }
  std::vector<Entry> entries(offsets[cells]);
  // Pass 2: fill. The order within a cell depends on thread timing; finishCell's sort removes it.
  parallelFor(0, hs.size(), [&](std::size_t l) {
    if (hs[l].radius > 0.0f)
      forEachCell(std::uint32_t(l), [&](std::size_t cell, glm::vec3 blo, glm::vec3 bhi) {
        const std::uint32_t slot = counts[cell].fetch_add(1, std::memory_order_relaxed);
        entries[offsets[cell] + slot] = {std::uint32_t(l), cellBound(hs[l], blo, bhi)};
      });
  }, 64);
  std::atomic<std::uint64_t> overflow{0};
  parallelFor(0, cells, [&](std::size_t i) {
    if (finishCell(entries.data() + offsets[i], entries.data() + offsets[i + 1], desc.k, g.slots.data() + i * desc.k))
      overflow.fetch_add(1, std::memory_order_relaxed);
  }, 256);
  g.overflowCells = overflow;
  g.candidates = offsets[cells];
  return g;
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
