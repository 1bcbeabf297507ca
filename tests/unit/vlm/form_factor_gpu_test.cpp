// shaders/vlm/form_factor.glsl on the GPU agrees with engine/gi/vlm/form_factor.hpp (float) on
// the same inputs: random configurations plus the awkward ones (horizon crossings, a vertex at the
// shading point, degenerate and back-facing lights). Runs shaders/vlm/form_factor_selftest.comp.
#include <gtest/gtest.h>

#include <cstring>
#include <iostream>

#include "engine/gi/vlm/form_factor.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "tests/support/compute_selftest.hpp"

using namespace bounce;

namespace {

// Same float code on both sides, but the GPU may fuse multiply-adds and its atan/sqrt/division
// differ from libm by a few ulps. F is a sum of up to 4 edge terms, each up to ~1/2, so float
// rounding leaves ~1e-7 absolute error however small F is (cancellation). Hence: relative 1e-4
// above F = 1e-2, absolute 1e-6 below. Still catches a wrong sign, constant or clipping branch
// (errors ≥ 1e-2 relative).
constexpr double kTolerance = 1e-4;
constexpr double kFloor = 1e-2;

struct Case {
  float x[4], n[4], v0[4], v1[4], v2[4];
};
static_assert(sizeof(Case) == 80);

void set(float* dst, glm::vec3 v) { dst[0] = v.x, dst[1] = v.y, dst[2] = v.z, dst[3] = 0.0f; }

}  // namespace

TEST(VlmFormFactorGpu, GlslMatchesCppOnRandomAndAwkwardCases) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  std::vector<Case> cases;
  auto add = [&](glm::vec3 x, glm::vec3 n, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    Case k;
    set(k.x, x), set(k.n, n), set(k.v0, a), set(k.v1, b), set(k.v2, c);
    cases.push_back(k);
  };
  const glm::vec3 up(0, 0, 1), o(0.0f);
  add(o, up, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1});            // facing down onto the receiver
  add(o, up, {-1, -1, 1}, {1, 1, 1}, {-1, 1, 1});            // facing away: 0
  add(o, up, {1, -1, -1}, {1, -1, 1}, {1, 1, 1});            // wall crossing the horizon
  add(o, up, {1, -1, -1}, {1, 1, 1}, {1, 1, -1});            // its other half
  add(o, up, {0.5f, 1, 0}, {0.5f, 0, 1}, {0.5f, -1, 0});     // standing on the plane
  add(o, up, o, {1, 0, 1}, {0, 1, 1});                       // vertex at the shading point
  add(o, up, {0, 0, 1}, {1, 0, 1}, {2, 0, 1});               // collinear
  add(o, up, {-1e-2f, -1e-2f, 1}, {-1e-2f, 1e-2f, 1}, {1e-2f, 1e-2f, 1});  // small
  add(o, up, {-1e3f, -1e3f, 1}, {-1e3f, 1e3f, 1}, {1e3f, 1e3f, 1});        // huge
  math::Pcg32 rng(21, 4);
  auto rnd = [&](float lo, float hi) { return rng.nextFloat3() * (hi - lo) + lo; };
  while (cases.size() < 1024) {
    glm::vec3 n = rnd(-1, 1);
    if (glm::dot(n, n) < 0.01f) continue;
    n = glm::normalize(n);
    const glm::vec3 x = rnd(0, 1);
    add(x, n, x + rnd(-2, 2), x + rnd(-2, 2), x + rnd(-2, 2));
  }
  const std::uint32_t count = std::uint32_t(cases.size());
  const std::vector<float> gpuF =
      testgpu::runComputeSelfTest<float>(ctx, "vlm/form_factor_selftest.comp.spv", std::span<const Case>(cases));
  ASSERT_EQ(gpuF.size(), count);

  auto v = [](const float* p) { return glm::vec3(p[0], p[1], p[2]); };
  double worst = 0.0;
  int lit = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const Case& k = cases[i];
    const float cpu = gi::vlm::formFactor<float>(v(k.x), v(k.n), v(k.v0), v(k.v1), v(k.v2));
    ASSERT_TRUE(std::isfinite(gpuF[i])) << "case " << i;
    const double err = std::abs(double(gpuF[i]) - cpu) / std::max<double>(cpu, kFloor);
    worst = std::max(worst, err);
    EXPECT_LT(err, kTolerance) << "case " << i << ": gpu " << gpuF[i] << " cpu " << cpu;
    if (cpu > 1e-3f) ++lit;
  }
  EXPECT_GT(gpuF[0], 0.1f);
  EXPECT_EQ(gpuF[1], 0.0f);
  EXPECT_EQ(gpuF[5], 0.0f);
  EXPECT_EQ(gpuF[6], 0.0f);
  EXPECT_GT(lit, 200);
  std::cout << "[vlm] GLSL vs C++ float: worst relative error " << worst << "\n";
}
