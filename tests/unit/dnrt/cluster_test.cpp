// The clustered mode's CPU halves (engine/gi/dnrt/cluster.hpp): tile masks from projected outer
// cubes, and the field atlas's layout and padding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/dnrt/cluster.hpp"
#include "engine/gi/dnrt/gpu_object.hpp"

namespace bounce::gi::dnrt {
namespace {

// A camera at the origin looking down −z, 90° vertical field of view, square pixels, Vulkan clip
// space (+Y down, depth 0..1) as the renderer builds it.
glm::mat4 viewProj(glm::uvec2 res) {
  glm::mat4 proj = glm::perspectiveRH_ZO(glm::half_pi<float>(), float(res.x) / float(res.y), 0.1f, 100.0f);
  proj[1][1] *= -1.0f;
  return proj;
}

glm::mat4 cube(glm::vec3 centre, float half) {
  glm::mat4 m(half);
  m[3] = glm::vec4(centre, 1.0f);
  return m;
}

TEST(DnrtCluster, ScreenRectOfACubeIsItsProjectedCorners) {
  const glm::uvec2 res(160, 160);
  // A cube of half-size 1 centred 10 m ahead: its near face (z = −9) spans x, y ∈ ±1/9 in NDC
  // (tan 45° = 1), i.e. pixels 80 ± 80/9 = 71.1 .. 88.9, widened to whole pixels 71 .. 89.
  EXPECT_EQ(screenRect(viewProj(res), cube({0, 0, -10}, 1), res), (PixelRect{71, 71, 89, 89}));
  // Off to the right by 3 m: x from (3 − 1)/11 (far face) to (3 + 1)/9 (near face) in NDC.
  const PixelRect right = screenRect(viewProj(res), cube({3, 0, -10}, 1), res);
  EXPECT_EQ(right.x0, std::uint32_t(80 + 80 * 2.0f / 11.0f));   // floor(94.5) = 94
  EXPECT_EQ(right.x1, std::uint32_t(std::ceil(80 + 80 * 4.0f / 9.0f)));  // ceil(115.6) = 116
  // The eye inside the cube, or a corner behind the eye plane: every pixel.
  EXPECT_EQ(screenRect(viewProj(res), cube({0, 0, 0}, 1), res), (PixelRect{0, 0, 160, 160}));
  EXPECT_EQ(screenRect(viewProj(res), cube({0, 0, 5}, 6), res), (PixelRect{0, 0, 160, 160}));
  // Wholly beside the frustum, behind the far plane: nothing.
  EXPECT_TRUE(screenRect(viewProj(res), cube({40, 0, -10}, 1), res).empty());
  EXPECT_TRUE(screenRect(viewProj(res), cube({0, 0, -200}, 1), res).empty());
}

TEST(DnrtCluster, TileMasksHoldEachObjectsBitInTheTilesItTouchesAndBatchesOf32) {
  const glm::uvec2 res(160, 90);  // 10 × 6 tiles of 16 (the last row 10 pixels tall)
  const TileGrid grid = tileGrid(res);
  EXPECT_EQ(grid.tilesX, 10u);
  EXPECT_EQ(grid.tilesY, 6u);
  std::vector<glm::mat4> boxes(34, cube({0, 0, -10}, 1));
  boxes[1] = cube({0, 0, 0}, 1);       // the eye inside: every tile
  boxes[2] = cube({40, 0, -10}, 1);    // off screen: no tile
  boxes[33] = cube({0, 0, 0}, 1);      // batch 1, bit 1
  const std::vector<std::uint32_t> masks = binObjects(viewProj(res), res, boxes);
  ASSERT_EQ(masks.size(), 2 * grid.count());
  // Object 0 (and 3..31, the same cube): 16:9, so NDC x ±(1/9)·(9/16) → pixels 80 ± 5, y ±1/9 →
  // 45 ± 5: tiles x 4..5 (64..95), y 2..3 (32..63), whichever way the pixel edges round.
  int tilesWith0 = 0;
  for (std::uint32_t ty = 0; ty < grid.tilesY; ++ty)
    for (std::uint32_t tx = 0; tx < grid.tilesX; ++tx) {
      const std::uint32_t m = masks[ty * grid.tilesX + tx];
      const bool inRect = tx >= 4 && tx <= 5 && ty >= 2 && ty <= 3;
      EXPECT_EQ(m, inRect ? 0xFFFFFFFBu : 0x2u) << tx << "," << ty;  // bit 2 never; bit 1 everywhere
      tilesWith0 += (m & 1u) ? 1 : 0;
      const std::uint32_t second = masks[grid.count() + ty * grid.tilesX + tx];
      EXPECT_EQ(second, inRect ? 0x3u : 0x2u) << "batch 1: objects 32 and 33";
    }
  EXPECT_EQ(tilesWith0, 4);
}

// A cube turned 45° about the view axis projects to a diamond: the tiles in its bounding
// rectangle's corners are left out, exactly those whose square misses the diamond.
TEST(DnrtCluster, TilesFollowTheProjectedHullNotItsRectangle) {
  const glm::uvec2 res(160, 160);
  // Half-size 4, 10 m ahead: the near face (depth 6) is the hull, a diamond about pixel (80, 80)
  // with corners 80 · 4√2/6 = 75.4 pixels out (the far face, depth 14, lies inside it).
  const glm::mat4 box = cube({0, 0, -10}, 4) * glm::rotate(glm::mat4(1.0f), glm::quarter_pi<float>(), glm::vec3(0, 0, 1));
  const float r = 80.0f * 4.0f * std::sqrt(2.0f) / 6.0f;
  const ScreenHull hull = screenHull(viewProj(res), box, res);
  ASSERT_FALSE(hull.all);
  EXPECT_EQ(hull.points.size(), 4u);
  const std::vector<glm::mat4> boxes = {box};
  const std::vector<std::uint32_t> masks = binObjects(viewProj(res), res, boxes);
  const TileGrid grid = tileGrid(res);
  int flagged = 0, expected = 0;
  for (std::uint32_t ty = 0; ty < grid.tilesY; ++ty)
    for (std::uint32_t tx = 0; tx < grid.tilesX; ++tx) {
      // Distance of the tile's square from the centre in the diamond's (L1) metric.
      const float dx = std::max({16.0f * tx - 80.0f, 0.0f, 80.0f - 16.0f * (tx + 1)});
      const float dy = std::max({16.0f * ty - 80.0f, 0.0f, 80.0f - 16.0f * (ty + 1)});
      const bool meets = dx + dy <= r;
      // Within a pixel of the edge the float hull may go either way; none of these tiles is that close.
      ASSERT_GT(std::abs(dx + dy - r), 1.0f) << tx << "," << ty;
      EXPECT_EQ(masks[ty * grid.tilesX + tx] != 0u, meets) << tx << "," << ty;
      flagged += masks[ty * grid.tilesX + tx] != 0u ? 1 : 0;
      expected += meets ? 1 : 0;
    }
  EXPECT_EQ(flagged, expected);
  EXPECT_LT(flagged, 100);  // the rectangle would be all 10 × 10
  EXPECT_EQ(masks[0], 0u) << "the rectangle's corner tile";
}

Field smallField(int n, int sh, std::uint8_t seed) {
  Field f;
  f.settings.grid = n;
  f.settings.shCount = sh;
  f.textures.assign(std::size_t(textureCount(sh)), std::vector<std::uint8_t>(std::size_t(n) * n * n * 4));
  for (std::size_t t = 0; t < f.textures.size(); ++t)
    for (std::size_t i = 0; i < f.textures[t].size(); ++i) f.textures[t][i] = std::uint8_t(seed + 7 * t + i * 13);
  return f;
}

TEST(DnrtCluster, AtlasStacksPaddedBricksAndCopiesEdges) {
  const Field a = smallField(4, 4, 1), b = smallField(6, 9, 50);
  const std::vector<const Field*> fields = {&a, &b};
  const AtlasLayout l = atlasLayout(fields, 4096);
  EXPECT_EQ(l.size, glm::uvec3(8, 8, 6 + 8));
  EXPECT_EQ(l.z0, (std::vector<std::uint32_t>{0, 6}));
  EXPECT_EQ(l.slots, 7);
  const auto at = [&](const std::vector<std::uint8_t>& t, int x, int y, int z, int c) {
    return t[((std::size_t(z) * l.size.y + y) * l.size.x + x) * 4 + c];
  };
  for (int slot : {0, 3, 6}) {
    const std::vector<std::uint8_t> t = atlasTexels(l, fields, slot);
    ASSERT_EQ(t.size(), std::size_t(8 * 8 * 14 * 4));
    // b's vertex (x, y, z) is texel (1 + x, 1 + y, 6 + 1 + z); its padding repeats the edge vertex.
    for (int z = -1; z <= 6; ++z)
      for (int y = -1; y <= 6; ++y)
        for (int x = -1; x <= 6; ++x)
          for (int c = 0; c < 4; ++c) {
            const std::size_t v = b.vertexIndex(std::clamp(x, 0, 5), std::clamp(y, 0, 5), std::clamp(z, 0, 5));
            ASSERT_EQ(at(t, 1 + x, 1 + y, 7 + z, c), b.textures[std::size_t(slot)][v * 4 + std::size_t(c)]);
          }
    // a (4 SH) has slot 0 only of these; its brick is 6 wide, the rest of its layers zero.
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(at(t, 1 + 2, 1 + 3, 1 + 1, c), slot == 0 ? a.textures[0][a.vertexIndex(2, 3, 1) * 4 + std::size_t(c)] : 0);
      EXPECT_EQ(at(t, 7, 7, 2, c), 0) << "outside a's 6-texel brick";
    }
  }
  // A depth limit leaves out the fields that no longer fit, in order.
  const AtlasLayout one = atlasLayout(fields, 10);
  EXPECT_EQ(one.z0.size(), 1u);
  EXPECT_EQ(one.size, glm::uvec3(6, 6, 6));
  EXPECT_EQ(one.slots, 3);
}

TEST(DnrtCluster, ClusterRecordIsTheFoldedRecordAndItsBrick) {
  DnrtShaderObject f;
  f.worldToQ[1] = glm::vec4(1, 2, 3, 4);
  f.k[6] = glm::vec4(5, 6, 7, 0);
  f.ids.x = 9;
  const DnrtClusterObject c = clusterObject(f, 40);
  EXPECT_EQ(c.worldToQ[1], f.worldToQ[1]);
  EXPECT_EQ(c.k[6], f.k[6]);
  EXPECT_EQ(c.ids.x, 9u);
  EXPECT_EQ(c.atlas, glm::vec4(1.5f, 1.5f, 41.5f, 0.0f));  // vertex (0, 0, 0)'s texel centre after the padding
}

// The probes pass is drawn as a fused object's outer cube only with the eye inside it and no face clipped by
// the near or far plane where the view sees it (eyeInsideOuterCube): otherwise some pixel's ray would leave
// the cube through no drawn face. The camera above: eye at the origin, 90° both ways (tan θ_corner² = 2),
// near 0.1 m, far 100 m.
TEST(DnrtCluster, EyeInsideOuterCubeOnlyWhenNoSeenFaceIsClipped) {
  const glm::mat4 proj = viewProj({160, 160}), view(1.0f);
  EXPECT_TRUE(eyeInsideOuterCube(cube({0, 0, 0}, 1), view, proj));
  EXPECT_FALSE(eyeInsideOuterCube(cube({0, 0, -10}, 1), view, proj)) << "ahead of the eye";
  // The nearest face 0.2 m away: seen at depths ≥ 0.2 cos θ_corner = 0.2/√3 = 0.115 m, beyond the near plane;
  // 0.15 m away: ≥ 0.087 m, so the near plane may clip it where the corner rays meet it.
  EXPECT_TRUE(eyeInsideOuterCube(cube({0.8f, 0, 0}, 1), view, proj));
  EXPECT_FALSE(eyeInsideOuterCube(cube({0.85f, 0, 0}, 1), view, proj));
  // The farthest corner 50√3 = 86.6 m away, inside the far plane; 60√3 = 103.9 m, past it.
  EXPECT_TRUE(eyeInsideOuterCube(cube({0, 0, 0}, 50), view, proj));
  EXPECT_FALSE(eyeInsideOuterCube(cube({0, 0, 0}, 60), view, proj));
  // The eye placed by the view matrix, and a rotated, stretched cube (its faces' distances are not its
  // half-sizes along the world axes): 0.5 m along its short axis from the centre, the face 0.5 m further.
  const glm::mat4 eyeAt = glm::lookAt(glm::vec3(3, 2, 1), glm::vec3(3, 2, 0), glm::vec3(0, 1, 0));
  const glm::mat4 stretched = glm::translate(glm::mat4(1.0f), glm::vec3(3, 2, 1)) *
                              glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 0, 1)) *
                              glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 5.0f, 5.0f));
  EXPECT_TRUE(eyeInsideOuterCube(glm::translate(stretched, glm::vec3(0.5f, 0, 0)), eyeAt, proj));
  EXPECT_FALSE(eyeInsideOuterCube(glm::translate(stretched, glm::vec3(0.95f, 0, 0)), eyeAt, proj)) << "0.05 m";
  EXPECT_FALSE(eyeInsideOuterCube(glm::translate(stretched, glm::vec3(1.5f, 0, 0)), eyeAt, proj)) << "outside";
  // Only a perspective projection as the renderer makes.
  EXPECT_FALSE(eyeInsideOuterCube(cube({0, 0, 0}, 1), view, glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 100.0f)));
}

}  // namespace
}  // namespace bounce::gi::dnrt
