// The VLM grid (engine/gi/vlm/grid.hpp): the scatter build equals the thesis's gather build slot for
// slot on random scenes, lists are complete when they do not overflow, and overflow keeps the
// lights with the largest irradiance bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "engine/gi/vlm/grid.hpp"
#include "engine/math/sampling.hpp"

using namespace bounce;

namespace {

std::vector<gi::vlm::GridLight> randomLights(std::uint32_t count, float size, std::uint64_t seed) {
  math::Pcg32 rng(seed, 1);
  std::vector<gi::vlm::GridLight> lights(count);
  for (auto& l : lights) {
    const glm::vec3 c = rng.nextFloat3();
    auto jitter = [&] { return (rng.nextFloat3() - 0.5f) * size; };
    l.v0 = c + jitter(), l.v1 = c + jitter(), l.v2 = c + jitter();
    l.weight = 0.1f + rng.nextFloat();
  }
  lights[0].v2 = lights[0].v1;  // one degenerate light: never a candidate
  return lights;
}

}  // namespace

TEST(VlmGrid, ScatterEqualsGatherOnRandomScenes) {
  struct Case {
    std::uint32_t lights, dims, k;
    float size, range;
  };
  // 17³ and 12³: grids that are not a whole number of the scatter's 8³ blocks; K 8 among ~30
  // candidates: lists that compact while they fill.
  const Case cases[] = {{500, 8, 4, 0.1f, 2.5f},   {2000, 12, 16, 0.05f, 1.5f}, {1000, 10, 64, 0.2f, 4.5f},
                        {300, 5, 2, 0.3f, 3.5f},   {3000, 17, 8, 0.06f, 2.5f}};
  gi::vlm::GridScatterBuilder builder;  // reused across cases, as the per-frame dynamic grid is
  gi::vlm::Grid reused;
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const Case& c = cases[i];
    const auto lights = randomLights(c.lights, c.size, 17 + i);
    const auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(c.dims), c.k, c.range);
    const gi::vlm::Grid gather = gi::vlm::buildGridGather(lights, desc);
    const gi::vlm::Grid scatter = gi::vlm::buildGridScatter(lights, desc);
    builder.build(lights, desc, reused);
    EXPECT_EQ(scatter.slots, gather.slots) << "case " << i;
    EXPECT_EQ(reused.slots, gather.slots) << "case " << i;
    EXPECT_EQ(reused.overflowCells, gather.overflowCells) << "case " << i;
    EXPECT_EQ(scatter.overflowCells, gather.overflowCells) << "case " << i;
    EXPECT_EQ(scatter.candidates, gather.candidates) << "case " << i;
    EXPECT_GT(gather.candidates, 0u);
    if (c.k <= 4) {
      EXPECT_GT(gather.overflowCells, 0u) << "case " << i << " should overflow";
    }
    // The degenerate light 0 appears nowhere.
    EXPECT_EQ(std::count(gather.slots.begin(), gather.slots.end(), 0u), 0);
  }
}

// Hostile lights: black, NaN and infinite weights, collinear and coincident vertices, lights far
// outside the grid or straddling its faces, vertices at huge coordinates. Both builds agree, and
// no light that cannot emit (zero area) or lies wholly outside is listed.
TEST(VlmGrid, HostileLightsAgreeAndDegenerateOnesAreNeverListed) {
  auto lights = randomLights(600, 0.1f, 23);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  lights[1].weight = 0.0f;
  lights[2].weight = nan;
  lights[3].weight = inf;
  lights[4].v2 = lights[4].v0 + 2.0f * (lights[4].v1 - lights[4].v0);  // collinear
  lights[5].v0 = lights[5].v1 = lights[5].v2 = glm::vec3(0.5f);          // a point
  lights[6] = {glm::vec3(50.0f), glm::vec3(50.1f, 50.0f, 50.0f), glm::vec3(50.0f, 50.1f, 50.0f), 1.0f};  // far outside
  lights[7] = {glm::vec3(-0.05f, 0.5f, 0.5f), glm::vec3(0.05f, 0.45f, 0.5f), glm::vec3(0.05f, 0.55f, 0.5f), 1.0f};  // on a face
  lights[8] = {glm::vec3(1e30f), glm::vec3(-1e30f, 1e30f, 0.0f), glm::vec3(0.0f, -1e30f, 1e30f), 1.0f};  // huge
  const auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(9), 12, 2.5f);
  const gi::vlm::Grid gather = gi::vlm::buildGridGather(lights, desc);
  const gi::vlm::Grid scatter = gi::vlm::buildGridScatter(lights, desc);
  EXPECT_EQ(scatter.slots, gather.slots);
  EXPECT_EQ(scatter.candidates, gather.candidates);
  for (std::uint32_t never : {0u, 4u, 5u, 6u, 8u})
    EXPECT_EQ(std::count(gather.slots.begin(), gather.slots.end(), never), 0) << "light " << never;
  EXPECT_GT(std::count(gather.slots.begin(), gather.slots.end(), 7u), 0) << "a light on the grid's face lights the cells in front";
}

