// SH projection: exact quadrature, Monte Carlo and cube maps, against band-limited functions.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/math/sh_project.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

// Exact quadrature of a degree <= 6 polynomial: rounding only, ~100 terms of O(1).
constexpr double kExactTol = 1e-12;
// Stratified jittered Monte Carlo with 256² samples of a smooth integrand of magnitude ~2: in 2D
// jittered sampling of a smooth function converges as N^-1 (Owen 1997); observed 2.4e-4 for the
// seed used below and at most 4.1e-4 over seeds 0..19, so 2e-3 leaves ~5× margin for any seed.
constexpr double kMonteCarloTol = 2e-3;
// Solid angles from the exact atan2 formula: a sum of 6·size² terms of rounding ~1e-16.
constexpr double kSolidAngleTol = 1e-11;
// Cube-map projection of a smooth band-limited function at 64² per face: texel-centre
// (midpoint) rule, error ~h²/24 · |f''| per unit solid angle with h = 2/64 and |f''| ~ 10 for
// these l <= 2 polynomials: ~4e-4; observed 4.4e-5.
constexpr double kCubeProjectionTol = 5e-4;

const double kPi = math::kPi;

}  // namespace

TEST(ShProject, QuadratureRoundTripIsExactForBandLimitedFunctions) {
  math::Pcg32 rng(10);
  for (int order = 1; order <= kMaxOrder; ++order) {
    const auto c = testutil::randomCoeffs(rng, coeffCount(order));
    const auto f = [&](const glm::dvec3& d) { return evalSum(c, d); };
    const auto p = projectQuadrature(f, order, order - 1);
    ASSERT_EQ(p.size(), c.size());
    for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(p[i], c[i], kExactTol) << "order " << order << " i " << i;
  }
}

TEST(ShProject, ProjectingToLowerOrderKeepsLeadingCoefficients) {
  // Orthogonality: projecting an order-4 function onto order 2 gives its first 4 coefficients.
  math::Pcg32 rng(11);
  const auto c = testutil::randomCoeffs(rng, 16);
  const auto p = projectQuadrature([&](const glm::dvec3& d) { return evalSum(c, d); }, 2, 3);
  ASSERT_EQ(p.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(p[i], c[i], kExactTol);
}

TEST(ShProject, MonteCarloRoundTripWithinStratifiedError) {
  math::Pcg32 rng(12);
  const auto c = testutil::randomCoeffs(rng, 9);
  const auto f = [&](const glm::dvec3& d) { return evalSum(c, d); };
  const auto p = projectMonteCarlo(f, 3, 256, 7);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(p[i], c[i], kMonteCarloTol) << i;
}

TEST(ShProject, MonteCarloIsDeterministicPerSeed) {
  const auto f = [](const glm::dvec3& d) { return std::exp(d.x) + d.y * d.z; };
  const auto a = projectMonteCarlo(f, 4, 16, 99);
  const auto b = projectMonteCarlo(f, 4, 16, 99);
  const auto c = projectMonteCarlo(f, 4, 16, 100);
  EXPECT_EQ(a, b);  // bit-identical: bakes must be reproducible
  EXPECT_NE(a, c);
}

TEST(ShProject, MonteCarloRgbEqualsPerChannel) {
  const auto f = [](const glm::dvec3& d) { return glm::dvec3(d.x, 2.0 * d.x * d.y, 1.0); };
  const auto rgb = projectMonteCarlo(f, 3, 16, 5);
  const auto g = projectMonteCarlo([](const glm::dvec3& d) { return 2.0 * d.x * d.y; }, 3, 16, 5);
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(rgb[i].y, g[i]);
}

TEST(ShProject, CubeTexelSolidAnglesSumToFourPi) {
  for (int size : {1, 2, 7, 32}) {
    double sum = 0.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) sum += 6.0 * cubeTexelSolidAngle(x, y, size);
    EXPECT_NEAR(sum, 4.0 * kPi, kSolidAngleTol) << "size " << size;
  }
  // A whole face is a sixth of the sphere; corner texels are smaller than centre texels.
  EXPECT_NEAR(cubeTexelSolidAngle(0, 0, 1), 4.0 * kPi / 6.0, kSolidAngleTol);
  EXPECT_LT(cubeTexelSolidAngle(0, 0, 8), cubeTexelSolidAngle(3, 3, 8));
  EXPECT_NEAR(cubeTexelSolidAngle(0, 0, 8), cubeTexelSolidAngle(7, 7, 8), kSolidAngleTol);
}

