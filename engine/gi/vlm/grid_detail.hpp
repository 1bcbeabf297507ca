#pragma once
// What the two VLM grid builds (grid.cpp: gather; grid_scatter.cpp: scatter) share, so that they
// agree slot for slot: the heuristic and the bound split per axis, the overflow ranking key, the
// per-cell candidate list, and the common ending (finishGrid). Internal to engine/gi/vlm.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/combinable.h>

#include "engine/gi/vlm/grid.hpp"

namespace bounce::gi::vlm::detail {

inline constexpr float kPi = 3.14159265358979f;

// The heuristic and the bound (public as touchesCell / cellBound), split per axis so the scatter
// build can compute a row's y and z parts once. Both builds combine the parts in the same order,
// x + (y + z), so they agree bit for bit.
struct AxisTerms {
  float gap2;   // squared distance from the centre to the cell along this axis
  float front;  // this axis's share of n·(corner − centre), the cell's corner furthest along n
};
// `front` takes that corner itself (hi where n_a > 0, else lo) rather than mid ± half: the same
// number in exact arithmetic, and in float a monotone function of the cell index. c, n: the
// light's centre and normal along the axis; [lo, hi]: the cell's extent.
inline AxisTerms axisTerms(float c, float n, float lo, float hi) {
  const float g = std::clamp(c, lo, hi) - c;
  return {g * g, n * ((n > 0.0f ? hi : lo) - c)};
}
// The cell's extent meets the half-ball box's along axis a.
inline bool overlapsAxis(const ActiveHemisphere& h, int a, float lo, float hi) { return !(h.lo[a] > hi) && !(h.hi[a] < lo); }
// Given the three parts: inside the sphere, and some corner strictly in front of the light's plane.
inline bool accepts(float radius2, const AxisTerms& x, float yzGap2, float yzFront) {
  return x.gap2 + yzGap2 <= radius2 && x.front + yzFront > 0.0f;
}
// E = π L F with F ≤ 1 and F ≤ A/(π d²): E ≤ L · min(π, A/d²), d from the light's bounding sphere.
// (The scatter build evaluates the same IEEE operations four cells at a time.)
inline float boundAt(float extent, float area, float weight, float gap2) {
  const float d = std::max(std::sqrt(gap2) - extent, 0.0f);
  const float shape = d > 0.0f ? std::min(kPi, area / (d * d)) : kPi;
  return weight * shape;
}

inline bool touches(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  if (!(h.radius > 0.0f)) return false;
  if (!overlapsAxis(h, 0, lo.x, hi.x) || !overlapsAxis(h, 1, lo.y, hi.y) || !overlapsAxis(h, 2, lo.z, hi.z)) return false;
  const AxisTerms x = axisTerms(h.centre.x, h.normal.x, lo.x, hi.x), y = axisTerms(h.centre.y, h.normal.y, lo.y, hi.y),
                  z = axisTerms(h.centre.z, h.normal.z, lo.z, hi.z);
  return accepts(h.radius * h.radius, x, y.gap2 + z.gap2, y.front + z.front);
}

inline float bound(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi) {
  const AxisTerms x = axisTerms(h.centre.x, h.normal.x, lo.x, hi.x), y = axisTerms(h.centre.y, h.normal.y, lo.y, hi.y),
                  z = axisTerms(h.centre.z, h.normal.z, lo.z, hi.z);
  return boundAt(h.extent, h.area, h.weight, x.gap2 + (y.gap2 + z.gap2));
}

// The overflow ranking of a (light, cell) pair as one integer, smaller = kept first: largest bound
// first, then lowest light index. A positive float's bits order like the float, so their complement
// goes in the high word; a bound that is not positive (a black or NaN weight) ranks last.
inline std::uint32_t boundBits(float bound) { return bound > 0.0f ? std::bit_cast<std::uint32_t>(bound) : 0u; }
inline std::uint64_t rankKeyFromBits(std::uint32_t bits, std::uint32_t light) {
  return (std::uint64_t(~bits) << 32) | light;
}
inline std::uint64_t rankKey(float bound, std::uint32_t light) { return rankKeyFromBits(boundBits(bound), light); }
inline std::uint32_t lightOf(std::uint64_t key) { return std::uint32_t(key); }

// Rearranges keys[0, n) so that its k smallest come first (0 < k < n; keys distinct). A quickselect
// whose partition step has no data-dependent branch (a cell's keys arrive in no useful order, so a
// branchy nth_element mispredicts about every other comparison) and partitions out of place (an
// in-place branch-free partition reloads what it just stored). The result is a function of the
// input sequence alone, which is what lets both builds agree slot for slot.
void selectBest(std::uint64_t* keys, std::uint32_t n, std::uint32_t k);

// One cell's list while a build runs: keys appended in the order offered; when `capacity` fill
// up, the k best are kept (selectBest) and appending goes on. Both builds offer every cell its
// candidates in increasing light index, so they end with the same keys in the same slots. The
// stored order is that offer-and-select order (packed, nulls last), not sorted: the shader reads
// every slot up to the first null, in any order, and a sort per cell would cost more than the
// rest of the build.
struct CandidateList {
  std::uint64_t* keys;
  std::uint32_t k, capacity;  // capacity > k
  std::uint32_t size = 0;
  std::uint32_t offered = 0;