TEST(VlmGrid, ListsAreCompleteWithoutOverflowAndExcludeTheBackSide) {
  const auto lights = randomLights(400, 0.1f, 5);
  const auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(10), 256, 2.5f);
  const gi::vlm::Grid g = gi::vlm::buildGridScatter(lights, desc);
  ASSERT_EQ(g.overflowCells, 0u);
  math::Pcg32 rng(8, 2);
  int inside = 0, behind = 0;
  for (std::uint32_t l = 1; l < lights.size(); ++l) {
    const auto h = gi::vlm::activeHemisphere(lights[l], desc.range);
    for (int s = 0; s < 20; ++s) {
      const glm::vec3 p = h.centre + (rng.nextFloat3() * 2.0f - 1.0f) * h.radius;
      const std::int64_t cell = g.cellOf(p);
      if (cell < 0) continue;
      const auto list = g.cell(std::uint64_t(cell));
      const bool listed = std::find(list.begin(), list.end(), l) != list.end();
      const glm::vec3 d = p - h.centre;
      if (glm::dot(d, d) < h.radius * h.radius && glm::dot(d, h.normal) > 0.0f) {
        ++inside;
        EXPECT_TRUE(listed) << "light " << l << " missing from the cell of a point in its active hemisphere";
      }
      // A cell lying wholly behind the light's plane never lists it.
      glm::vec3 lo, hi;
      const std::uint64_t ci = std::uint64_t(cell);
      gi::vlm::cellBox(desc, {std::uint32_t(ci % 10), std::uint32_t(ci / 10 % 10), std::uint32_t(ci / 100)}, lo, hi);
      const glm::vec3 mid = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
      if (glm::dot(h.normal, mid - h.centre) + glm::dot(glm::abs(h.normal), half) < 0.0f) {
        ++behind;
        EXPECT_FALSE(listed);
      }
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(behind, 100);
}

namespace {

glm::uvec3 cellCoords(const gi::vlm::GridDesc& desc, std::uint64_t c) {
  return {std::uint32_t(c % desc.dims.x), std::uint32_t(c / desc.dims.x % desc.dims.y),
          std::uint32_t(c / (std::uint64_t(desc.dims.x) * desc.dims.y))};
}

// A cell's list as a sorted set of light indices (slots are packed, nulls last).
std::vector<std::uint32_t> listed(std::span<const std::uint32_t> cell) {
  std::vector<std::uint32_t> out(cell.begin(), std::find(cell.begin(), cell.end(), gi::vlm::kNullLight));
  EXPECT_TRUE(std::all_of(cell.begin() + std::ptrdiff_t(out.size()), cell.end(), [](std::uint32_t i) { return i == gi::vlm::kNullLight; }))
      << "slots are packed";
  std::sort(out.begin(), out.end());
  return out;
}

// Brute force: the k candidates of cell c with the largest bound (ties: lower index), as a sorted set.
std::vector<std::uint32_t> bestK(std::span<const gi::vlm::GridLight> lights, const gi::vlm::GridDesc& desc, std::uint64_t c,
                                 std::uint32_t k) {
  glm::vec3 lo, hi;
  gi::vlm::cellBox(desc, cellCoords(desc, c), lo, hi);
  std::vector<std::pair<float, std::uint32_t>> found;
  for (std::uint32_t l = 0; l < lights.size(); ++l) {
    const auto h = gi::vlm::activeHemisphere(lights[l], desc.range);
    if (gi::vlm::touchesCell(h, lo, hi)) found.push_back({gi::vlm::cellBound(h, lo, hi), l});
  }
  std::sort(found.begin(), found.end(), [](auto& a, auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < std::min<std::size_t>(k, found.size()); ++i) out.push_back(found[i].second);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(VlmGrid, OverflowKeepsTheLargestBounds) {
  const auto lights = randomLights(800, 0.15f, 9);
  // K 3 overflows at most cells; K 40 in some (and its lists go through a compaction: more
  // candidates than the list's capacity of 2K in the fullest cells).
  for (std::uint32_t k : {3u, 40u}) {
    const auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(6), k, 3.5f);
    const gi::vlm::Grid small = gi::vlm::buildGridScatter(lights, desc);
    auto all = desc;
    all.k = 4096;
    const gi::vlm::Grid full = gi::vlm::buildGridScatter(lights, all);
    ASSERT_EQ(full.overflowCells, 0u);
    ASSERT_GT(small.overflowCells, 0u);
    std::uint64_t overflowing = 0;
    std::size_t most = 0;
    for (std::uint64_t c = 0; c < desc.cellCount(); ++c) {
      EXPECT_EQ(listed(small.cell(c)), bestK(lights, desc, c, k)) << "K " << k << " cell " << c;
      const std::size_t every = listed(full.cell(c)).size();
      most = std::max(most, every);
      if (every > k) ++overflowing;
    }
    EXPECT_EQ(overflowing, small.overflowCells);
    if (k == 40u) {
      EXPECT_GT(most, 2u * k) << "no cell exercised the list's compaction";
    }
  }
}

namespace {

// Brute force: how many of cell c's candidates have a bound of at least `threshold`.
std::uint32_t aboveThreshold(std::span<const gi::vlm::GridLight> lights, const gi::vlm::GridDesc& desc, std::uint64_t c,
                             float threshold) {
  glm::vec3 lo, hi;
  gi::vlm::cellBox(desc, cellCoords(desc, c), lo, hi);
  std::uint32_t n = 0;
  for (const auto& l : lights) {
    const auto h = gi::vlm::activeHemisphere(l, desc.range);
    if (gi::vlm::touchesCell(h, lo, hi) && gi::vlm::cellBound(h, lo, hi) >= threshold) ++n;
  }
  return n;
}

}  // namespace

// Conservative overflow mode (issue 5 §4): no light whose bound reaches the threshold is dropped
// while maxK allows; the lists grow to the largest such count (never below K); both builds agree;
// with a small maxK the pairs that still do not fit are counted exactly.
TEST(VlmGrid, ConservativeModeKeepsEveryLightAboveTheThreshold) {
  const auto lights = randomLights(800, 0.15f, 9);
  auto desc = gi::vlm::fitGrid(glm::vec3(0.0f), glm::vec3(1.0f), glm::uvec3(6), 3, 3.5f);
  const gi::vlm::Grid plain = gi::vlm::buildGridScatter(lights, desc);
  ASSERT_GT(plain.overflowCells, 0u);
  EXPECT_EQ(plain.droppedAboveThreshold, 0u);

  desc.conservativeThreshold = 2.0f;  // of cellBound's range here, about (0.03, 3.5): keeps a few per cell
  std::uint32_t need = 0;
  std::vector<std::uint32_t> above(desc.cellCount());
  for (std::uint64_t c = 0; c < desc.cellCount(); ++c) need = std::max(need, above[c] = aboveThreshold(lights, desc, c, 2.0f));
  ASSERT_GT(need, desc.k) << "the threshold should force longer lists than K";
  ASSERT_LT(need, desc.maxK);

  const gi::vlm::Grid scatter = gi::vlm::buildGridScatter(lights, desc);
  const gi::vlm::Grid gather = gi::vlm::buildGridGather(lights, desc);
  EXPECT_EQ(scatter.slots, gather.slots);
  EXPECT_EQ(scatter.desc.k, need);
  EXPECT_EQ(gather.desc.k, need);
  EXPECT_EQ(scatter.droppedAboveThreshold, 0u);
  EXPECT_EQ(scatter.overflowCells, gather.overflowCells);
  for (std::uint64_t c = 0; c < desc.cellCount(); ++c) {
    // The kept set is the `need` best, so it holds every above-threshold light.
    const auto kept = listed(scatter.cell(c));
    EXPECT_EQ(kept, bestK(lights, desc, c, need)) << "cell " << c;
    EXPECT_GE(kept.size(), std::size_t(above[c]));
  }

  // maxK below what the threshold asks for: lists stop at maxK and the rest is counted.
  desc.maxK = desc.k + 1;
  const gi::vlm::Grid capped = gi::vlm::buildGridScatter(lights, desc);
  EXPECT_EQ(capped.desc.k, desc.maxK);
  std::uint64_t dropped = 0;
  for (std::uint32_t a : above) dropped += a > desc.maxK ? a - desc.maxK : 0;
  ASSERT_GT(dropped, 0u);
  EXPECT_EQ(capped.droppedAboveThreshold, dropped);
  EXPECT_EQ(gi::vlm::buildGridGather(lights, desc).droppedAboveThreshold, dropped);

  // A threshold no bound reaches changes nothing but the report.
  desc.maxK = 256;
  desc.conservativeThreshold = 1e6f;
  const gi::vlm::Grid high = gi::vlm::buildGridScatter(lights, desc);
  EXPECT_EQ(high.slots, plain.slots);
  EXPECT_EQ(high.desc.k, plain.desc.k);
}

TEST(VlmGrid, OverflowLineNamesBothGridsAndTheConservativeCount) {
  gi::vlm::OverflowReport r;
  r.cellsPerGrid = 4096;
  r.k = 32;
  r.staticCells = 12;
  r.dynamicCells = 3;
  r.dynamicMaxCells = 5;
  EXPECT_EQ(gi::vlm::formatOverflow(r), "vlm overflow: static 12/4096 cells, dynamic 3/4096 (most 5), K 32");
  r.conservative = true;
  r.droppedAboveThreshold = 7;
  EXPECT_EQ(gi::vlm::formatOverflow(r),
            "vlm overflow: static 12/4096 cells, dynamic 3/4096 (most 5), K 32, conservative: 7 candidates above the "
            "threshold dropped");
}
