// sh.glsl on the GPU agrees with engine/math on the same inputs (DESIGN.md: "one SH library,
// mirrored by one sh.glsl, tested against each other"). Runs shaders/common/sh_selftest.comp.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "tests/support/compute_selftest.hpp"

using namespace bounce;

namespace {

// float32 evaluation on the GPU vs double on the CPU: basis values are O(1) polynomials of degree
// ≤ 3, so a few float ulps (~1e-6) per term; sums of 16 terms with coefficients up to 10 give
// absolute errors ~1e-5. 1e-4 (relative to max(1, |value|)) leaves margin for lavapipe's
// fused multiply-adds while still catching a wrong constant or sign (errors ≥ 1e-2).
constexpr double kTolerance = 1e-4;
constexpr std::uint32_t kDirections = 256;

struct Input {
  float dir[4];
  float coeff[16][4];
};
struct Output {
  float basis[16];
  float evalSum[4];
  float irradiance4[4];
  float irradiance9[4];
  float irradiance16[4];
};
static_assert(sizeof(Input) == 272 && sizeof(Output) == 128);

double near(double gpu, double cpu) { return std::abs(gpu - cpu) / std::max(1.0, std::abs(cpu)); }

}  // namespace

TEST(ShGpu, GlslMatchesLibraryForBasisReconstructionAndIrradiance) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  math::Pcg32 rng(7, 11);
  std::vector<Input> inputs(kDirections);
  std::vector<glm::dvec3> dirs(kDirections);
  std::vector<std::vector<glm::dvec3>> coeffs(kDirections, std::vector<glm::dvec3>(16));
  for (std::uint32_t i = 0; i < kDirections; ++i) {
    // Include the poles and axes, where sign slips hide most easily.
    glm::dvec3 d = i < 6 ? glm::dvec3(i / 2 == 0, i / 2 == 1, i / 2 == 2) * (i % 2 ? -1.0 : 1.0)
                         : math::uniformSphere(rng.next2D());
    d = glm::normalize(d);
    dirs[i] = d;
    inputs[i].dir[0] = float(d.x), inputs[i].dir[1] = float(d.y), inputs[i].dir[2] = float(d.z);
    for (int k = 0; k < 16; ++k) {
      const glm::dvec3 c = glm::dvec3(rng.nextFloat3()) * 20.0 - 10.0;
      coeffs[i][k] = glm::dvec3(glm::vec3(c));  // what the GPU sees, exactly
      for (int ch = 0; ch < 3; ++ch) inputs[i].coeff[k][ch] = float(c[ch]);
    }
  }
  const std::vector<Output> results =
      testgpu::runComputeSelfTest<Output>(ctx, "common/sh_selftest.comp.spv", std::span<const Input>(inputs));
  ASSERT_EQ(results.size(), kDirections);

  double worst = 0.0;
  for (std::uint32_t i = 0; i < kDirections; ++i) {
    const auto y = sh::evalBasis<double>(4, dirs[i]);
    for (int k = 0; k < 16; ++k) worst = std::max(worst, near(results[i].basis[k], y[k]));
    const auto sum = sh::evalSum<glm::dvec3, double>(coeffs[i], dirs[i]);
    const std::vector<glm::dvec3> c4(coeffs[i].begin(), coeffs[i].begin() + 4), c9(coeffs[i].begin(), coeffs[i].begin() + 9);
    const auto e4 = sh::evalIrradiance<glm::dvec3, double>(c4, dirs[i]);
    const auto e9 = sh::evalIrradiance<glm::dvec3, double>(c9, dirs[i]);
    const auto e16 = sh::evalIrradiance<glm::dvec3, double>(coeffs[i], dirs[i]);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_LT(near(results[i].evalSum[ch], sum[ch]), kTolerance) << "direction " << i;
      EXPECT_LT(near(results[i].irradiance4[ch], e4[ch]), kTolerance) << "direction " << i;
      EXPECT_LT(near(results[i].irradiance9[ch], e9[ch]), kTolerance) << "direction " << i;
      EXPECT_LT(near(results[i].irradiance16[ch], e16[ch]), kTolerance) << "direction " << i;
    }
  }
  EXPECT_LT(worst, kTolerance);
}