TEST(ShProject, CubeTexelDirectionsFollowVulkanFaceTable) {
  const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const glm::dvec3 d = cubeTexelDirection(f, 0, 0, 1);
    EXPECT_NEAR(glm::length(d - axes[f]), 0.0, kExactTol) << "face " << f;
  }
  // Top-left texel (x = 0, y = 0, so sc < 0 and tc < 0) of a 2×2 face:
  // +X: sc = -z, tc = -y → z > 0, y > 0.   +Y: sc = +x, tc = +z → x < 0, z < 0.
  // +Z: sc = +x, tc = -y → x < 0, y > 0.   -Z: sc = -x, tc = -y → x > 0, y > 0.
  const double h = 1.0 / std::sqrt(1.5);  // components of normalize(±0.5, ±0.5, ±1)
  EXPECT_NEAR(glm::length(cubeTexelDirection(0, 0, 0, 2) - glm::dvec3(1, 0.5, 0.5) * h), 0.0, kExactTol);
  EXPECT_NEAR(glm::length(cubeTexelDirection(2, 0, 0, 2) - glm::dvec3(-0.5, 1, -0.5) * h), 0.0, kExactTol);
  EXPECT_NEAR(glm::length(cubeTexelDirection(4, 0, 0, 2) - glm::dvec3(-0.5, 0.5, 1) * h), 0.0, kExactTol);
  EXPECT_NEAR(glm::length(cubeTexelDirection(5, 0, 0, 2) - glm::dvec3(0.5, 0.5, -1) * h), 0.0, kExactTol);
  EXPECT_THROW(cubeTexelDirection(6, 0, 0, 2), InternalError);
}

TEST(ShProject, ConstantCubeMapProjectsToBandZeroExactly) {
  const int size = 9;
  std::vector<glm::vec3> texels(6 * size * size, glm::vec3(2.0f, 0.5f, 0.0f));
  const auto c = projectCubeMap(texels, size, 4);
  // c_00 = L · ∫Y_00 = L · 4π/(2√π) = 2√π L; the cube is symmetric under x, y, z → -x, -y, -z
  // and axis swaps, which kills every other band exactly.
  EXPECT_NEAR(c[0].x, 2.0 * 2.0 * std::sqrt(kPi), kSolidAngleTol);
  EXPECT_NEAR(c[0].y, 0.5 * 2.0 * std::sqrt(kPi), kSolidAngleTol);
  for (int i = 1; i < 16; ++i) EXPECT_NEAR(glm::length(c[i]), 0.0, kSolidAngleTol) << i;
}

TEST(ShProject, CubeMapProjectionOfBandLimitedFunction) {
  math::Pcg32 rng(13);
  const auto c = testutil::randomCoeffs(rng, 9);
  const int size = 64;
  std::vector<glm::vec3> texels;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double v = evalSum(c, cubeTexelDirection(f, x, y, size));
        texels.push_back(glm::vec3(float(v), float(-v), 0.0f));
      }
  const auto p = projectCubeMap(texels, size, 3);
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(p[i].x, c[i], kCubeProjectionTol) << i;
    EXPECT_NEAR(p[i].y, -c[i], kCubeProjectionTol) << i;
  }
}

TEST(ShProject, CubeMapWithWrongTexelCountThrows) {
  std::vector<glm::vec3> texels(6 * 4 * 4 - 1);
  EXPECT_THROW(projectCubeMap(texels, 4, 3), InternalError);
  EXPECT_THROW(projectCubeMap(texels, 0, 3), InternalError);
  std::vector<glm::vec3> ok(6 * 4 * 4);
  EXPECT_THROW(projectCubeMap(ok, 4, 5), InternalError);
}
