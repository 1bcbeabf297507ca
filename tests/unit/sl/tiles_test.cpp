// SL pass 2's screen tiles (engine/gi/sl/tiles.hpp): which SLs each 16×16 tile's pixels may need.
// The property that keeps the tiled pass's image equal to the full-screen one: every receiver inside
// an SL's influence ball (|p − c| < F·r, where rule 0 has not yet culled it) projects into a listed
// tile with that SL's bit set.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/sl/tiles.hpp"

namespace bounce::gi::sl {
namespace {

// A camera at the origin looking down −z, 90° vertical field of view, Vulkan clip space (+Y down).
glm::mat4 viewProj(glm::uvec2 res) {
  glm::mat4 proj = glm::perspectiveRH_ZO(glm::half_pi<float>(), float(res.x) / float(res.y), 0.1f, 100.0f);
  proj[1][1] *= -1.0f;
  return proj;
}

const ShadeTile* find(const std::vector<ShadeTile>& tiles, std::uint32_t tx, std::uint32_t ty) {
  for (const ShadeTile& t : tiles)
    if (t.tile.x == tx && t.tile.y == ty) return &t;
  return nullptr;
}

TEST(SlTiles, ListsTheTilesAnInfluenceBallMeetsWithItsBitAndNoOthers) {
  const glm::uvec2 res(160, 160);
  std::vector<ShadedSphere> spheres(41);
  for (ShadedSphere& s : spheres) s = {glm::vec3(40.0f, 0.0f, -10.0f), 0.25f};  // beside the frustum
  spheres[0].centre = glm::vec3(0.0f, 0.0f, -10.0f);   // word 0, bit 0
  spheres[40].centre = glm::vec3(0.0f, 0.0f, -10.0f);  // word 1, bit 8
  // Ball radius F·r = 3 at distance 10: its silhouette spans 80 ± 80·tan(asin 0.3) = 80 ± 25.2 pixels,
  // tiles 3..6. The cube around it (half-size 3, near face at depth 7: 80 ± 80·3/7, tiles 2..7) would
  // list 36 tiles; the ball test against each tile's frustum keeps 16.
  const float F = 12.0f;
  const std::vector<ShadeTile> tiles = binTiles(viewProj(res), res, spheres, F);
  ASSERT_EQ(tiles.size(), 16u) << "tiles 3..6 × 3..6: pixels 54.8 … 105.2";
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const ShadeTile& t = tiles[k];
    EXPECT_EQ(t.tile, glm::uvec4(3 + k % 4, 3 + k / 4, 0, 0)) << "row by row";
    EXPECT_EQ(t.mask, glm::uvec4(1u, 1u << 8, 0u, 0u));
  }
}

TEST(SlTiles, EveryReceiverInsideAnInfluenceBallIsInAListedTileWithThatBit) {
  const glm::uvec2 res(320, 180);
  const glm::mat4 vp = viewProj(res);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<ShadedSphere> spheres;
  for (int i = 0; i < 70; ++i)  // three mask words
    spheres.push_back({glm::vec3(8.0f * u(rng), 4.0f * u(rng), -9.0f + 3.0f * u(rng)), 0.03f + 0.02f * (u(rng) + 1.0f)});
  const float F = 12.0f;
  const std::vector<ShadeTile> tiles = binTiles(vp, res, spheres, F);
  const TileGrid grid = tileGrid(res);
  EXPECT_LT(tiles.size(), grid.count()) << "some tiles are left out";
  int checked = 0;
  for (std::size_t i = 0; i < spheres.size(); ++i)
    for (int k = 0; k < 200; ++k) {
      glm::vec3 d(u(rng), u(rng), u(rng));
      if (glm::length(d) > 1.0f) continue;
      const glm::vec3 p = spheres[i].centre + 0.999f * F * spheres[i].radius * d;
      const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
      if (clip.w <= 0.1f) continue;
      const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(res);
      if (pixel.x < 0.0f || pixel.y < 0.0f || pixel.x >= float(res.x) || pixel.y >= float(res.y)) continue;
      const std::uint32_t tx = std::uint32_t(pixel.x) / kScreenTile, ty = std::uint32_t(pixel.y) / kScreenTile;
      const ShadeTile* t = find(tiles, tx, ty);
      ASSERT_NE(t, nullptr) << "sphere " << i << " receiver at pixel " << pixel.x << "," << pixel.y;
      EXPECT_NE(t->mask[int(i / 32)] & (1u << (i % 32)), 0u) << "sphere " << i;
      ++checked;
    }
  EXPECT_GT(checked, 5000);
}

TEST(SlTiles, WithoutAnInfluenceBoundEveryTileListsEverySL) {
  const glm::uvec2 res(100, 50);  // 7 × 4 tiles, the last column and row partial
  std::vector<ShadedSphere> spheres(70, ShadedSphere{glm::vec3(0.0f, 0.0f, 50.0f), 0.1f});  // behind the camera
  const std::vector<ShadeTile> tiles = binTiles(viewProj(res), res, spheres, 0.0f);
  ASSERT_EQ(tiles.size(), 28u);
  for (const ShadeTile& t : tiles) EXPECT_EQ(t.mask, glm::uvec4(0xffffffffu, 0xffffffffu, 0x3fu, 0u));
  EXPECT_TRUE(binTiles(viewProj(res), res, {}, 12.0f).empty());
}

}  // namespace
}  // namespace bounce::gi::sl
