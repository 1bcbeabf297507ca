// incident.glsl on the device agrees with the CPU face (the same file compiled as C++, engine/gi/
// incident) on random lights of every kind, receivers near and far, radii and visibilities: runs
// shaders/common/incident_selftest.comp (as sh_gpu runs sh_selftest.comp).
#include <gtest/gtest.h>

#include <cstring>

#include "engine/gi/incident/incident.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "tests/support/compute_selftest.hpp"

using namespace bounce;

namespace {

// Both faces run the same float code; the device may contract multiply-adds and its sqrt/division
// differ by an ulp or two, amplified by at most the 1/d² (≤ 1e2 here) and 9-term sums: a few 1e-6
// relative to the largest coefficient of the case. 1e-4 of it still catches a wrong constant,
// sign, band factor or light kind (errors ≥ 1e-2).
constexpr double kTolerance = 1e-4;
constexpr std::uint32_t kCases = 512;

struct Case {
  render::LightGpu light;
  float pointRadius[4];
  float visibility[4];
};
struct Output {
  float sh[9][4];
};
static_assert(sizeof(Case) == 112 && sizeof(Output) == 144);

}  // namespace

TEST(IncidentGpu, GlslMatchesCpuFaceForEveryLightKind) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  math::Pcg32 rng(21, 4);
  std::vector<Case> cases(kCases);
  for (std::uint32_t i = 0; i < kCases; ++i) {
    Case& c = cases[i];
    const auto type = render::LightType(i % 3);
    const glm::vec3 pos = (rng.nextFloat3() * 2.0f - 1.0f);
    const glm::vec3 dir = glm::normalize(glm::vec3(math::uniformSphere(rng.next2D())));
    c.light.positionType = glm::vec4(pos, float(type));
    c.light.directionRange = glm::vec4(dir, (i % 7 == 0) ? 1.5f : 0.0f);  // some with a range window
    c.light.radiance = glm::vec4(rng.nextFloat3() * 2.0f, 0.0f);
    const float outer = 0.2f + 0.8f * rng.nextFloat3().x;
    c.light.cone = glm::vec4(std::cos(outer), std::cos(outer * 0.6f), 0.0f, 0.0f);
    c.light.shadow = glm::vec4(-1.0f);
    // Receivers from on the lamp (i % 11 == 0: the hard case) to 1.7 m away; radius 0 or up to 0.3
    // m (so some lamps are inside the receiver's sphere).
    glm::vec3 p = rng.nextFloat3() * 2.0f - 1.0f;
    if (i % 11 == 0) p = pos + glm::vec3(0.01f, 0.0f, 0.0f);
    const float radius = (i % 4 == 0) ? 0.0f : 0.3f * rng.nextFloat3().y;
    c.pointRadius[0] = p.x, c.pointRadius[1] = p.y, c.pointRadius[2] = p.z, c.pointRadius[3] = radius;
    c.visibility[0] = (i % 5 == 0) ? 0.0f : rng.nextFloat3().z;
  }
  const std::vector<Output> results =
      testgpu::runComputeSelfTest<Output>(ctx, "common/incident_selftest.comp.spv", std::span<const Case>(cases));
  ASSERT_EQ(results.size(), kCases);

  int nonZero = 0;
  for (std::uint32_t i = 0; i < kCases; ++i) {
    const Case& c = cases[i];
    gi::incident::RadianceSH cpu{};
    gi::incident::addLight(c.light, glm::vec3(c.pointRadius[0], c.pointRadius[1], c.pointRadius[2]), c.pointRadius[3],
                           c.visibility[0], cpu);
    double scale = 1.0;
    for (const auto& v : cpu) scale = std::max({scale, double(std::abs(v.r)), double(std::abs(v.g)), double(std::abs(v.b))});
    nonZero += cpu[0] != glm::vec3(0.0f);
    for (int k = 0; k < 9; ++k)
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_LT(std::abs(double(results[i].sh[k][ch]) - double(cpu[k][ch])), kTolerance * scale)
            << "case " << i << " (type " << i % 3 << ") coefficient " << k << " channel " << ch;
  }
  EXPECT_GT(nonZero, int(kCases) / 2);  // the cases exercise lit receivers, not only zeros
}
