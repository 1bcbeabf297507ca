// The reference with bounces 0 is the rasteriser's direct lighting with exact visibility: on the
// Cornell level the two agree wherever shadow-map filtering and bias do not decide the answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/core/file.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/ref/reference.hpp"
#include "game/capture_run.hpp"

namespace bounce::ref {
namespace {

constexpr std::uint32_t kSize = 64;
// A pixel agrees when within 2 % (+ a floor for black): float maths on both sides, 8-bit texture
// filtering on the GPU, and the rasteriser's depth-reconstructed position differ by far less.
constexpr double kPixelRelTolerance = 0.02;
constexpr double kPixelAbsTolerance = 1e-3;
// Pixels allowed to disagree: shadow-map edges (PCF penumbra vs a hard traced shadow) and
// normal-offset bias in contact corners. Measured: 0.4 % of this 64×64 view (16 pixels).
constexpr double kMaxDisagreeingFraction = 0.02;

TEST(RasterMatch, DirectOnlyReferenceEqualsTheRasterisersDirectLighting) {
  const auto out = std::filesystem::path(BOUNCE_TEST_OUT) / "ref" / "raster-match";
  const auto level = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  const auto script = out / "frame0.json";
  writeFileAtomic(script, "{\"bounce_capture\": 1, \"level\": \"" + level.string() +
                              "\", \"resolution\": [64, 64], \"dt\": 0.0166667, \"frames\": 1, \"capture\": [0], "
                              "\"effects\": [\"direct\", \"shadows\"]}");  // the rasteriser's direct light only
  const game::CaptureResult raster = game::runCaptureScript(script, out / "capture");
  ASSERT_EQ(raster.frames.size(), 1u);
  const gpu::FloatImage gpuImage = gpu::readPfm(raster.frames[0].pfm);

  ReferenceRequest r;
  r.input = script;
  r.spp = 1;  // bounces 0 through pixel centres uses no random numbers: one sample is exact
  r.bounces = 0;
  r.cacheDir = out / "reference";
  r.cookCache = out / "cooked";
  r.progress = false;
  const gpu::FloatImage refImage = renderReference(r).image;
  ASSERT_EQ(refImage.rgb.size(), gpuImage.rgb.size());

  std::size_t disagree = 0;
  double refSum = 0.0, gpuSum = 0.0;
  for (std::size_t i = 0; i < kSize * kSize; ++i) {
    bool ok = true;
    for (int c = 0; c < 3; ++c) {
      const double a = refImage.rgb[3 * i + c], b = gpuImage.rgb[3 * i + c];
      ok &= std::abs(a - b) <= kPixelRelTolerance * std::max(a, b) + kPixelAbsTolerance;
      refSum += a;
      gpuSum += b;
    }
    disagree += !ok;
  }
  const double fraction = double(disagree) / (kSize * kSize);
  std::printf("reference vs rasteriser (bounces 0): %.1f %% of pixels differ; mean %.5f vs %.5f\n", 100 * fraction,
              refSum / (3 * kSize * kSize), gpuSum / (3 * kSize * kSize));
  EXPECT_LE(fraction, kMaxDisagreeingFraction);
  EXPECT_GT(refSum, 0.0);
}

}  // namespace
}  // namespace bounce::ref
