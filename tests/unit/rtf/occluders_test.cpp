// The bouncing step's lamp and room light through the posed objects (issue 14, session 18):
// PosedOccluders' world segments through an object posed in its own frame (occluders.hpp), and the room's
// lamp light the objects' shadows take off at a point (room_shadows.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/rtf/occluders.hpp"
#include "engine/gi/rtf/room_shadows.hpp"
#include "tests/support/box_mesh.hpp"
#include "tests/support/point_light.hpp"

namespace bounce::gi::rtf {
namespace {

using bounce::testing::pointLight;  // tests/support/point_light.hpp

// An axis-aligned box [lo, hi] as a closed triangle mesh (the shadow rays' occluder).
ref::SceneDesc boxScene(glm::vec3 lo, glm::vec3 hi) {
  ref::SceneDesc s;
  s.materials.push_back({});
  ref::RefMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  m.normals.assign(8, glm::vec3(0.0f, 1.0f, 0.0f));
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  s.meshes.push_back(std::move(m));
  return s;
}

// A unit box posed by a rotation, a scale of 0.2 and a translation blocks exactly the world rays through
// its posed volume: t is the world's (the direction is not renormalised in its frame), tMax ends the
// segment before it, its own index is left out, and a box with no triangles blocks nothing.
TEST(RtfOccluders, PosedBoxBlocksTheWorldSegmentsThroughIt) {
  std::vector<ref::SceneDesc> scenes = {boxScene(glm::vec3(-0.5f), glm::vec3(0.5f)), ref::SceneDesc{}};
  const PosedOccluders occ(std::move(scenes));
  ASSERT_EQ(occ.size(), 2u);
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 0.0f)) *
                          glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.2f));
  const std::optional<PosedOccluders::Pose> p = occ.pose(0, world);
  ASSERT_TRUE(p.has_value());
  EXPECT_FALSE(occ.pose(1, world).has_value());  // no triangles: nothing to pose
  const std::vector<PosedOccluders::Pose> poses = {*p};
  const glm::vec3 o(1.0f, 0.0f, 0.0f), up(0.0f, 1.0f, 0.0f);  // the box spans y 1.9..2.1 above o
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, 5.0f));
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(occ.occluded(poses, 99, o, up, 1.85f));  // the segment ends 5 cm short of it
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, 1.95f));
  EXPECT_FALSE(occ.occluded(poses, 0, o, up, 5.0f));  // its own rays: left out
  EXPECT_FALSE(occ.occluded(poses, 99, o + glm::vec3(0.2f, 0.0f, 0.0f), up, 5.0f));  // beside it (bounding sphere 0.173 m)
  EXPECT_FALSE(occ.occluded({}, 99, o, up, 5.0f));
  // Sheared: scale (4, 1, 1) after a 45° turn about z makes the box a rhombus reaching x = ±2.83 (σ_max 4),
  // while its columns' norms are 2.92, so a cull sphere of 0.866 × 2.92 = 2.52 m would miss its tips.
  // A vertical ray at x = 2.7 crosses the tip (|y| ≤ 0.032 there); one at x = 2.9 passes beyond it.
  const glm::mat4 sheared = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f, 1.0f, 1.0f)) *
                            glm::rotate(glm::mat4(1.0f), 0.78539816f, glm::vec3(0.0f, 0.0f, 1.0f));
  const std::optional<PosedOccluders::Pose> s = occ.pose(0, sheared);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->cullRadius, 0.5f * std::sqrt(3.0f) * 4.0f, 1e-4f);  // exact σ_max here (Gershgorin row sum 16)
  const std::vector<PosedOccluders::Pose> shearedPoses = {*s};
  EXPECT_TRUE(occ.occluded(shearedPoses, 99, glm::vec3(2.7f, -1.0f, 0.0f), up, 2.0f));
  EXPECT_FALSE(occ.occluded(shearedPoses, 99, glm::vec3(2.9f, -1.0f, 0.0f), up, 2.0f));
}

