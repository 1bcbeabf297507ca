// Error metrics on hand-made images (exact values), invariants (identity, scaling, masks) and the
// object-effect metric with a known answer.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/ref/metrics.hpp"
#include "test_util.hpp"

namespace bounce::ref {
namespace {

// Scaling float pixels by a non-power-of-two rounds each value (relative 2^-24 ≈ 6e-8); over
// many pixels the ratio of two such sums moves by about that much. 1e-6 leaves 16× headroom.
constexpr double kScaleRoundingTol = 1e-6;

// r = [(1,1,1), (3,3,3)], a = [(2,1,1), (3,3,1)]: differences (1,0,0) and (0,0,−2).
struct HandMade {
  ImageRGB a{2, 1}, r{2, 1};
  HandMade() {
    r.pixels = {{1, 1, 1}, {3, 3, 3}};
    a.pixels = {{2, 1, 1}, {3, 3, 1}};
  }
};

TEST(Metrics, ExactValuesOnHandMadeImages) {
  const HandMade h;
  const ErrorStats s = computeErrorStats(h.a, h.r);
  // N = 6 channel values, Σd² = 1 + 4 = 5, Σ|d| = 3, mean(r) = 12/6 = 2.
  EXPECT_EQ(s.pixelCount, 2u);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(5.0 / 6.0));
  EXPECT_DOUBLE_EQ(s.relativeRmse, std::sqrt(5.0 / 6.0) / 2.0);
  EXPECT_TRUE(s.relativeDefined);
  EXPECT_DOUBLE_EQ(s.mae, 0.5);
  EXPECT_DOUBLE_EQ(s.maxAbs, 2.0);
  EXPECT_DOUBLE_EQ(s.referenceMean, 2.0);
  EXPECT_DOUBLE_EQ(s.referenceMax, 3.0);
  // Per-pixel form: (1/(1+ε) + 4/(9+ε)) / 6 under the root.
  const double eps = kDefaultRelativeEpsilon;
  EXPECT_DOUBLE_EQ(s.perPixelRelativeRmse, std::sqrt((1.0 / (1.0 + eps) + 4.0 / (9.0 + eps)) / 6.0));
  EXPECT_DOUBLE_EQ(perPixelRelativeRmse(h.a, h.r, nullptr, 0.0), std::sqrt((1.0 + 4.0 / 9.0) / 6.0));
  // PSNR with peak max(r) = 3: 10·log10(9 / (5/6)).
  EXPECT_DOUBLE_EQ(psnr(h.a, h.r), 10.0 * std::log10(9.0 / (5.0 / 6.0)));
  EXPECT_DOUBLE_EQ(psnr(h.a, h.r, nullptr, 1.0), 10.0 * std::log10(1.0 / (5.0 / 6.0)));
  // The single-number functions agree with the struct.
  EXPECT_EQ(rmse(h.a, h.r), s.rmse);
  EXPECT_EQ(relativeRmse(h.a, h.r), s.relativeRmse);
  EXPECT_EQ(meanAbsoluteError(h.a, h.r), s.mae);
  EXPECT_EQ(maxAbsoluteError(h.a, h.r), s.maxAbs);
}

TEST(Metrics, MaskSelectsPixels) {
  const HandMade h;
  PixelMask m(2, 1);
  m.set(1, 0);
  EXPECT_EQ(m.count(), 1u);
  const ErrorStats s = computeErrorStats(h.a, h.r, &m);
  // Only pixel 1: d = (0,0,−2), r = (3,3,3).
  EXPECT_EQ(s.pixelCount, 1u);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(4.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.relativeRmse, std::sqrt(4.0 / 3.0) / 3.0);
  EXPECT_DOUBLE_EQ(s.mae, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.maxAbs, 2.0);

  PixelMask none(2, 1);
  const ErrorStats z = computeErrorStats(h.a, h.r, &none);
  EXPECT_EQ(z.pixelCount, 0u);
  EXPECT_EQ(z.rmse, 0.0);
  EXPECT_FALSE(z.relativeDefined);

  PixelMask rect(4, 4);
  rect.setRect(-1, 2, 3, 10);  // clipped to [0,3)×[2,4)
  EXPECT_EQ(rect.count(), 6u);
  EXPECT_TRUE(rect.test(2, 3));
  EXPECT_FALSE(rect.test(3, 3));
  EXPECT_THROW(computeErrorStats(h.a, h.r, &rect), InternalError);
}

TEST(Metrics, IdenticalImagesHaveZeroError) {
  const ImageRGB img = test::randomImage(16, 9, 5, 0.0f, 10.0f);
  const ErrorStats s = computeErrorStats(img, img);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.relativeRmse, 0.0);
  EXPECT_EQ(s.perPixelRelativeRmse, 0.0);
  EXPECT_EQ(s.mae, 0.0);
  EXPECT_EQ(s.maxAbs, 0.0);
  EXPECT_EQ(psnr(img, img), std::numeric_limits<double>::infinity());
}

