// The relight bake (engine/gi/probes/relight.hpp) on a hand-built closed box: surfels area-uniform
// over its faces, and each probe's rays are the probe bake's own directions.
#include <gtest/gtest.h>

#include <array>

#include "engine/gi/probes/relight.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "tests/unit/ref/test_scenes.hpp"

using namespace bounce;
using namespace bounce::gi::probes;

TEST(ProbeRelightBake, SurfelsAreAreaUniformOverTheStaticFaces) {
  // Six equal faces: the stratified area CDF puts count/6 surfels on each, up to the one stratum a
  // face boundary splits (±1), every one on its face's plane with its front normal.
  ref::SceneDesc s;
  s.meshes = ref::test::insideOfCube(0.5f, 0);
  s.materials = {{glm::vec3(0.5f), -1, glm::vec3(0.0f), -1}};
  const std::vector<Surfel> surfels = sampleSurfels(s, 600);
  ASSERT_EQ(surfels.size(), 600u);
  std::array<int, 6> perFace{};
  for (const Surfel& sf : surfels) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(sf.normal[a]) > std::abs(sf.normal[axis])) axis = a;
    EXPECT_NEAR(std::abs(sf.normal[axis]), 1.0f, 1e-6f);
    // Inside of the cube: the normal points inwards, so the face sits at −0.5·sign(n).
    EXPECT_NEAR(sf.position[axis], -0.5f * (sf.normal[axis] > 0 ? 1.0f : -1.0f), 1e-6f);
    ++perFace[std::size_t(2 * axis + (sf.normal[axis] > 0 ? 1 : 0))];
    EXPECT_FLOAT_EQ(sf.area, 6.0f / 600.0f);
    EXPECT_EQ(sf.albedo, glm::vec3(0.5f));
  }
  for (int n : perFace) EXPECT_NEAR(n, 100, 1);
}

TEST(ProbeRelightBake, RaysAreTheProbeBakersDirectionsAndHitFacingSurfels) {
  ref::SceneDesc s;
  s.meshes = ref::test::insideOfCube(0.5f, 0);
  s.materials = {{glm::vec3(0.5f), -1, glm::vec3(0.0f), -1}};
  const ref::SceneBvh bvh(std::move(s));
  const ProbeGrid grid = gridOverBounds(glm::vec3(-0.5f), glm::vec3(0.5f), 0.5f);
  ProbeSettings settings;
  settings.rays = 64;
  const RelightData d = bakeRelight(bvh, grid, settings, 384, "");
  ASSERT_EQ(d.probes(), grid.probeCount());
  for (std::size_t i = 0; i < grid.probeCount(); ++i) {
    // sh::projectMonteCarlo's directions with bakeProbes' seed (bake.hpp probeRaySeed), recorded in order.
    std::vector<glm::dvec3> want;
    sh::projectMonteCarlo([&](const glm::dvec3& dir) { want.push_back(dir); return 0.0; }, 2, 8, probeRaySeed(i));
    ASSERT_EQ(want.size(), 64u);
    for (std::size_t k = 0; k < 64; ++k) {
      EXPECT_EQ(d.dirs[i * 64 + k], glm::vec3(want[k])) << "probe " << i << " ray " << k;
      // A closed box: every ray hits a front face, and its surfel faces the ray.
      const std::uint32_t hit = d.hit[i * 64 + k];
      ASSERT_NE(hit, kRelightMiss);
      EXPECT_LT(glm::dot(d.surfels[hit].normal, d.dirs[i * 64 + k]), 0.0f);
    }
  }
  // Round trip through the cache format.
  const RelightData back = deserializeRelight(serializeRelight(d), "test");
  EXPECT_EQ(back.hit, d.hit);
  EXPECT_EQ(back.dirs, d.dirs);
  ASSERT_EQ(back.surfels.size(), d.surfels.size());
  EXPECT_EQ(back.surfels[7].position, d.surfels[7].position);
}

// The bake's grid search (relight.cpp SurfelGrid) gives exactly the scan's surfel: the nearest one
// facing the ray, ties to the lower index. Points on the box's faces (where the bake's hits are),
// inside it, and outside the surfels' bounds; every direction, so the facing test excludes whole
// faces. The scan was the bake's O(probes · R · surfels) cost (README "Probes relit each frame,
// session 10").
TEST(ProbeRelightBake, GridSearchFindsTheScansNearestFacingSurfel) {
  ref::SceneDesc s;
  s.meshes = ref::test::insideOfCube(0.5f, 0);
  s.materials = {{glm::vec3(0.5f), -1, glm::vec3(0.0f), -1}};
  const std::vector<Surfel> surfels = sampleSurfels(s, 1000);
  math::Pcg32 rng(7);
  std::vector<glm::vec3> q, dir;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 p(rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f, rng.nextFloat() - 0.5f);
    if (i % 3 == 0) p[i % 9 / 3] = (i % 2 ? 0.5f : -0.5f);  // on a face
    if (i % 3 == 1) p *= 3.0f;                             // mostly outside the box
    q.push_back(p);
    dir.push_back(glm::vec3(math::uniformSphere(rng.next2D())));
  }
  q.push_back(glm::vec3(0.0f)), dir.push_back(glm::vec3(0.0f, 0.0f, 1.0f));  // the centre: many ties of distance
  const std::vector<std::uint32_t> got = nearestFacingSurfels(surfels, q, dir);
  ASSERT_EQ(got.size(), q.size());
  std::size_t misses = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const std::uint32_t want = nearestFacingSurfel(surfels, q[i], dir[i]);
    EXPECT_EQ(got[i], want) << "point " << i;
    misses += want == kRelightMiss;
  }
  EXPECT_EQ(misses, 0u);  // some face always faces any direction
}
