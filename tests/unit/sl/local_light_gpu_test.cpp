// SL local lights' GLSL (shaders/sl/local_light.glsl via local_light_selftest.comp) against
// sl::localLightVisibility (the double-precision reference, Cap form): receivers on a floor under two
// objects' spheres and inside / on a sphere, for a large light, a small one (the planar-lens path)
// and a point; every output finite and in [0, 1].
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "engine/gi/sl/local_light.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/testing.hpp"
#include "shade_selftest.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

// fp32 against double: the lens's three acos take arguments near ±1 where a float's rounding becomes
// ~√ε in angle, and below 0.02 rad the GLSL takes the planar lens (local_light.glsl kSlLocalPlanar).
// Measured worst: 6.8e-3 (R 0.4, spherical lens), 2.5e-3 (R 0.02, planar), 1e-11 (point) of the
// light. A receiver on a point light's hard edge may flip (v 0 or 1): counted, must be few.
constexpr double kLocalTolerance = 1.5e-2;

struct Receiver {
  glm::vec4 p, n, light;
};

std::vector<float> runShader(gpu::Context& ctx, const std::vector<ShadedSphere>& spheres, std::span<const Receiver> receivers) {
  ShadeData data(ctx, 4);
  data.setSpheres(spheres);
  gpu::Buffer intensity(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.intensity"});
  std::memset(intensity.mapped(), 0, intensity.size());
  const gpu::SpecConstants spec = ShadeData::specialization(4, Blocking::PerObject, std::uint32_t(spheres.size()), 0.0f);
  const std::vector<glm::vec4> out =
      sltest::runShadeSelfTest<glm::vec4, Receiver>(ctx, data, intensity, "sl/local_light_selftest.comp.spv", spec, receivers);
  std::vector<float> v;
  for (const glm::vec4& x : out) v.push_back(x.x);
  return v;
}

}  // namespace

TEST(SlLocalLightGpu, GlslEqualsTheReferenceForLargeSmallAndPointLights) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  // Two objects above the floor z = 0: a chain of overlapping spheres and a cluster.
  const std::vector<Sphere> spheres{{{-0.3, 0.0, 0.6}, 0.25}, {{-0.1, 0.1, 0.75}, 0.2}, {{0.1, 0.15, 0.9}, 0.18},
                                    {{0.5, -0.6, 0.4}, 0.2},  {{0.7, -0.5, 0.45}, 0.15}, {{0.55, -0.3, 0.7}, 0.12}};
  // Union shares and shadow scales per object, as a baked set gives them (fp32-exact values).
  std::vector<ShadedSphere> shaded;
  std::vector<double> share, scale;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    shaded.push_back({glm::vec3(spheres[i].centre), float(spheres[i].radius), glm::mat3(1.0f), i < 3 ? 0u : 1u,
                      i < 3 ? 0.75f : 0.875f, i < 3 ? 0.5f : 0.625f});
    share.push_back(shaded.back().share);
    scale.push_back(shaded.back().silhouette);
  }
  for (const float radius : {0.4f, 0.02f, 0.0f}) {
    const glm::vec4 light(0.1f, -0.1f, 2.5f, radius);
    std::vector<Receiver> r;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x)
        r.push_back({glm::vec4(-1.2f + 2.4f * float(x) / 15.0f, -1.2f + 2.4f * float(y) / 15.0f, 0.0f, 0.0f),
                     glm::vec4(0, 0, 1, 0), light});
    // Inside, on and just outside the first sphere, facing up and sideways.
    for (float t : {0.3f, 0.6f, 0.99f, 1.0f, 1.01f})
      for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)})
        r.push_back({glm::vec4(glm::vec3(-0.3f, 0.0f, 0.6f) + t * 0.25f * glm::vec3(0, 0, -1), 0.0f), glm::vec4(n, 0.0f), light});
    const std::vector<float> gpu = runShader(ctx, shaded, r);
    double worst = 0.0;
    int flips = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      ASSERT_TRUE(std::isfinite(gpu[i]) && gpu[i] >= 0.0f && gpu[i] <= 1.0f) << i;
      const double ref = localLightVisibility(spheres, {glm::dvec3(glm::vec3(light)), double(light.w)},
                                              glm::dvec3(glm::vec3(r[i].p)), glm::dvec3(glm::vec3(r[i].n)), 4, 0.0,
                                              LocalForm::Cap, sh::LogKind::Windowed, share, scale);
      const double e = std::abs(double(gpu[i]) - ref);
      if (radius == 0.0f && e > 0.5)
        ++flips;  // a point light's hard edge through this receiver: float and double disagree on the side
      else
        worst = std::max(worst, e);
    }
    std::printf("light R %.2f: worst |GPU - C++| %.2e, %d edge flips of %zu\n", double(radius), worst, flips, r.size());
    EXPECT_LT(worst, kLocalTolerance);
    EXPECT_LE(flips, 2);
  }
}