TEST(Metrics, RelativeRmseIsScaleInvariant) {
  const ImageRGB a = test::randomImage(32, 24, 11, 0.0f, 2.0f);
  const ImageRGB r = test::randomImage(32, 24, 12, 0.0f, 2.0f);
  const ErrorStats base = computeErrorStats(a, r);
  for (float s : {1.0f / 1024.0f, 0.37f, 7.5f, 4096.0f}) {
    const ImageRGB as = scaled(a, s), rs = scaled(r, s);
    const ErrorStats t = computeErrorStats(as, rs);
    EXPECT_NEAR(t.relativeRmse / base.relativeRmse, 1.0, kScaleRoundingTol) << "s=" << s;
    // Absolute errors scale with s.
    EXPECT_NEAR(t.rmse / (base.rmse * s), 1.0, kScaleRoundingTol) << "s=" << s;
    EXPECT_NEAR(t.mae / (base.mae * s), 1.0, kScaleRoundingTol) << "s=" << s;
    // The per-pixel form is invariant only when ε scales by s² with the images.
    const double eps = kDefaultRelativeEpsilon;
    EXPECT_NEAR(perPixelRelativeRmse(as, rs, nullptr, eps * s * s) / perPixelRelativeRmse(a, r, nullptr, eps), 1.0,
                kScaleRoundingTol)
        << "s=" << s;
  }
  // Powers of two scale floats exactly, so the result is bit-identical.
  EXPECT_EQ(relativeRmse(scaled(a, 8.0f), scaled(r, 8.0f)), base.relativeRmse);
}

TEST(Metrics, BlackReferenceConventions) {
  const ImageRGB black(2, 2);
  ImageRGB img(2, 2);
  img.pixels[3] = {1, 0, 0};
  const ErrorStats s = computeErrorStats(img, black);
  EXPECT_FALSE(s.relativeDefined);
  EXPECT_EQ(s.relativeRmse, std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(1.0 / 12.0));
  EXPECT_EQ(relativeRmse(black, black), 0.0);
  EXPECT_EQ(psnr(img, black), -std::numeric_limits<double>::infinity());
}

TEST(Metrics, SizeMismatchIsInternalError) {
  EXPECT_THROW(computeErrorStats(ImageRGB(2, 2), ImageRGB(2, 3)), InternalError);
  EXPECT_THROW(objectEffectError(ImageRGB(2, 2), ImageRGB(2, 2), ImageRGB(2, 2), ImageRGB(3, 2)), InternalError);
}

// Scene with a known object effect. Values are multiples of 1/8 so every sum is exact.
struct EffectScene {
  static constexpr int kW = 6, kH = 4;
  ImageRGB background{kW, kH}, effect{kW, kH}, techBias{kW, kH};
  EffectScene() {
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        background.at(x, y) = glm::vec3(1.0f + x / 8.0f, 0.5f + y / 8.0f, 0.75f);
        // The object darkens a 2x2 patch (shadow-like) and adds bounce light to one column.
        if (x >= 1 && x < 3 && y >= 1 && y < 3) effect.at(x, y) = glm::vec3(-0.25f);
        if (x == 5) effect.at(x, y) = glm::vec3(0.125f, 0.0f, 0.0f);
        // The technique's error unrelated to the object (it must cancel out).
        techBias.at(x, y) = glm::vec3(0.125f * float((x + y) % 3));
      }
  }
  ImageRGB add(const ImageRGB& a, const ImageRGB& b, float sb = 1.0f) const {
    ImageRGB o = a;
    for (std::size_t i = 0; i < o.pixels.size(); ++i) o.pixels[i] += sb * b.pixels[i];
    return o;
  }
};

