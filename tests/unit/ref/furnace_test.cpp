// White furnace (the inside of a closed cube, albedo ρ, emission Le on every wall): the radiance
// of every pixel is the geometric series Le·Σ_{k≤N} ρ^k = Le·(1 − ρ^{N+1})/(1 − ρ), → Le/(1 − ρ).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/unit/ref/test_scenes.hpp"

namespace bounce::ref {
namespace {

using test::pixel;

SceneDesc furnace(glm::vec3 albedo, float le) {
  SceneDesc s;
  s.materials.push_back({albedo, -1, glm::vec3(le), -1});
  s.meshes = test::insideOfCube(1.0f, 0);
  // Off-centre and tilted, so rays meet walls, edges and corners at many angles.
  s.camera = test::lookAt({0.2f, -0.1f, 0.3f}, {1.0f, 0.5f, -1.0f}, {0, 1, 0}, 90.0f);
  return s;
}

// Below the Russian-roulette depth every path has the same value (every hit emits Le and every
// bounce multiplies by ρ), so the image is exact up to float rounding of ρ and the sums.
constexpr double kExactTolerance = 1e-5;

TEST(Furnace, BounceLimitedIsTheExactGeometricSeries) {
  const glm::dvec3 rho(0.2, 0.5, 0.8);
  const double le = 1.5;
  SceneBvh bvh(furnace(glm::vec3(rho), float(le)));
  for (std::uint32_t n = 0; n <= kRouletteAfter; ++n) {
    const gpu::FloatImage img = trace(bvh, test::settings(16, 2, n));
    const glm::dvec3 expected = le * (1.0 - glm::pow(rho, glm::dvec3(n + 1.0))) / (1.0 - rho);
    for (std::uint32_t y = 0; y < 16; ++y)
      for (std::uint32_t x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(pixel(img, x, y)[c], expected[c], kExactTolerance * expected[c])
              << "bounces " << n << " pixel " << x << "," << y << " channel " << c;
  }
}

// ρ = ½, unlimited bounces: depths 0..3 are exact (1 + ½ + ¼ + ⅛ = 1.875 Le); the tail ⅛·Le is
// estimated by Russian roulette. A path survives into the tail with p = ρ⁴ = 1/16 and then
// carries weight 1 per further hit, continuing with p = ½: the tail sample X is 0 with
// probability 15/16, else G ~ Geometric(½) on {1, 2, …} (E G = 2, E G² = 6). So E X = ⅛ and
// Var X = 6/16 − 1/64 ≈ 0.36: σ ≈ 0.60 Le per sample.
constexpr double kSigmaPerSample = 0.60;
constexpr double kSigmas = 5.5;  // per-pixel bound: 1024 pixels, P(|z| > 5.5) ≈ 4e-8 each

TEST(Furnace, UnlimitedBouncesConvergeToLeOverOneMinusRho) {
  const double rho = 0.5, le = 1.0, expected = le / (1.0 - rho);
  SceneBvh bvh(furnace(glm::vec3(float(rho)), float(le)));
  const std::uint32_t size = 32, spp = 256;
  const gpu::FloatImage img = trace(bvh, test::settings(size, spp, kUnlimitedBounces));
  const double sigmaPixel = kSigmaPerSample * le / std::sqrt(double(spp));
  double mean = 0.0;
  for (std::uint32_t y = 0; y < size; ++y)
    for (std::uint32_t x = 0; x < size; ++x) {
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(pixel(img, x, y)[c], expected, kSigmas * sigmaPixel) << "pixel " << x << "," << y;
      mean += pixel(img, x, y).x;
    }
  mean /= double(size) * size;
  EXPECT_NEAR(mean, expected, kSigmas * sigmaPixel / size);  // the mean of 1024 independent pixels
}

// Monte Carlo error falls like 1/√spp: 4× the samples halves the RMSE. With 4096 pixels the
// RMSE itself is known to a few percent (the furnace's per-sample error is heavy-tailed:
// kurtosis ≈ 7 at 16 spp gives a 2 % relative spread of the RMSE), so [0.4, 0.6] is > 5σ wide.
constexpr double kRatioLow = 0.4, kRatioHigh = 0.6;

TEST(Furnace, ErrorFallsLikeInverseSqrtOfSamples) {
  const double rho = 0.5, le = 1.0, expected = le / (1.0 - rho);
  SceneBvh bvh(furnace(glm::vec3(float(rho)), float(le)));
  auto rmse = [&](std::uint32_t spp) {
    const gpu::FloatImage img = trace(bvh, test::settings(64, spp, kUnlimitedBounces));
    double sum = 0.0;
    for (float v : img.rgb) sum += (v - expected) * (v - expected);
    return std::sqrt(sum / double(img.rgb.size()));
  };
  const double low = rmse(16), high = rmse(64);
  std::printf("furnace RMSE: 16 spp %.5f, 64 spp %.5f, ratio %.3f\n", low, high, high / low);
  EXPECT_GT(low, 0.0);
  EXPECT_GE(high / low, kRatioLow) << "rmse 16 spp " << low << ", 64 spp " << high;
  EXPECT_LE(high / low, kRatioHigh) << "rmse 16 spp " << low << ", 64 spp " << high;
}

}  // namespace
}  // namespace bounce::ref
