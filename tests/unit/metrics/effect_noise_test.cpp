// ref::effectNoise and ref::noiseCorrectedError (engine/ref/effect_noise.hpp) on synthetic
// references with known Gaussian noise: the floor a perfect technique scores, and the error
// against the converged effect.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "engine/ref/effect_noise.hpp"

namespace bounce::ref {
namespace {

constexpr int kSize = 256;  // M = 256² × 3 = 196608 values
// Relative tolerance on the noise estimates: the sample rms of M Gaussian values has a relative
// standard deviation of 1/sqrt(2M) = 0.0016; 0.01 is 6 of those.
constexpr double kNoiseTolerance = 0.01;
// A perfect technique's corrected error e*² = max(0, e² − f²)/(1 − f²) compares two independent
// noise energies ||n||², ||d||² of M values each: e*² scatters by s = 2σₙ²/(sqrt(M)·rms(r*)²) (σₙ the
// full reference's noise per value); the bound allows kScatterSds of those.
constexpr double kScatterSds = 4.0;
constexpr double kValues = 3.0 * kSize * kSize;

// Standard normal values from raw mt19937 draws (Box–Muller): the standard fixes mt19937's output,
// not normal_distribution's, so the test sees the same numbers everywhere.
struct Gauss {
  std::mt19937 rng;
  explicit Gauss(std::uint32_t seed) : rng(seed) {}
  double uniform() { return (double(rng() >> 8) + 0.5) * (1.0 / 16777216.0); }
  double operator()() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform()); }
};

// The converged scene: a background and an object effect of rms ~0.0159 (a sine pattern).
struct Truth {
  ImageRGB with{kSize, kSize}, without{kSize, kSize};
  Truth() {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float bg = 0.3f + 0.2f * float(x) / kSize;
        const float fx = std::sin(0.05f * float(x)) * std::cos(0.07f * float(y));
        without.at(x, y) = glm::vec3(bg, 0.9f * bg, 0.8f * bg);
        with.at(x, y) = without.at(x, y) + 0.04f * glm::vec3(fx, 0.8f * fx, -0.5f * fx);
      }
  }
};

double rms(const ImageRGB& a, const ImageRGB& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) s += std::pow(double(a.pixels[i][c]) - double(b.pixels[i][c]), 2);
  return std::sqrt(s / (3.0 * double(a.pixels.size())));
}

// One half of a reference: truth + noise shared by with and without (the same sample indices
// trace the same paths where the objects do not matter; it cancels in the effect) + noise of
// standard deviation sigma on `with` only (the effect's own noise).
std::pair<ImageRGB, ImageRGB> noisyHalf(const Truth& t, double sigma, std::uint32_t seed) {
  Gauss g(seed);
  ImageRGB with = t.with, without = t.without;
  for (std::size_t i = 0; i < with.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float shared = float(0.05 * g());
      without.pixels[i][c] += shared;
      with.pixels[i][c] += shared + float(sigma * g());
    }
  return {with, without};
}

ImageRGB mean(const ImageRGB& a, const ImageRGB& b) {
  ImageRGB out = a;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
  return out;
}