TEST(ObjectEffect, HalfTheEffectGivesHalfError) {
  const EffectScene sc;
  const ImageRGB refWithout = sc.background, refWith = sc.add(sc.background, sc.effect);
  const ImageRGB techWithout = sc.add(sc.background, sc.techBias);
  const ImageRGB techWith = sc.add(techWithout, sc.effect, 0.5f);
  const ObjectEffectError e = objectEffectError(techWith, techWithout, refWith, refWithout);
  // e_r = E, e_t = E/2, so e_t − e_r = −E/2: relative error exactly 0.5, energy ratio 0.5.
  // Σ E² = 4 pixels·3·0.0625 + 4 pixels·0.015625 = 0.8125 over N = 72 channel values.
  EXPECT_EQ(e.pixelCount, 24u);
  EXPECT_DOUBLE_EQ(e.referenceRms, std::sqrt(0.8125 / 72.0));
  EXPECT_DOUBLE_EQ(e.techniqueRms, 0.5 * std::sqrt(0.8125 / 72.0));
  EXPECT_DOUBLE_EQ(e.effectRmse, 0.5 * std::sqrt(0.8125 / 72.0));
  EXPECT_DOUBLE_EQ(e.relativeError, 0.5);
  EXPECT_DOUBLE_EQ(e.energyRatio, 0.5);
  EXPECT_FALSE(e.referenceEffectIsZero);
}

TEST(ObjectEffect, PerfectAndOmittedEffect) {
  const EffectScene sc;
  const ImageRGB refWithout = sc.background, refWith = sc.add(sc.background, sc.effect);
  const ImageRGB techWithout = sc.add(sc.background, sc.techBias);
  // Reproducing the effect exactly: zero error despite the technique's unrelated bias.
  const ObjectEffectError perfect =
      objectEffectError(sc.add(techWithout, sc.effect), techWithout, refWith, refWithout);
  EXPECT_EQ(perfect.relativeError, 0.0);
  EXPECT_DOUBLE_EQ(perfect.energyRatio, 1.0);
  // Leaving it out: relative error 1 ("as wrong as omitting it"), energy ratio 0.
  const ObjectEffectError omitted = objectEffectError(techWithout, techWithout, refWith, refWithout);
  EXPECT_DOUBLE_EQ(omitted.relativeError, 1.0);
  EXPECT_EQ(omitted.energyRatio, 0.0);
  // A mask around the darkened patch only: the bounce column no longer counts.
  PixelMask m(EffectScene::kW, EffectScene::kH);
  m.setRect(0, 0, 4, 4);
  const ObjectEffectError masked = objectEffectError(techWithout, techWithout, refWith, refWithout, &m);
  EXPECT_EQ(masked.pixelCount, 16u);
  EXPECT_DOUBLE_EQ(masked.referenceRms, std::sqrt(12 * 0.0625 / 48.0));
  EXPECT_DOUBLE_EQ(masked.relativeError, 1.0);
}

TEST(ObjectEffect, ZeroReferenceEffectIsFlaggedNotDivided) {
  const EffectScene sc;
  const ImageRGB ref = sc.background;
  ImageRGB techWith = sc.background;
  techWith.at(2, 2) += glm::vec3(0.25f, 0.0f, 0.0f);  // the technique invents an effect
  const ObjectEffectError e = objectEffectError(techWith, sc.background, ref, ref);
  EXPECT_TRUE(e.referenceEffectIsZero);
  EXPECT_EQ(e.referenceRms, 0.0);
  // relativeError holds the absolute RMSE: sqrt(0.0625 / 72).
  EXPECT_DOUBLE_EQ(e.effectRmse, std::sqrt(0.0625 / 72.0));
  EXPECT_EQ(e.relativeError, e.effectRmse);
  EXPECT_TRUE(std::isfinite(e.relativeError));
  EXPECT_EQ(e.energyRatio, 0.0);
  // An empty selection is also "no reference effect", with zero error.
  const PixelMask none(EffectScene::kW, EffectScene::kH);
  const ObjectEffectError z = objectEffectError(techWith, sc.background, ref, ref, &none);
  EXPECT_TRUE(z.referenceEffectIsZero);
  EXPECT_EQ(z.pixelCount, 0u);
  EXPECT_EQ(z.relativeError, 0.0);
}

}  // namespace
}  // namespace bounce::ref
