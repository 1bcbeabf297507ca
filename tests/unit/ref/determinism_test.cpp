// The reference is a pure function of (scene, settings): bit-identical for any thread count and
// any split of the samples into progressive passes.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>

#include "tests/unit/ref/test_scenes.hpp"

namespace bounce::ref {
namespace {

// A closed, lit box with an occluder: every kind of ray (camera, bounce with roulette, shadow).
SceneDesc litBox() {
  SceneDesc s;
  s.materials.push_back({{0.7f, 0.6f, 0.5f}, -1, glm::vec3(0.0f), -1});
  s.materials.push_back({{0.2f, 0.8f, 0.3f}, -1, glm::vec3(0.05f), -1});
  s.meshes = test::insideOfCube(1.0f, 0);
  s.meshes.push_back(test::quad({-0.3f, -0.2f, -0.3f}, {0, 0, 0.6f}, {0.6f, 0, 0}, 1));
  RefLight lamp;
  lamp.position = {0.1f, 0.8f, 0.0f};
  lamp.radiance = glm::vec3(1.0f);
  s.lights.push_back(lamp);
  s.camera = test::lookAt({0.0f, 0.5f, 0.9f}, {0, -0.5f, 0}, {0, 1, 0}, 80.0f);
  return s;
}

TEST(Determinism, SameImageForOneThreadAndAllThreads) {
  // A size that is not a multiple of the tile, and uneven passes, to cover every loop edge.
  TraceSettings settings = test::settings(1, 7, kUnlimitedBounces);
  settings.width = 37;
  settings.height = 21;

  gpu::FloatImage one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    SceneBvh bvh(litBox());  // the BVH is built under the limit too
    settings.passSpp = 3;
    one = trace(bvh, settings);
  }
  SceneBvh bvh(litBox());
  settings.passSpp = 7;
  const gpu::FloatImage all = trace(bvh, settings);

  ASSERT_EQ(one.rgb.size(), all.rgb.size());
  double sum = 0.0;
  for (float v : all.rgb) sum += v;
  EXPECT_GT(sum, 0.0);  // a black image would be trivially identical
  EXPECT_EQ(std::memcmp(one.rgb.data(), all.rgb.data(), one.rgb.size() * sizeof(float)), 0);
}

TEST(Determinism, PathDependsOnlyOnPixelAndSampleIndex) {
  SceneBvh bvh(litBox());
  const TraceSettings settings = test::settings(16, 4, kUnlimitedBounces);
  std::uint64_t rays = 0;
  const glm::dvec3 a = tracePath(bvh, settings, 5, 9, 3, rays);
  tracePath(bvh, settings, 6, 9, 3, rays);  // other work in between changes nothing
  const glm::dvec3 b = tracePath(bvh, settings, 5, 9, 3, rays);
  EXPECT_EQ(a, b);
  // Different samples of one pixel are different paths.
  int differing = 0;
  for (std::uint32_t s = 0; s < 8; ++s) differing += tracePath(bvh, settings, 5, 9, s, rays) != a;
  EXPECT_GE(differing, 6);
}

}  // namespace
}  // namespace bounce::ref