  void offer(std::uint64_t key) {
    if (size == capacity) {
      selectBest(keys, size, k);
      size = k;
    }
    keys[size++] = key;
    ++offered;
  }
  // The kept keys, best k (in the order above) when it overflowed.
  std::uint32_t finish() {
    if (size > k) selectBest(keys, size, k), size = k;
    return size;
  }
};
// Slots a list appends into before it compacts: twice k for the usual K (a compaction per k new
// candidates), k + 256 for very long lists.
inline std::uint32_t listCapacity(std::uint32_t k) { return k + std::clamp(k, 16u, 256u); }

// Conservative mode's first pass: how many of a cell's candidates have a bound ≥ the threshold,
// i.e. a key ≤ the largest key such a bound can have.
struct CountAbove {
  std::uint64_t limit;
  std::uint32_t count = 0;
  void offer(std::uint64_t key) { count += key <= limit; }
};

// The cells [lo, hi] along each axis whose boxes (cellBox) overlap the half-ball's box [h.lo, h.hi]
// exactly as touchesCell() compares them in float (empty, lo > hi, when it misses the grid).
void cellRange(const GridDesc& d, const ActiveHemisphere& h, glm::uvec3& lo, glm::uvec3& hi);

// Both builds end here. `pass(capacity, makeCell, done)` offers every cell's candidates, in
// increasing light index, to a cell state made by makeCell(scratch) (scratch: `capacity` keys of
// its own) and calls done(cell, state) once per cell, in parallel. Conservative mode first runs a
// counting pass to size the lists (grid.hpp). Writes every field of `g`.
template <class Pass>
void finishGrid(const GridDesc& desc, Pass&& pass, Grid& g) {
  const std::size_t cells = desc.cellCount();
  GridDesc built = desc;
  std::vector<std::uint32_t> above;
  const bool conservative = desc.conservativeThreshold > 0.0f;
  if (conservative) {
    above.assign(cells, 0u);
    const std::uint64_t limit = rankKey(desc.conservativeThreshold, 0xFFFFFFFFu);
    pass(0u, [&](std::uint64_t*) { return CountAbove{limit}; }, [&](std::size_t i, CountAbove& c) { above[i] = c.count; });
    const std::uint32_t need = cells ? *std::max_element(above.begin(), above.end()) : 0u;
    built.k = std::clamp(need, desc.k, std::max(desc.k, desc.maxK));
  }
  g.desc = built;
  g.slots.resize(cells * built.k);  // every slot is written below (a reused grid keeps its memory)
  g.overflowCells = g.droppedAboveThreshold = g.candidates = 0;
  struct Counts {
    std::uint64_t overflow = 0, dropped = 0, candidates = 0;
  };
  tbb::combinable<Counts> counts;
  const std::uint32_t k = built.k;
  pass(listCapacity(k), [&](std::uint64_t* scratch) { return CandidateList{scratch, k, listCapacity(k)}; },
       [&](std::size_t i, CandidateList& list) {
         std::uint32_t* out = g.slots.data() + i * k;
         const std::uint32_t kept = list.finish();
         for (std::uint32_t s = 0; s < kept; ++s) out[s] = lightOf(list.keys[s]);
         std::fill(out + kept, out + k, kNullLight);
         if (list.offered) {
           Counts& c = counts.local();
           c.candidates += list.offered;
           c.overflow += list.offered > k;
           if (conservative && above[i] > k) c.dropped += above[i] - k;
         }
       });
  counts.combine_each([&](const Counts& c) {
    g.overflowCells += c.overflow;
    g.droppedAboveThreshold += c.dropped;
    g.candidates += c.candidates;
  });
}

// One pass over the lights: their active hemispheres.
std::vector<ActiveHemisphere> hemispheres(std::span<const GridLight> lights, float range);

}  // namespace bounce::gi::vlm::detail