TEST(EffectNoise, EstimatesKnownGaussianNoiseAndAPerfectTechniqueScoresTheFloor) {
  const Truth t;
  const double truthRms = rms(t.with, t.without);
  for (const double sigma : {0.005, 0.02, 0.06}) {  // floors ~0.22, ~0.67, ~0.94
    const auto [h1With, h1Without] = noisyHalf(t, sigma, 7);
    const auto [h2With, h2Without] = noisyHalf(t, sigma, 8);
    const ImageRGB fullWith = mean(h1With, h2With), fullWithout = mean(h1Without, h2Without);
    const EffectNoise n = effectNoise(fullWith, fullWithout, h1With, h1Without);
    // The full reference averages two halves: its effect's noise is sigma/sqrt(2) per value.
    const double noise = sigma / std::sqrt(2.0);
    EXPECT_NEAR(n.noiseRms, noise, kNoiseTolerance * noise) << sigma;
    const double floor = noise / std::sqrt(truthRms * truthRms + noise * noise);
    EXPECT_NEAR(n.floor, floor, kNoiseTolerance * floor) << sigma;
    EXPECT_FALSE(n.effectIsZero);
    EXPECT_EQ(n.pixelCount, std::size_t(kSize) * kSize);

    // A technique equal to the noiseless truth scores the floor against the noisy reference,
    // and about 0 once corrected.
    const double perfect = objectEffectError(t.with, t.without, fullWith, fullWithout).relativeError;
    EXPECT_NEAR(perfect, n.floor, 2.0 * kNoiseTolerance * n.floor) << sigma;
    const double scatter = 2.0 * noise * noise / (std::sqrt(kValues) * truthRms * truthRms);
    EXPECT_LT(noiseCorrectedError(perfect, n.floor), std::sqrt(kScatterSds * scatter)) << sigma;

    // Leaving the effect out scores 1 against the reference and 1 once corrected (the convention
    // "1 = effect missing" survives the correction).
    const double missing = objectEffectError(t.without, t.without, fullWith, fullWithout).relativeError;
    EXPECT_NEAR(missing, 1.0, 1e-9);
    EXPECT_NEAR(noiseCorrectedError(missing, n.floor), 1.0, 1e-9);

    // Half the effect: 0.5 against the converged effect, whatever the noise.
    ImageRGB halfEffect = t.with;
    for (std::size_t i = 0; i < halfEffect.pixels.size(); ++i)
      halfEffect.pixels[i] = 0.5f * (t.with.pixels[i] + t.without.pixels[i]);
    const double half = objectEffectError(halfEffect, t.without, fullWith, fullWithout).relativeError;
    // The raw number is inflated by the noise: e² = (0.25·||r*||² + ||n||²)/||r||² = 0.25 + 0.75·f².
    EXPECT_NEAR(half, std::sqrt(0.25 + 0.75 * n.floor * n.floor), kScatterSds * scatter) << sigma;
    // e*² = 0.25 ± scatter: e* = 0.5 ± scatter (d e* = d e*² / (2 · 0.5)).
    EXPECT_NEAR(noiseCorrectedError(half, n.floor), 0.5, kScatterSds * scatter) << sigma;
  }
}

TEST(EffectNoise, MaskSelectsThePixelsAndANoiselessReferenceHasFloorZero) {
  const Truth t;
  const auto [h1With, h1Without] = noisyHalf(t, 0.02, 11);
  const auto [h2With, h2Without] = noisyHalf(t, 0.02, 12);
  const ImageRGB fullWith = mean(h1With, h2With), fullWithout = mean(h1Without, h2Without);
  PixelMask left(kSize, kSize);
  left.setRect(0, 0, kSize / 2, kSize);
  const EffectNoise n = effectNoise(fullWith, fullWithout, h1With, h1Without, &left);
  EXPECT_EQ(n.pixelCount, left.count());
  EXPECT_NEAR(n.noiseRms, 0.02 / std::sqrt(2.0), 2.0 * kNoiseTolerance * 0.02 / std::sqrt(2.0));
  // Exact references (the bounces-0 one): the halves are the full image, floor 0, e* = e.
  const EffectNoise exact = effectNoise(t.with, t.without, t.with, t.without);
  EXPECT_EQ(exact.noiseRms, 0.0);
  EXPECT_EQ(exact.floor, 0.0);
  EXPECT_DOUBLE_EQ(noiseCorrectedError(0.42, 0.0), 0.42);
  // No effect at all: no ratio.
  const EffectNoise none = effectNoise(t.without, t.without, t.without, t.without);
  EXPECT_TRUE(none.effectIsZero);
  EXPECT_TRUE(std::isnan(none.floor));
}

TEST(EffectNoise, CorrectedErrorClosedForms) {
  EXPECT_DOUBLE_EQ(noiseCorrectedError(0.6, 0.6), 0.0);  // scoring the floor = perfect
  EXPECT_DOUBLE_EQ(noiseCorrectedError(0.3, 0.6), 0.0);  // below the floor: clamped, not imaginary
  EXPECT_DOUBLE_EQ(noiseCorrectedError(1.0, 0.7), 1.0);
  // e = 0.8, f = 0.6: sqrt((0.64 − 0.36) / 0.64) = sqrt(0.4375)
  EXPECT_NEAR(noiseCorrectedError(0.8, 0.6), std::sqrt(0.4375), 1e-15);
  EXPECT_TRUE(std::isnan(noiseCorrectedError(0.9, 1.0)));  // all noise: nothing to correct against
  EXPECT_TRUE(std::isnan(noiseCorrectedError(std::nan(""), 0.5)));
  EXPECT_TRUE(std::isnan(noiseCorrectedError(0.5, std::nan(""))));
}

}  // namespace
}  // namespace bounce::ref