// The room's lost lamp light (room_shadows.hpp) at χ 0.1 m over a grey floor (ρ 0.5, 4 × 4 m) under a
// lamp 1 m up: none with the blocker away (exactly 0), and with a blocker that shadows the whole floor
// the floor's whole one-bounce light, so its l = 0 term is −∫ Y_00 ρ/π E cos dω over the floor seen from
// χ, computed here on a fine grid over the floor (independent of the directions). Tolerance: 64
// Fibonacci directions of which ~30 see the floor estimate that smooth integral to a few per cent
// (kDirections' error); 10 % allows it.
TEST(RtfRoomShadow, NoneWithoutABlockerAndTheFloorsWholeBounceUnderOne) {
  const ref::SceneBvh level(bounce::testing::floorMesh(2.0f, glm::vec3(0.5f)));
  std::vector<ref::SceneDesc> blocker = {boxScene(glm::vec3(-0.5f), glm::vec3(0.5f))};
  const PosedOccluders occ(std::move(blocker));
  const std::vector<render::LightGpu> lamp = {pointLight(glm::vec3(0, 1, 0), glm::vec3(2.0f))};
  const glm::vec3 chi(0.0f, 0.1f, 0.0f);
  // Away: a small box far to the side.
  const std::vector<PosedOccluders::Pose> away = {*occ.pose(0, glm::translate(glm::mat4(1.0f), glm::vec3(8, 0.5f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.1f)))};
  const incident::RadianceSH none = roomShadow(level, occ, away, lamp, chi);
  for (const glm::vec3& c : none) EXPECT_EQ(c, glm::vec3(0.0f));
  // A thin slab 0.8 m up, 20 m wide: every floor point's ray to the lamp crosses it; χ's rays do not meet it
  // (χ traces the static level only).
  const std::vector<PosedOccluders::Pose> slab = {*occ.pose(0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.8f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(20, 0.01f, 20)))};
  const incident::RadianceSH lost = roomShadow(level, occ, slab, lamp, chi);
  // ∫ over the floor of Y_00 L(x) dω, dω = cos_χ dA / r², L = ρ/π · I cos_l / d², cos_l = 1/d (lamp at height 1).
  const double y00 = 0.28209479177387814, pi = 3.14159265358979323846;
  double want = 0.0;
  const int n = 800;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -2.0 + 4.0 * (i + 0.5) / n, z = -2.0 + 4.0 * (j + 0.5) / n, dA = (4.0 / n) * (4.0 / n);
      const double d2 = x * x + z * z + 1.0, r2 = x * x + z * z + 0.01;
      const double L = 0.5 / pi * 2.0 * (1.0 / std::sqrt(d2)) / d2;
      want += y00 * L * (0.1 / std::sqrt(r2)) * dA / r2;
    }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(-lost[0][c], want, 0.10 * want) << c;
}

// The room's albedo at a hit is its texture's there (ref::surfaceAlbedo, as the probe bake's paths reflect
// it; until session 19 the material's factor alone): the same floor and slab as above, once with factor 1
// times a uniform 0.25 texture and once with factor 0.25 and no texture, lose the same light — and 1/4 of
// a white floor's. Tolerance 1e-6 relative: the bilinear mix of equal texels rounds in the last bit.
TEST(RtfRoomShadow, TheRoomsAlbedoIsItsTextureAtTheHit) {
  const auto floorScene = [](glm::vec3 factor, bool textured) {
    ref::SceneDesc floor;
    if (textured) floor.textures.push_back(ref::RefTexture{2, 2, std::vector<glm::vec3>(4, glm::vec3(0.25f))});
    floor.materials.push_back({factor, textured ? 0 : -1, glm::vec3(0.0f), -1});
    ref::RefMesh m;
    m.positions = {{-2, 0, -2}, {2, 0, -2}, {-2, 0, 2}, {2, 0, 2}};
    m.normals.assign(4, glm::vec3(0, 1, 0));
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    m.indices = {0, 2, 1, 1, 2, 3};
    floor.meshes.push_back(m);
    return floor;
  };
  const ref::SceneBvh textured(floorScene(glm::vec3(1.0f), true)), plain(floorScene(glm::vec3(0.25f), false)),
      white(floorScene(glm::vec3(1.0f), false));
  std::vector<ref::SceneDesc> blocker = {boxScene(glm::vec3(-0.5f), glm::vec3(0.5f))};
  const PosedOccluders occ(std::move(blocker));
  const std::vector<render::LightGpu> lamp = {pointLight(glm::vec3(0, 1, 0), glm::vec3(2.0f))};
  const std::vector<PosedOccluders::Pose> slab = {*occ.pose(0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.8f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(20, 0.01f, 20)))};
  const glm::vec3 chi(0.3f, 0.1f, -0.2f);
  const incident::RadianceSH a = roomShadow(textured, occ, slab, lamp, chi), b = roomShadow(plain, occ, slab, lamp, chi),
                             w = roomShadow(white, occ, slab, lamp, chi);
  ASSERT_LT(a[0].x, -1e-3f);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a[i][c], b[i][c], 1e-6f * std::abs(b[0][c])) << i << " " << c;
      EXPECT_NEAR(a[i][c], 0.25f * w[i][c], 1e-6f * std::abs(b[0][c])) << i << " " << c;
    }
}

// The room's lost light never takes more than the probes' mean holds (a light brighter than the bake's):
// where L₀ + ΔL₀ ≥ 0 the sum is exact; where not, that channel's ΔL is scaled so L₀ + ΔL₀ = 0 exactly.
TEST(RtfRoomShadow, NeverTakesMoreThanTheProbesHold) {
  incident::RadianceSH L{}, dL{};
  L[0] = glm::vec3(2.0f, 1.0f, 0.0f), L[3] = glm::vec3(0.5f);
  dL[0] = glm::vec3(-1.0f, -4.0f, -1.0f), dL[3] = glm::vec3(-0.2f, -0.8f, 0.3f);
  const incident::RadianceSH out = withRoomShadow(L, dL);
  EXPECT_FLOAT_EQ(out[0].x, 1.0f);   // 2 − 1: enough light, exact
  EXPECT_FLOAT_EQ(out[3].x, 0.3f);
  EXPECT_FLOAT_EQ(out[0].y, 0.0f);   // 1 − 4 → scaled by 1/4
  EXPECT_FLOAT_EQ(out[3].y, 0.5f - 0.2f);
  EXPECT_FLOAT_EQ(out[0].z, 0.0f);   // nothing to lose: scale 0
  EXPECT_FLOAT_EQ(out[3].z, 0.5f);
}

}  // namespace
}  // namespace bounce::gi::rtf
