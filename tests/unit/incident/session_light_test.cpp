// The incident-light service's session inputs (engine/gi/incident/session_light.hpp), which DNRT,
// RTF and SL now share through gi::Services instead of building one each: the indirect source is
// the probes' volume when given, else exactly the level's background; the light visibility is built
// on the first ask only (nothing cooked before), once (the same BVH for every later ask), from the
// level's static geometry.
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/core/paths.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/scene/level.hpp"

using namespace bounce;
using namespace bounce::gi;

namespace {

// Under this build's test output, not testing::TempDir() (/tmp/, shared by every build and user on the
// machine: two ctest runs at once removed each other's folder).
std::filesystem::path freshDir(const char* name) {
  const std::filesystem::path d = std::filesystem::path(BOUNCE_TEST_OUT) / "incident" / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

TEST(SessionLight, WithoutProbesTheIndirectLightIsExactlyTheBackground) {
  scene::Level level;
  level.background = glm::vec3(0.2f, 0.3f, 0.4f);
  incident::SessionLight light(level, freshDir("session-light-bg"), nullptr);
  const incident::ConstantEnvironment expected(level.background);
  for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.0f, -2.0f, 3.0f), glm::vec3(1e3f)}) {
    const incident::RadianceSH got = light.indirect().radianceSH(p), want = expected.radianceSH(p);
    for (std::size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got[k], want[k]) << "coefficient " << k;
  }
}

TEST(SessionLight, WithProbesTheIndirectLightIsTheVolumesSHPaddedToNine) {
  // A 2×2×2 order-2 volume, every probe valid with the same 4 coefficients: the lookup at any
  // point inside returns them (normalised weights), and coefficients 4..8 are 0.
  probes::ProbeVolume v;
  v.grid.origin = glm::vec3(0.0f);
  v.grid.spacing = 1.0f;
  v.grid.count = glm::ivec3(2);
  v.order = 2;
  const glm::vec3 c[4] = {{1.0f, 2.0f, 3.0f}, {0.5f, -0.25f, 0.125f}, {-1.0f, 0.0f, 1.0f}, {0.0f, 4.0f, -2.0f}};
  for (std::size_t p = 0; p < v.grid.probeCount(); ++p)
    for (const glm::vec3& k : c) v.sh.push_back(k);
  v.valid.assign(v.grid.probeCount(), 1u);
  // Moments far beyond the cell: the Chebyshev test passes every probe fully.
  v.moments.assign(v.grid.probeCount() * probes::kVisBins, glm::vec2(100.0f, 100.0f * 100.0f));
  scene::Level level;
  level.background = glm::vec3(9.0f);  // must not be used
  incident::SessionLight light(level, freshDir("session-light-probes"), &v);
  const incident::RadianceSH got = light.indirect().radianceSH(glm::vec3(0.3f, 0.6f, 0.4f));
  for (int k = 0; k < 4; ++k)
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[std::size_t(k)][ch], c[k][ch], 1e-5f) << "coefficient " << k;
  for (std::size_t k = 4; k < got.size(); ++k) EXPECT_EQ(got[k], glm::vec3(0.0f)) << "coefficient " << k;
}

TEST(SessionLight, BuildsTheStaticScenesVisibilityOnFirstAskOnly) {
  const std::filesystem::path cache = freshDir("session-light-vis");
  const scene::Level level = scene::loadLevel(contentDir() / "levels" / "cornell-1.json");
  incident::SessionLight light(level, cache, nullptr);
  EXPECT_TRUE(std::filesystem::is_empty(cache)) << "nothing is cooked before a technique asks";
  const incident::SceneVisibility& first = light.lightVisibility();
  EXPECT_FALSE(std::filesystem::is_empty(cache));
  EXPECT_EQ(&first, &light.lightVisibility()) << "one BVH per session";
  // The Cornell room and its two blocks; cornell-1's dynamic prop is not in it (static scene).
  EXPECT_GT(first.bvh().triangleCount(), 12u);
  const scene::Level without = probes::staticLevel(level);
  EXPECT_LT(without.entities.size(), level.entities.size()) << "cornell-1 has a dynamic entity to leave out";
}
