// SL pass 2's tile-list cut (shaders/sl/tile_cut.glsl slBoxCut, run per crafted tile box by
// shaders/sl/tile_cut_selftest.comp): an SL stays listed exactly when its influence ball (radius
// 1.001·F·r plus the slack) meets the box holding the tile's receivers; an empty box (a background
// tile) lists nothing; F = 0 keeps every listed SL; the cut never adds an SL. Checked bit for bit.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/testing.hpp"
#include "shade_selftest.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

struct Box {
  glm::vec4 lo, hi;
  glm::uvec4 mask;
};
static_assert(sizeof(Box) == 48);

// The cut list of each box over `spheres`, with rule 0's F = influence.
std::vector<glm::uvec4> runCut(gpu::Context& ctx, const std::vector<ShadedSphere>& spheres, const std::vector<Box>& boxes,
                               float influence) {
  ShadeData data(ctx, 4);
  data.setSpheres(spheres);
  gpu::Buffer intensity(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.intensity"});
  std::memset(intensity.mapped(), 0, intensity.size());
  gpu::SpecConstants spec;
  std::uint32_t f;
  std::memcpy(&f, &influence, 4);
  spec.push_back(f);  // tile_cut_selftest.comp kInfluence
  return sltest::runShadeSelfTest<glm::uvec4, Box>(ctx, data, intensity, "sl/tile_cut_selftest.comp.spv", spec, boxes);
}

glm::uvec4 bits(std::initializer_list<std::uint32_t> ids) {
  glm::uvec4 m(0u);
  for (std::uint32_t i : ids) m[int(i / 32)] |= 1u << (i % 32);
  return m;
}

}  // namespace

TEST(SlTileCutGpu, KeepsExactlyTheSLsWhoseInfluenceBallMeetsTheTilesReceivers) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  // F = 6, r = 0.1: balls of 0.6 m (0.6006 m with the 1.001 slack). Box: the floor patch
  // [0, 1]² × {0} (a tile that sees only floor). SLs 0–39, far away unless set below, so bits in
  // all of words 0 and 1 are exercised.
  std::vector<ShadedSphere> s(40);
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = {glm::vec3(10.0f + float(i), 0.0f, 0.0f), 0.1f};
  s[0].centre = {0.5f, 0.5f, 0.5f};    // 0.5 above the patch: kept
  s[1].centre = {0.5f, 0.5f, 0.7f};    // 0.7 above: cut
  s[2].centre = {2.0f, 0.5f, 0.0f};    // 1.0 beside it: cut
  s[3].centre = {1.3f, 1.3f, 0.0f};    // 0.42 from the corner: kept
  s[4].centre = {1.4f, 1.4f, 0.2f};    // 0.6 from the corner, on the ball (rule 0 gives 0 there): kept, conservative
  s[5].centre = {1.42f, 1.42f, 0.2f};  // 0.628 from the corner: cut
  s[33].centre = {0.2f, 0.9f, -0.3f};  // below, 0.3 from the patch (word 1): kept
  s[34].centre = {0.2f, 0.9f, -0.3f};
  s[34].radius = 0.04f;                // the same centre, ball 0.24: cut
  s[35].centre = {0.5f, 0.5f, 0.0f};   // on the patch, but not listed: stays out
  const glm::uvec4 listed = bits({0, 1, 2, 3, 4, 5, 6, 33, 34});
  std::vector<Box> boxes = {
      {glm::vec4(0.0f), glm::vec4(1.0f, 1.0f, 0.0f, 0.0f), listed},
      // No receiver (every pixel background): the box is empty, nothing is listed.
      {glm::vec4(3.0e38f), glm::vec4(-3.0e38f), listed},
      // A box holding every centre: the cut keeps every listed SL.
      {glm::vec4(-1.0f), glm::vec4(60.0f), listed},
  };
  const auto cut = runCut(ctx, s, boxes, 6.0f);
  EXPECT_EQ(cut[0], bits({0, 3, 4, 33}));
  EXPECT_EQ(cut[1], glm::uvec4(0u));
  EXPECT_EQ(cut[2], listed);
  // Without an influence bound (F = 0) nothing is culled by distance; an empty box still lists nothing.
  const auto uncut = runCut(ctx, s, boxes, 0.0f);
  EXPECT_EQ(uncut[0], listed);
  EXPECT_EQ(uncut[1], glm::uvec4(0u));
  EXPECT_EQ(uncut[2], listed);
}
